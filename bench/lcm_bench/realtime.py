"""4. Real-time pacing: a minute at 1 kHz with a listener taking every state, against a bare clock_nanosleep loop
and its datagram in the same minute (as shipped, and at SCHED_FIFO as launch --rt-priority runs it); 4b. the
hardware loop on its own URL, each process's own period error against the bare loop's."""
import os
import subprocess

from .ports import lcm_url
from .processes import Proc, load_and_start, result_line

SPIN_US = 150
RT_PRIORITY = 80


def run(b, fifo=False):
    """A minute of real time with a listener taking every state as a controller would (row 4): as shipped, on the
    controller manager the lockstep part used; or (fifo, row 4c) as launch --rt-priority runs the two loops, with
    a controller manager of its own and the listener and both floors at the same SCHED_FIFO priority."""
    b.sample_load()
    name = "turret_bot"
    urdf, config, ctrl = b.models[name]
    duration = 1.0 if b.smoke else 60.0
    flags = ["--spin-us", str(SPIN_US), "--rt-priority", str(RT_PRIORITY)] if fifo else []
    chrt = ["chrt", "-f", str(RT_PRIORITY)] if fifo else []
    cm = None
    if fifo:
        url = lcm_url()
        cm = Proc([b.exe("controller_manager"), "--urdf", urdf, "--config", config, "--lcm-url", url,
                   "--log-level", "warn"] + flags, "controller_manager[realtime fifo]")
    else:
        url = b.cms[name][1]
    try:
        if cm:
            load_and_start(b.exe("cmctl"), url, ctrl)
        listener = Proc(chrt + [b.exe("bench_realtime"), "--lcm-url", url, "--seconds", str(duration + 30),
                                "--skip", "0.2" if b.smoke else "1"], "bench_realtime")
        listener.wait_for("listening", 10)
        sim = Proc([b.exe("sim_server"), "--urdf", urdf, "--config", config, "--lcm-url", url,
                    "--duration", str(duration), "--log-level", "warn"] + flags, "sim_server[realtime]")
        # The floor runs in the same minute, next to the sim: a bare loop sleeping to 1 kHz deadlines sees the
        # same competition for the CPUs (it costs ~1 % of a core).
        timer = Proc(chrt + [b.exe("bench_realtime"), "--timer-floor", str(duration)], "bench_realtime timer")
        # The floor of a period seen from another process: the bare loop's datagram, received as the listener
        # does.
        chain = Proc(chrt + [b.exe("bench_realtime"), "--chain-floor", str(duration)], "bench_realtime chain")
        if sim.wait(duration + 30) != 0:
            raise RuntimeError(f"sim_server (real time) failed:\n{sim.output()[-3000:]}")
        if listener.wait(10) != 0:
            raise RuntimeError(f"bench_realtime failed:\n{listener.output()[-3000:]}")
        if timer.wait(30) != 0:
            raise RuntimeError(f"bench_realtime --timer-floor failed:\n{timer.output()[-3000:]}")
        if chain.wait(30) != 0:
            raise RuntimeError(f"bench_realtime --chain-floor failed:\n{chain.output()[-3000:]}")
    finally:
        rc = cm.stop(5) if cm else 0
    if rc != 0:
        raise RuntimeError(f"controller_manager (real time, SCHED_FIFO) exited with {rc}:\n{cm.output()[-3000:]}")
    f, c, t = result_line(listener, "realtime"), result_line(chain, "chain"), result_line(timer, "timer")
    suffix = "_fifo" if fifo else ""
    b.r["chain_floor" + suffix] = {
        "n": int(c[1]), "p50": float(c[2]), "p99": float(c[3]), "max": float(c[4]), "short": int(c[5]),
        "latency_p50": float(c[6]), "latency_p99": float(c[7]), "seconds": duration}
    b.r["timer_floor" + suffix] = {
        "n": int(t[1]), "p50": float(t[2]), "p99": float(t[3]), "max": float(t[4]), "missed": int(t[5]),
        "short": int(t[6]), "window": float(t[7]), "seconds": duration}
    b.r.setdefault(name, {})["realtime" + suffix] = {
        "n": int(f[1]), "lost": int(f[2]), "p50": float(f[3]), "p99": float(f[4]), "max": float(f[5]),
        "sim_max": float(f[6]), "missed": int(f[7]), "overruns": int(f[8]), "cm_missed": int(f[9]),
        "rtf": float(f[10]), "sim_jitter": float(f[11]), "short": int(f[12]), "arrival_p50": float(f[13]),
        "arrival_p99": float(f[14]), "cm_window": float(f[17]), "duration": duration,
        "sim_rss": sim.rusage.ru_maxrss}
    b.sample_load()


def fifo_permitted():
    """Whether this user may run a process at SCHED_FIFO (root, CAP_SYS_NICE or an rtprio limit)."""
    try:
        return subprocess.run(["chrt", "-f", "1", "true"], capture_output=True).returncode == 0
    except OSError:
        return False


def quiet(b, fifo):
    """The real-time loop as one runs a robot that tools watch: the hardware loop on a URL of its own
    (--hardware-lcm-url), a listener taking only the 1 Hz statistics, and the bare loop sleeping to its deadlines in
    the same seconds; nothing else wakes at 1 kHz. Each process's own period error p99 per 1 s window (the figure
    both publish), median over the windows, against the bare loop's. Four ways, alternated three times: as
    shipped; as shipped over shared memory (--hardware-url shm:NAME); --spin-us on both; and launch's real-time profile (--rt-priority with --spin-us on both, the bare loop
    at the same SCHED_FIFO priority) where SCHED_FIFO is permitted."""
    name = "turret_bot"
    urdf, config, ctrl = b.models[name]
    duration = 1.0 if b.smoke else 15.0
    ways = ["shipped", "shm", "spin"] + (["fifo"] if fifo else [])
    runs = {w: [] for w in ways}
    for way in ways * (1 if b.smoke else 3):
        b.sample_load()
        url, hw = lcm_url(), lcm_url()
        if way == "shm":  # the hardware loop over shared memory (issue 34), as shipped otherwise
            hw = f"shm:bench-quiet-{os.getpid()}"
        flags = [] if way in ("shipped", "shm") else ["--spin-us", str(SPIN_US)]
        if way == "fifo":
            flags += ["--rt-priority", str(RT_PRIORITY)]
        cm = Proc([b.exe("controller_manager"), "--urdf", urdf, "--config", config, "--lcm-url", url,
                   "--hardware-lcm-url", hw, "--log-level", "warn"] + flags, f"controller_manager[quiet {way}]")
        try:
            load_and_start(b.exe("cmctl"), url, ctrl)
            listener = Proc([b.exe("bench_realtime"), "--lcm-url", url, "--statistics-only", "yes",
                             "--seconds", str(duration + 30), "--skip", "0.2" if b.smoke else "1"],
                            "bench_realtime[quiet]")
            listener.wait_for("listening", 10)
            sim = Proc([b.exe("sim_server"), "--urdf", urdf, "--config", config, "--lcm-url", url,
                        "--hardware-lcm-url", hw, "--duration", str(duration), "--log-level", "warn"] + flags,
                       f"sim_server[quiet {way}]")
            chrt = ["chrt", "-f", str(RT_PRIORITY)] if way == "fifo" else []
            timer = Proc(chrt + [b.exe("bench_realtime"), "--timer-floor", str(duration)],
                         "bench_realtime timer")
            if sim.wait(duration + 30) != 0:
                raise RuntimeError(f"sim_server (quiet, {' '.join(flags)}) failed:\n{sim.output()[-3000:]}")
            if timer.wait(30) != 0 or listener.wait(30) != 0:
                raise RuntimeError(f"bench_realtime (quiet) failed:\n{timer.output()[-2000:]}"
                                   f"{listener.output()[-2000:]}")
        finally:
            rc = cm.stop(5)
        if rc != 0:
            raise RuntimeError(f"controller_manager (quiet) exited with {rc}:\n{cm.output()[-3000:]}")
        f, t = result_line(listener, "realtime"), result_line(timer, "timer")
        runs[way].append({"missed": int(f[7]), "cm_missed": int(f[9]), "cm": float(f[17]), "sim": float(f[18]),
                          "floor": float(t[7]), "floor_missed": int(t[5])})
    b.r.setdefault(name, {})["quiet"] = {"runs": runs, "duration": duration}
