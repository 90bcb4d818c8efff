#!/usr/bin/env python3
"""The tutorial across three hosts (issue 13): sim_server, controller_manager
and the tools each in a network namespace of their own, over udpm ttl=1.

    sim host ──┐                 ┌── cm host
               └─ switch (relay) ┘
    tool host ─┘   delay, loss, partition

Each host reaches a switch namespace over a veth pair, with its multicast route
on that link. The switch is this script's own relay: it forwards each
multicast datagram to the other links, and on the way delays it, drops it at
random, or drops everything of a partitioned host. (This kernel has no
sch_netem, so `tc netem` cannot do it; the relay is the impairment, measured
here the same way.) The hardware loop has its own URL (--hardware-lcm-url).

Checks:
1. Real time, a clean link: j1 goes to 0.5 and j2 follows 3.14*sin(i/100) at
   60 Hz from the tool host.
2. Real time, 20 ms delay each way and 5 % loss per link: j2 still follows; the
   statistics of sim_server and controller_manager count what was lost.
3. A 2 s partition of the controller manager's host: the sim's watchdog holds
   the robot, the controller manager says the hardware went silent and counts
   the steps it missed, and after the partition heals the loop resumes from the
   measured state, without a jump.
4. Lockstep on one host, across the three hosts, and across them with 5 % loss
   from the start (the spawner's requests and the command sources resent, the
   sim's republish recovering a lost state or command): no deadlock, and every
   joint_states row that arrives is the same bit for bit in all three.

Needs root and ip (iproute2); exits 77 (skipped) without them. Every process is
started with a time bound and stopped by its pid; the namespaces are removed.
"""
import argparse
import csv
import heapq
import math
import os
import random
import select
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from netns import run, skip  # noqa: E402

GROUP = "239.255.76.67"
PORT, HW_PORT = 7667, 7668  # each namespace has its own ports: nothing else on the machine sees them
URL = f"udpm://{GROUP}:{PORT}?ttl=1"
HW_URL = f"udpm://{GROUP}:{HW_PORT}?ttl=1"
HOSTS = ["sim", "cm", "tool"]
IP_PKTINFO = getattr(socket, "IP_PKTINFO", 8)  # Linux's value; Python 3.11's socket module leaves it out



# ------------------------------------------------------------------ the relay (runs in the switch namespace)

def relay_main(links, ports, seed):
    """links: [(host, ifname, ip)]. Reads commands on stdin: `delay MS`, `loss PERCENT`, `partition HOST`, `heal`,
    `counts`; prints `relay ready`, and answers `counts` with `forwarded=N lost=N cut=N` since the last `counts`."""
    rng = random.Random(seed)
    index_to_host = {socket.if_nametoindex(ifname): host for host, ifname, _ in links}
    receivers = []
    for port in ports:
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4 << 20)
        s.setsockopt(socket.IPPROTO_IP, IP_PKTINFO, 1)
        s.bind(("", port))
        for _, _, ip in links:
            s.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, socket.inet_aton(GROUP) + socket.inet_aton(ip))
        receivers.append((s, port))
    senders = {}
    for host, _, ip in links:
        o = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        o.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton(ip))
        o.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 1)
        o.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 0)
        senders[host] = o
    delay, loss, cut_hosts = 0.0, 0.0, set()
    forwarded = lost = cut = 0
    queue = []  # (due, seq, host, port, data)
    seq = 0
    pending = ""
    print("relay ready", flush=True)
    fds = [s for s, _ in receivers] + [sys.stdin]
    while True:
        now = time.monotonic()
        while queue and queue[0][0] <= now:
            _, _, host, port, data = heapq.heappop(queue)
            senders[host].sendto(data, (GROUP, port))
        timeout = max(0.0, queue[0][0] - now) if queue else 0.5
        ready, _, _ = select.select(fds, [], [], timeout)
        for r in ready:
            if r is sys.stdin:
                chunk = os.read(sys.stdin.fileno(), 4096).decode()  # not readline(): its buffer hides lines from select
                if not chunk:
                    return
                pending += chunk
                while "\n" in pending:
                    line, pending = pending.split("\n", 1)
                    cmd = line.split()
                    if cmd[0] == "delay":
                        delay = float(cmd[1]) / 1000
                    elif cmd[0] == "loss":
                        loss = float(cmd[1]) / 100
                    elif cmd[0] == "partition":
                        cut_hosts.add(cmd[1])
                    elif cmd[0] == "heal":
                        cut_hosts.clear()
                    elif cmd[0] == "counts":
                        print(f"forwarded={forwarded} lost={lost} cut={cut}", flush=True)
                        forwarded = lost = cut = 0
                continue
            port = next(p for s, p in receivers if s is r)
            for _ in range(64):  # what is queued, without starving the timer
                try:
                    data, anc, _, _ = r.recvmsg(65536, socket.CMSG_SPACE(12), socket.MSG_DONTWAIT)
                except BlockingIOError:
                    break
                src = None
                for level, kind, value in anc:
                    if level == socket.IPPROTO_IP and kind == IP_PKTINFO:
                        src = index_to_host.get(struct.unpack("i", value[:4])[0])
                if src is None:
                    continue
                due = time.monotonic() + delay
                for host in senders:
                    if host == src:
                        continue
                    if src in cut_hosts or host in cut_hosts:
                        cut += 1
                    elif loss > 0 and rng.random() < loss:
                        lost += 1
                    else:
                        forwarded += 1
                        seq += 1
                        if delay > 0:
                            heapq.heappush(queue, (due, seq, host, port, data))
                        else:
                            senders[host].sendto(data, (GROUP, port))


# ------------------------------------------------------------------ namespaces and processes

class Net:
    def __init__(self):
        tag = str(os.getpid() % 100000)
        self.switch = f"l3sw{tag}"
        self.ns = {h: f"l3{h}{tag}" for h in HOSTS}
        self.host_if = {h: f"h{k}_{tag}" for k, h in enumerate(HOSTS)}
        self.switch_if = {h: f"s{k}_{tag}" for k, h in enumerate(HOSTS)}
        octet = 100 + os.getpid() % 100
        self.switch_ip = {h: f"10.{octet}.{k}.1" for k, h in enumerate(HOSTS)}
        self.host_ip = {h: f"10.{octet}.{k}.2" for k, h in enumerate(HOSTS)}
        self.made = []

    def open(self):
        for ns in [self.switch] + list(self.ns.values()):
            r = run("ip", "netns", "add", ns, check=False)
            if r.returncode != 0:
                skip(f"cannot create a network namespace: {r.stderr.strip()}")
            self.made.append(ns)
            self.exec(ns, "ip", "link", "set", "lo", "up")
        for h in HOSTS:
            run("ip", "link", "add", self.host_if[h], "netns", self.ns[h], "type", "veth", "peer", "name",
                self.switch_if[h], "netns", self.switch)
            self.exec(self.ns[h], "ip", "addr", "add", self.host_ip[h] + "/24", "dev", self.host_if[h])
            self.exec(self.ns[h], "ip", "link", "set", self.host_if[h], "up")
            self.exec(self.ns[h], "ip", "route", "add", "224.0.0.0/4", "dev", self.host_if[h])
            self.exec(self.switch, "ip", "addr", "add", self.switch_ip[h] + "/24", "dev", self.switch_if[h])
            self.exec(self.switch, "ip", "link", "set", self.switch_if[h], "up")

    def exec(self, ns, *argv, check=True):
        return run("ip", "netns", "exec", ns, *argv, check=check)

    def close(self):
        for ns in self.made:
            run("ip", "netns", "del", ns, check=False)


class Proc:
    """A program in a namespace, output to a file; stopped by its pid (ip netns exec execs the program)."""
    live = []

    def __init__(self, ns, argv, logdir, name, stdin=None):
        self.name = name
        self.path = os.path.join(logdir, name + ".out")
        self.out = open(self.path, "w")
        env = dict(os.environ, LCM_DEFAULT_URL=URL)
        self.p = subprocess.Popen(["ip", "netns", "exec", ns] + argv, stdout=self.out, stderr=subprocess.STDOUT,
                                  stdin=stdin if stdin is not None else subprocess.DEVNULL, env=env, text=True)
        Proc.live.append(self)

    def output(self):
        with open(self.path) as f:
            return f.read()

    def wait_for(self, text, timeout):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if text in self.output():
                return True
            if self.p.poll() is not None:
                return text in self.output()
            time.sleep(0.05)
        return False

    def wait(self, timeout):
        try:
            return self.p.wait(timeout)
        except subprocess.TimeoutExpired:
            return None

    def stop(self, grace=10):
        if self.p.poll() is None:
            self.p.send_signal(signal.SIGINT)
            try:
                self.p.wait(grace)
            except subprocess.TimeoutExpired:
                self.p.kill()
                self.p.wait()
        return self.p.returncode

    @staticmethod
    def kill_all():
        for pr in Proc.live:
            if pr.p.poll() is None:
                pr.p.kill()
                pr.p.wait()


class Relay:
    def __init__(self, net, logdir, seed):
        links = ",".join(f"{h}:{net.switch_if[h]}:{net.switch_ip[h]}" for h in HOSTS)
        self.p = subprocess.Popen(["ip", "netns", "exec", net.switch, sys.executable, os.path.abspath(__file__),
                                   "--relay", links, "--seed", str(seed)],
                                  stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        Proc.live.append(self)
        line = self.p.stdout.readline()
        if "relay ready" not in line:
            raise RuntimeError(f"the relay did not start: {line}{self.p.stdout.read()}")

    def say(self, *cmd):
        self.p.stdin.write(" ".join(str(c) for c in cmd) + "\n")
        self.p.stdin.flush()

    def counts(self):
        self.say("counts")
        return dict(kv.split("=") for kv in self.p.stdout.readline().split())

    def stop(self):
        self.p.stdin.close()
        self.p.wait(10)


# ------------------------------------------------------------------ reading what was recorded

def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [{k: v for k, v in row.items()} for row in csv.DictReader(f)]


def log_to_csv(bindir, log, outdir):
    r = run(os.path.join(bindir, "log2csv"), log, "--output-dir", outdir, "--log-time", check=False)
    if r.returncode != 0:
        raise RuntimeError("log2csv failed: " + r.stdout + r.stderr)


def j(row, k):
    return float(row[f"position[{k}]"])


def rms_tracking(states, commands, t0, t1):
    """RMS and max of (j2 command - j2 position), joined by receive time, over log times [t0, t1]."""
    cmds = [(int(c["log_utime"]), float(c["data"])) for c in commands]
    errs, ci, last = [], 0, None
    for s in states:
        t = int(s["log_utime"])
        while ci < len(cmds) and cmds[ci][0] <= t:
            last = cmds[ci][1]
            ci += 1
        if t0 <= t <= t1 and last is not None:
            errs.append(last - j(s, 1))
    if not errs:
        return float("nan"), float("nan"), 0
    return math.sqrt(sum(e * e for e in errs) / len(errs)), max(abs(e) for e in errs), len(errs)


def window_sum(stats, field, t0, t1):
    return sum(int(s[field]) for s in stats if t0 <= int(s["log_utime"]) <= t1)


def now_us():
    return int(time.time() * 1e6)  # lcm-logger stamps with the wall clock


# ------------------------------------------------------------------ the sessions

def model_args(src):
    return ["--urdf", os.path.join(src, "config/turret_bot.urdf"), "--config", os.path.join(src, "config/turret_bot.yaml")]


def real_time_session(net, relay, b, src, logdir, failures):
    def tool(name, *argv):
        return Proc(net.ns["tool"], [b(argv[0])] + list(argv[1:]), logdir, name)

    sim = Proc(net.ns["sim"], [b("sim_server")] + model_args(src) + ["--hardware-lcm-url", HW_URL], logdir, "rt_sim")
    cm = Proc(net.ns["cm"], [b("controller_manager")] + model_args(src) + ["--hardware-lcm-url", HW_URL], logdir,
              "rt_cm")
    log = os.path.join(logdir, "rt.lcmlog")
    logger = Proc(net.ns["tool"], ["lcm-logger", f"--lcm-url={URL}", "-f", log], logdir, "rt_logger")
    spawner = tool("rt_spawner", "spawner", "joint_state_controller", "j1_controller", "j2_controller")
    if not spawner.wait_for("ready:", 40):
        failures.append("real time: the spawner on the tool host did not bring the controllers up:\n" +
                        spawner.output() + cm.output()[-2000:])
        return
    marks = {"start": now_us()}
    if tool("rt_j1", "turret-cmd", "j1_controller", "0.5").wait(15) != 0:
        failures.append("real time: turret-cmd j1 failed")
    sine = ["turret-cmd", "j2_controller", "3.14*sin(i/100)", "--rate", "60", "--duration", "4"]
    tool("rt_sine_clean", *sine).wait(20)
    marks["clean_end"] = now_us()

    relay.counts()
    relay.say("delay", 20)
    relay.say("loss", 5)
    marks["impaired"] = now_us()
    tool("rt_sine_impaired", *sine).wait(20)
    marks["impaired_end"] = now_us()
    impaired_counts = relay.counts()
    relay.say("delay", 0)
    relay.say("loss", 0)

    tool("rt_j2_hold", "turret-cmd", "j2_controller", "1.0").wait(15)
    time.sleep(2.0)
    marks["partition"] = now_us()
    relay.say("partition", "cm")
    time.sleep(2.0)
    relay.say("heal")
    marks["healed"] = now_us()
    time.sleep(2.5)
    marks["end"] = now_us()

    spawner.stop(15)
    for p in (cm, sim, logger):
        p.stop(15)
    outdir = os.path.join(logdir, "rt_csv")
    log_to_csv(os.path.dirname(b("log2csv")), log, outdir)
    states = read_csv(os.path.join(outdir, "joint_states.csv"))
    j2cmd = read_csv(os.path.join(outdir, "j2_controller__command.csv"))
    sim_stats = read_csv(os.path.join(outdir, "sim_server__statistics.csv"))
    cm_stats = read_csv(os.path.join(outdir, "controller_manager__statistics.csv"))
    if not states:
        failures.append("real time: no joint_states reached the tool host")
        return

    def at(t):  # the last joint_states received before t
        before = [s for s in states if int(s["log_utime"]) <= t]
        return before[-1] if before else None

    s = at(marks["clean_end"])
    print(f"real time, clean: j1 {j(s, 0):.4f} at the end of the sine")
    if abs(j(s, 0) - 0.5) > 0.01:
        failures.append(f"real time: j1 is {j(s, 0):.4f}, not 0.5")
    clean = rms_tracking(states, j2cmd, marks["start"] + 1_000_000, marks["clean_end"])
    impaired = rms_tracking(states, j2cmd, marks["impaired"] + 1_000_000, marks["impaired_end"])
    print(f"real time, j2 tracking rms / max |error| (rad): clean {clean[0]:.4f} / {clean[1]:.4f} ({clean[2]} "
          f"samples); 20 ms delay + 5 % loss {impaired[0]:.4f} / {impaired[1]:.4f} ({impaired[2]} samples)")
    print(f"relay during the impaired phase: {impaired_counts}")
    if int(impaired_counts.get("lost", 0)) == 0:
        failures.append("the relay lost nothing in the impaired phase: the test did not test loss")
    if not clean[0] < 0.5:
        failures.append(f"real time, clean: j2 does not follow the sine (rms {clean[0]:.4f} rad)")
    if not impaired[0] < 0.6:
        failures.append(f"real time, 20 ms + 5 %: j2 does not follow the sine (rms {impaired[0]:.4f} rad)")
    sim_missed = window_sum(sim_stats, "missed", marks["impaired"], marks["impaired_end"] + 1_100_000)
    cm_missed = window_sum(cm_stats, "missed", marks["impaired"], marks["impaired_end"] + 1_100_000)
    print(f"statistics during 20 ms + 5 %: sim_server missed {sim_missed}, controller_manager missed {cm_missed}")
    if sim_missed <= 0 or cm_missed <= 0:
        failures.append(f"the statistics did not count the losses (sim_server missed {sim_missed}, "
                        f"controller_manager missed {cm_missed})")

    before, after = at(marks["partition"]), [x for x in states if int(x["log_utime"]) > marks["healed"]]
    sim_part = window_sum(sim_stats, "missed", marks["partition"], marks["healed"] + 1_100_000)
    cm_part = window_sum(cm_stats, "missed", marks["healed"], marks["end"])
    print(f"partition of the cm host for 2 s: sim_server missed {sim_part}, controller_manager missed {cm_part} "
          f"(steps it never saw)")
    if sim_part < 1000:
        failures.append(f"sim_server/statistics counted {sim_part} missed commands over a 2 s partition")
    if cm_part < 1000:
        failures.append(f"controller_manager/statistics counted {cm_part} missed steps over a 2 s partition")
    if not after:
        failures.append("no joint_states after the partition healed")
    else:
        first = after[0]
        jump = max(abs(j(first, 0) - j(before, 0)), abs(j(first, 1) - j(before, 1)))
        vel = max(abs(float(x["velocity[1]"])) for x in after[:60])
        print(f"after the partition: first joint_states {(int(first['log_utime']) - marks['healed']) / 1e3:.0f} ms "
              f"after it healed, position change across it {jump:.5f} rad, |j2 velocity| <= {vel:.4f} rad/s in the "
              f"next second")
        if jump > 0.01 or vel > 0.05:
            failures.append(f"the loop jumped after the partition: {jump:.4f} rad, {vel:.4f} rad/s")
    so, co = sim.output(), cm.output()
    for text, where, what in (("(watchdog): every actuator holds", so, "sim_server did not hold the robot"),
                              ("no hardware/state for", co, "controller_manager did not report the silence"),
                              ("running controllers restart from the current state", co,
                               "controller_manager did not restart its controllers from the measured state")):
        if text not in where:
            failures.append(f"partition: {what} ('{text}' not in its output)")


def lockstep_run(hosts, b, src, logdir, name, relay=None, loss=0):
    """The tutorial in lockstep for 3 s of sim time: cm, spawner, two command sources (sim time), state-logger,
    then sim_server. hosts maps role -> namespace. Returns (joint_states rows, wall seconds, sim output)."""
    csv_path = os.path.join(logdir, name + "_joint_states.csv")
    if relay:
        relay.counts()
        relay.say("loss", loss)  # from the start: the spawner's requests and the command sources cross it too
    cm = Proc(hosts["cm"], [b("controller_manager")] + model_args(src) + ["--hardware-lcm-url", HW_URL], logdir,
              name + "_cm")
    spawner = Proc(hosts["tool"], [b("spawner"), "joint_state_controller", "j1_controller", "j2_controller",
                                   "--hardware-later"], logdir, name + "_spawner")
    if not spawner.wait_for("ready:", 40):
        raise RuntimeError(f"{name}: spawner not ready:\n{spawner.output()}{cm.output()[-2000:]}")
    sources = [Proc(hosts["tool"], [b("turret-cmd"), "j1_controller", "0.5", "--sim-time", "--count", "1"], logdir,
                    name + "_j1"),
               Proc(hosts["tool"], [b("turret-cmd"), "j2_controller", "3.14*sin(i/100)", "--sim-time", "--rate", "60",
                                    "--duration", "3"], logdir, name + "_j2")]
    for s in sources:
        if not s.wait_for("command source for", 20):
            raise RuntimeError(f"{name}: command source not registered:\n{s.output()}")
    logger = Proc(hosts["tool"], [b("state-logger"), "joint_states", "--output", csv_path], logdir, name + "_logger")
    time.sleep(0.5)
    t0 = time.monotonic()
    sim = Proc(hosts["sim"], [b("sim_server")] + model_args(src) +
               ["--hardware-lcm-url", HW_URL, "--mode", "lockstep", "--duration", "3", "--lockstep-timeout", "0.02"],
               logdir, name + "_sim")
    code = sim.wait(120)
    wall = time.monotonic() - t0
    counts = relay.counts() if relay else {}
    if relay:
        relay.say("loss", 0)
    time.sleep(0.5)
    for p in sources + [spawner, logger, cm]:
        p.stop(15)
    if code != 0:
        raise RuntimeError(f"{name}: sim_server did not finish 3 s of sim time in 120 s (exit {code}): a deadlock?\n"
                           f"{sim.output()[-3000:]}")
    return read_csv(csv_path), wall, counts, sim.output()


def lockstep_checks(net, relay, b, src, logdir, failures):
    one = {h: net.ns["tool"] for h in HOSTS}
    ref, wall_ref, _, _ = lockstep_run(one, b, src, logdir, "ls_one_host")
    three, wall_three, _, _ = lockstep_run(net.ns, b, src, logdir, "ls_three_hosts", relay)
    lossy, wall_lossy, counts, sim_out = lockstep_run(net.ns, b, src, logdir, "ls_lossy", relay, loss=5)
    print(f"lockstep, 3 s of sim time: one host {len(ref)} joint_states in {wall_ref:.2f} s; three hosts "
          f"{len(three)} in {wall_three:.2f} s; three hosts with 5 % loss {len(lossy)} in {wall_lossy:.2f} s "
          f"(relay: {counts})")
    if len(ref) < 150:
        failures.append(f"lockstep on one host recorded {len(ref)} joint_states, expected 151")
        return
    key = lambda r: r["utime"]
    by_time = {key(r): r for r in ref}
    if [key(r) for r in three] != [key(r) for r in ref]:
        failures.append(f"lockstep across three hosts: {len(three)} joint_states, one host {len(ref)}")
    differ = [r["utime"] for r in three + lossy if key(r) in by_time and r != by_time[key(r)]]
    unknown = [r["utime"] for r in three + lossy if key(r) not in by_time]
    if differ or unknown:
        failures.append(f"lockstep rows differ from the one-host run at utime {(differ + unknown)[:5]}")
    if len(lossy) < 0.8 * len(ref):
        failures.append(f"lockstep with 5 % loss: only {len(lossy)} of {len(ref)} joint_states arrived")
    if int(counts.get("lost", 0)) == 0:
        failures.append("the relay lost nothing in the lossy lockstep run: the test did not test loss")
    last = ref[-1]
    print(f"lockstep: j1 ends at {j(last, 0):.4f}; rows equal to the one-host run: three hosts "
          f"{sum(1 for r in three if by_time.get(key(r)) == r)}/{len(three)}, lossy "
          f"{sum(1 for r in lossy if by_time.get(key(r)) == r)}/{len(lossy)}")
    if abs(j(last, 0) - 0.5) > 0.01:
        failures.append(f"lockstep: j1 ends at {j(last, 0):.4f}, not 0.5")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin-dir")
    ap.add_argument("--source-dir")
    ap.add_argument("--relay", help=argparse.SUPPRESS)
    ap.add_argument("--seed", type=int, default=1, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.relay:
        links = [tuple(x.split(":")) for x in args.relay.split(",")]
        relay_main(links, [PORT, HW_PORT], args.seed)
        return 0
    if os.geteuid() != 0:
        skip("needs root (network namespaces)")
    for tool in ("ip", "lcm-logger"):
        if not subprocess.run(["which", tool], capture_output=True).returncode == 0:
            skip(f"{tool} not found (scripts/setup installs it)")
    b = lambda name: os.path.join(args.bin_dir, name)
    failures = []
    net = Net()
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="three_hosts_") as logdir:
        try:
            net.open()
            relay = Relay(net, logdir, seed=7)
            real_time_session(net, relay, b, args.source_dir, logdir, failures)
            lockstep_checks(net, relay, b, args.source_dir, logdir, failures)
            relay.stop()
        except Exception as e:  # a failure to set up or run is a failure, with what the processes said
            failures.append(f"{type(e).__name__}: {e}")
        finally:
            Proc.kill_all()
            net.close()
            if failures:
                for f in sorted(os.listdir(logdir)):
                    if f.endswith(".out"):
                        with open(os.path.join(logdir, f)) as fh:
                            tail = fh.read()[-1500:]
                        print(f"--- {f} (last 1500 characters)\n{tail}")
    print(f"three hosts: {time.monotonic() - started:.1f} s")
    for f in failures:
        print("FAILED: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
