"""Children of a benchmark, started, signalled and reaped by tools/lib/process (liblcm_control_process.so, the way
launch and the tests run a child), with their output read line by line."""
import ctypes
import os
import shutil
import signal
import threading
import time

PROCESS_TARGET = "lcm_control_process"  # the library Proc runs children with

_process = None  # liblcm_control_process.so: tools/lib/process, the way launch and the tests run a child


class _Usage:
    """What a reaped child used: ru_utime, ru_stime (s) and ru_maxrss (kB), as os.wait4's rusage names them."""

    def __init__(self, user_s, system_s, maxrss_kb):
        self.ru_utime, self.ru_stime, self.ru_maxrss = user_s, system_s, maxrss_kb


def use_build_dir(build_dir):
    """Loads the process library of the build in build_dir (built with the benchmarks: PROCESS_TARGET)."""
    global _process
    path = os.path.join(os.path.abspath(build_dir), "lib", "liblcm_control_process.so")
    if not os.path.exists(path):
        raise RuntimeError(f"{path} is missing: build the target {PROCESS_TARGET} (bench/run builds it without "
                           "--no-build)")
    lib = ctypes.CDLL(path, use_errno=True)
    lib.lcm_control_start_process.argtypes = [ctypes.POINTER(ctypes.c_char_p), ctypes.c_int,
                                              ctypes.POINTER(ctypes.c_int), ctypes.c_int, ctypes.c_int]
    lib.lcm_control_start_process.restype = ctypes.c_int
    lib.lcm_control_signal_process.argtypes = [ctypes.c_int, ctypes.c_int]
    lib.lcm_control_signal_process.restype = None
    lib.lcm_control_reap_process.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.POINTER(ctypes.c_int),
                                             ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
                                             ctypes.POINTER(ctypes.c_long)]
    lib.lcm_control_reap_process.restype = ctypes.c_int
    _process = lib


def pin_threads(pid, cpus):
    """Moves every thread of a running process (LCM's receive thread too) to `cpus`."""
    for tid in os.listdir(f"/proc/{pid}/task"):
        try:
            os.sched_setaffinity(int(tid), cpus)
        except (ProcessLookupError, FileNotFoundError):
            pass


class Proc:
    """A child process, started (pinned to `cpus` if given; SIGTERM when bench/run ends, however it ends), signalled
    and reaped by tools/lib/process, with its output read line by line (each line timestamped on arrival)."""
    live = []

    def __init__(self, argv, name=None, cpus=None):
        if _process is None:
            raise RuntimeError("bench: use_build_dir() first")
        self.name = name or os.path.basename(argv[0])
        self.argv = argv
        self.lines = []  # (monotonic time, line)
        self.cond = threading.Condition()
        self.rusage = None
        self.returncode = None
        self.exit_time = None
        path = argv[0] if "/" in argv[0] else shutil.which(argv[0])
        if not path:
            raise RuntimeError(f"{self.name}: {argv[0]} is not on PATH")
        c_argv = (ctypes.c_char_p * (len(argv) + 1))(*[os.fsencode(a) for a in [path] + list(argv[1:])], None)
        c_cpus = (ctypes.c_int * len(cpus))(*sorted(cpus)) if cpus else None
        r, w = os.pipe()  # both close on exec: the child gets w as its stdout and stderr only
        self.pid = _process.lcm_control_start_process(c_argv, w, c_cpus, len(cpus) if cpus else 0, 0)
        os.close(w)
        if self.pid < 0:
            os.close(r)
            raise RuntimeError(f"{self.name}: cannot start {path}: {os.strerror(ctypes.get_errno())}")
        self.stdout = os.fdopen(r, "r", errors="replace")
        Proc.live.append(self)
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.stdout:
            with self.cond:
                self.lines.append((time.monotonic(), line.rstrip("\n")))
                self.cond.notify_all()
        with self.cond:
            self.cond.notify_all()

    def output(self):
        with self.cond:
            return "\n".join(l for _, l in self.lines)

    def wait_for(self, text, timeout):
        """Time the first line containing text arrived; raises if it does not within timeout."""
        end = time.monotonic() + timeout
        with self.cond:
            while True:
                for t, l in self.lines:
                    if text in l:
                        return t
                left = end - time.monotonic()
                if left <= 0 or (not self.running() and not self.reader.is_alive()):
                    raise RuntimeError(f"{self.name}: no '{text}' within {timeout} s; output:\n{self.output()[-3000:]}")
                self.cond.wait(min(left, 0.05))

    def _reap(self, block):
        """The exit code once reaped (its usage kept in rusage), None while it runs."""
        if self.returncode is not None:
            return self.returncode
        code, user, system, rss = ctypes.c_int(), ctypes.c_double(), ctypes.c_double(), ctypes.c_long()
        got = _process.lcm_control_reap_process(self.pid, 1 if block else 0, ctypes.byref(code), ctypes.byref(user),
                                                ctypes.byref(system), ctypes.byref(rss))
        if got == 0:
            return None
        self.exit_time = time.monotonic()
        self.returncode = code.value if got == 1 else -1  # -1: not our child any more (reaped elsewhere)
        if got == 1:
            self.rusage = _Usage(user.value, system.value, rss.value)
        self.reader.join(2)
        if self in Proc.live:
            Proc.live.remove(self)
        return self.returncode

    def running(self):
        return self._reap(False) is None

    def wait(self, timeout=None):
        """Waits for the exit; returns the exit code (128 + signal if a signal ended it), None on timeout."""
        if timeout is None:
            return self._reap(True)
        end = time.monotonic() + timeout
        while True:
            rc = self._reap(False)
            if rc is not None or time.monotonic() > end:
                return rc
            time.sleep(0.002)

    def vm_hwm_kb(self):
        """Peak resident set size so far (VmHWM), in kB."""
        with open(f"/proc/{self.pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
        return None

    def stop(self, grace=5.0, sig=signal.SIGINT):
        if self.returncode is not None:
            return self.returncode
        _process.lcm_control_signal_process(self.pid, sig)
        rc = self.wait(grace)
        if rc is None:
            _process.lcm_control_signal_process(self.pid, signal.SIGKILL)
            rc = self.wait(5)
        return rc


def stop_all():
    for p in list(Proc.live):
        p.stop(grace=3)


def run(argv, timeout, name=None):
    """Runs to completion; returns stdout+stderr, raises on failure."""
    p = Proc(argv, name)
    rc = p.wait(timeout)
    if rc is None:
        p.stop(1, signal.SIGKILL)
        raise RuntimeError(f"{p.name}: still running after {timeout} s; output:\n{p.output()[-3000:]}")
    if rc != 0:
        raise RuntimeError(f"{p.name} exited with {rc}: {' '.join(argv)}\n{p.output()[-3000:]}")
    return p.output()


def result_line(proc, prefix):
    """The fields of the last line `proc` printed that starts with `prefix` (bench_realtime's result lines)."""
    lines = [l for l in proc.output().splitlines() if l.startswith(prefix + " ")]
    if not lines:
        raise RuntimeError(f"{proc.name} printed no '{prefix}' line:\n{proc.output()[-3000:]}")
    return lines[-1].split()


def load_and_start(cmctl, url, controllers):
    """Loads and starts `controllers` on the controller manager at `url`, as spawner does."""
    for op in ("load", "start"):
        run([cmctl, "--lcm-url", url, "--timeout", "10", op] + controllers, 30, f"cmctl {op}")


def cpu_seconds(pid):
    """CPU time (user + system) a process has used so far, from /proc/PID/stat."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
