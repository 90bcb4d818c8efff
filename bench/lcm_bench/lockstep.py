"""3 and 5. Lockstep throughput as launch runs it (sim_server and controller_manager on one CPU), unpinned,
through LCM's receive thread and over shared memory, with each process's peak RSS, and the shared-memory floor
(a bare futex ping-pong between two processes on that CPU; and the same with a bare Bullet step in one loop)."""
import os
import re

from .figures import median, us_per_step
from .processes import Proc, pin_threads


def run(b):
    """Each model as launch runs it in lockstep (sim_server and controller_manager on one CPU: they take turns,
    and a hand-over on one CPU is a cheaper wake-up), 3 times; and once unpinned (launch's `cpu: none`)."""
    b.sample_load()
    reps = 1 if b.smoke else 3
    cpus = sorted(os.sched_getaffinity(0))
    # kinds: pinned, unpinned, pinned with LCM's receive thread on both sides ("lcm"), pinned over shared memory
    runs = {(name, kind): [] for name in b.names for kind in (True, False, "lcm", "shm", "shm_free")}
    for rep in range(reps):
        order = b.names if rep % 2 == 0 else list(reversed(b.names))
        for name in order:
            # The goals are on turret_bot and chain100 (60 s each); the middle chains only show the scaling.
            duration = 0.3 if b.smoke else 60.0 if name in ("turret_bot", "chain100") else 20.0
            kinds = (True, "lcm", "shm", False, "shm_free") if rep == 0 else (True, "lcm", "shm")
            for kind in (kinds if rep % 2 == 0 else tuple(reversed(kinds))):
                cpu = None if kind in (False, "shm_free") else cpus[-1]
                cm_key = (name, "shm") if kind == "shm_free" else (name, kind) if kind in ("lcm", "shm") else name
                pin_threads(b.cms[cm_key][0].pid, {cpu} if cpu is not None else set(cpus))
                runs[(name, kind)].append(lockstep_run(b, name, duration, cpu, kind == "lcm",
                                                       kind in ("shm", "shm_free")))
                pin_threads(b.cms[cm_key][0].pid, set(cpus))
                if kind == "shm":
                    # The floor again, seconds after the run it is compared with: this machine's speed drifts by
                    # up to 2x over the minutes between sections 1 and 3.
                    runs[(name, kind)][-1]["floor"] = {"futex": futex_floor(b, name, cpus[-1], quick=True)["p50"],
                                                       "bare": futex_loop_floor(b, name, cpus[-1], quick=True)["bare"]}
        b.sample_load()
    for name in b.names:
        cm = b.cms[name][0]
        for kind, key in ((False, "lockstep_unpinned"), (True, "lockstep"), ("lcm", "lockstep_lcm"),
                          ("shm", "lockstep_shm"), ("shm_free", "lockstep_shm_unpinned")):
            rs = runs[(name, kind)]
            b.r.setdefault(name, {})[key] = {
                "wall": median([x["wall"] for x in rs]), "rtf": median([x["rtf"] for x in rs]),
                "rtf_lo": min(x["rtf"] for x in rs), "rtf_hi": max(x["rtf"] for x in rs),
                "duration": rs[0]["duration"], "physics_us": median([x["physics_us"] for x in rs])}
        # Each repetition's run over shared memory with the run over LCM (direct reader) and the floor next to it.
        b.r[name]["lockstep_shm"]["pairs"] = [
            {"shm_us": us_per_step(s), "lcm_us": us_per_step(l), **s["floor"]}
            for s, l in zip(runs[(name, "shm")], runs[(name, True)])]
        b.r[name]["memory"] = {"sim_kb": max(x["rss"] for x in runs[(name, True)]), "cm_kb": cm.vm_hwm_kb()}
        b.r[name]["futex"] = futex_floor(b, name, cpus[-1])
        b.r[name]["futex_loop"] = futex_loop_floor(b, name, cpus[-1])


def futex_floor(b, name, cpu, quick=False):
    """The bare futex ping-pong between two processes on `cpu`, the state's and the command's bytes copied each way
    (from section 2's sizes): the transport floor of the loop over shared memory. quick: a fifth as many."""
    sizes = b.r.get(name, {}).get("rtt", {}).get("sizes") or (128, 64)
    n, warmup = (200, 20) if b.smoke else (4000, 400) if quick else (20000, 2000)
    p = Proc([b.exe("bench_pingpong"), "futex-ping", str(n), str(warmup),
              str(sizes[0]), str(sizes[1])], f"futex-ping[{name}]", cpus={cpu})
    rc = p.wait(60)
    if rc != 0:
        raise RuntimeError(f"bench_pingpong futex-ping failed ({rc}):\n{p.output()[-2000:]}")
    f = p.output().split()
    return {"min": float(f[0]), "p50": float(f[1]), "p99": float(f[2])}


def futex_loop_floor(b, name, cpu, quick=False):
    """The same floor as one loop on `cpu`: a bare Bullet step of the model, then a bare futex round trip to a forked
    echo (bench_physics --futex-loop), so that what the physics loses to the other process at each switch (its caches,
    its TLB) counts, as it does in the lockstep loop. quick: 3 rounds instead of 11."""
    sizes = b.r.get(name, {}).get("rtt", {}).get("sizes") or (128, 64)
    urdf, config, _ = b.models[name]
    argv = [b.exe("bench_physics")]
    argv += ["--rounds", "1", "--sub-blocks", "2", "--block-ms", "0.2", "--min-steps", "2"] if b.smoke else \
        ["--rounds", "3" if quick else "11", "--sub-blocks", "8", "--block-ms", "2"]
    p = Proc(argv + ["--futex-loop", str(sizes[0]), str(sizes[1]), name, urdf, config], f"futex-loop[{name}]",
             cpus={cpu})
    rc = p.wait(60 if b.smoke else 240)
    if rc != 0:
        raise RuntimeError(f"bench_physics --futex-loop failed ({rc}):\n{p.output()[-2000:]}")
    rounds = [line.split() for line in p.output().splitlines() if line.startswith("physics-futex ")]
    return {"bare": median([float(f[3]) for f in rounds]), "loop": median([float(f[4]) for f in rounds])}


def lockstep_run(b, name, duration, cpu, lcm_reader=False, shm=False):
    urdf, config, _ = b.models[name]
    url = b.cms[(name, "lcm") if lcm_reader else (name, "shm") if shm else name][1]
    argv = [b.exe("sim_server"), "--urdf", urdf, "--config", config, "--lcm-url", url,
            "--mode", "lockstep", "--duration", str(duration), "--log-level", "info"]
    if lcm_reader:
        argv += ["--hardware-reader", "lcm"]
    if shm:
        argv += ["--hardware-url", b.shm_url(name)]
    sim = Proc(argv + (["--cpu", str(cpu)] if cpu is not None else []), f"sim_server[{name}]")
    t0 = sim.wait_for("ready (", 30)
    rc = sim.wait(30 if b.smoke else 600)
    if rc != 0:
        raise RuntimeError(f"sim_server[{name}] exited with {rc}:\n{sim.output()[-3000:]}")
    wall = sim.exit_time - t0
    # sim_server's last line: "... physics X µs a step", its mean physics step (actuators and Bullet) in this loop.
    m = re.search(r"physics ([0-9.eE+-]+) \S+ a step", sim.output())  # µs, whatever the locale decodes
    if not m:
        raise RuntimeError(f"sim_server[{name}] did not say what its physics step took:\n{sim.output()[-2000:]}")
    return {"wall": wall, "rtf": duration / wall, "rss": sim.rusage.ru_maxrss, "duration": duration,
            "physics_us": float(m.group(1))}
