"""2. Loop round trip: state -> controller_manager -> command against bare LCM and raw UDP echo servers
(bench_loop, bench_pingpong), on one core and on two."""
import os
import signal

from .figures import median
from .ports import free_udp_port, lcm_url
from .processes import Proc, pin_threads


def run(b):
    """Two placements, each pinned so the floors and our loop see the same scheduling: every process on one
    core (the stable figure, and the goal), then the servers on one core and the hardware side on another."""
    b.sample_load()
    cpus = sorted(os.sched_getaffinity(0))
    placements = [("one", {cpus[-1]}, {cpus[-1]})]
    if len(cpus) > 1:
        placements.append(("two", {cpus[-1]}, {cpus[0]}))
    try:
        for key, srv, cli in placements:
            for name in b.names:
                pin_threads(b.cms[name][0].pid, srv)
            placement(b, key, srv, cli)
    finally:
        for name in b.names:
            pin_threads(b.cms[name][0].pid, set(cpus))


def placement(b, key, srv, cli):
    lcm = lcm_url()
    port = free_udp_port()
    echo_lcm = Proc([b.exe("bench_pingpong"), "lcm-echo", lcm], "lcm-echo", cpus=srv)
    echo_udp = Proc([b.exe("bench_pingpong"), "udp-echo", str(port)], "udp-echo", cpus=srv)
    try:
        for name in b.names:
            urdf, config, _ = b.models[name]
            argv = [b.exe("bench_loop"), "--urdf", urdf, "--config", config, "--cm-url", b.cms[name][1],
                    "--lcm-url", lcm, "--udp-port", str(port)]
            argv += ["--rounds", "1", "--n", "20", "--warmup", "5"] if b.smoke else \
                ["--rounds", "21", "--n", "500", "--warmup", "50"]
            p = Proc(argv, f"bench_loop[{name}]", cpus=cli)
            rc = p.wait(60 if b.smoke else 180)
            if rc != 0:
                p.stop(1, signal.SIGKILL)
                raise RuntimeError(f"bench_loop[{name}] failed ({rc}):\n{p.output()[-3000:]}")
            blocks = {"udp": [], "lcm": [], "ours": [], "clock": []}
            sizes = None
            for line in p.output().splitlines():
                f = line.split()
                if f and f[0] == "sizes":
                    sizes = (int(f[1]), int(f[2]))
                elif f and f[0] == "rtt":
                    blocks[f[1]].append({"min": float(f[3]), "p50": float(f[4]), "p99": float(f[5]),
                                         "max": float(f[6]), "n": int(f[7]), "lost": int(f[8])})
            res = {"sizes": sizes, "cpus": (sorted(srv), sorted(cli))}
            for kind, bl in blocks.items():
                res[kind] = {k: median([blk[k] for blk in bl]) for k in ("min", "p50", "p99", "max")}
                res[kind]["lost"] = sum(blk["lost"] for blk in bl)
            for num, den in (("ours", "lcm"), ("lcm", "udp"), ("clock", "ours")):
                res[f"{num}/{den}"] = {k: median([x[k] / y[k] for x, y in zip(blocks[num], blocks[den])])
                                   for k in ("min", "p50", "p99")}
            b.r.setdefault(name, {})["rtt" if key == "one" else "rtt2"] = res
        b.r["floor_rss_kb"] = echo_lcm.vm_hwm_kb()
    finally:
        echo_lcm.stop(2, signal.SIGKILL)
        echo_udp.stop(2, signal.SIGKILL)
