"""bench/run's table: one row per figure, one column per robot, with its goal and whether it is met."""
import statistics

from .figures import fmt, median, us_per_step


def realtime_rows(r, row, yes, key, label, how):
    """Row 4 (or 4c): a minute of real time with a listener taking every state, against the floors of the same
    minute."""
    suffix = key[len("realtime"):]
    rtd = r.get("turret_bot", {}).get(key)
    if not rtd:
        return
    row(f"{label} real time 1 kHz{how}, {rtd['duration']:g} s: period error p50 / p99 / max, µs (controller side)",
        lambda d: "**{}** / **{}** / {}".format(*(fmt(d[key][k]) for k in ("p50", "p99", "max"))),
        "p99 ≤ 100 µs", yes(rtd["p99"] <= 100))
    tf = r.get("timer_floor" + suffix)
    if tf:
        row(f"{label} floor: bare 1 kHz clock_nanosleep loop, the same {tf['seconds']:g} s: period error p50 / p99 / "
            "max, µs", lambda d: "{} / {} / {}".format(*(fmt(tf[k]) for k in ("p50", "p99", "max")))
            if d is r["turret_bot"] else "–")
        row(f"{label} period error p99 / floor p99", lambda d: f'{d[key]["p99"] / tf["p99"]:.2f}', "≤ 1.2",
            yes(rtd["p99"] / tf["p99"] <= 1.2))
        # The kernel stamps each datagram as sim_server sends it (SO_TIMESTAMP): the sim's own loop, before any
        # receiver wakes, against the bare loop.
        row(f"{label} sim_server's publish period (the kernel's arrival stamps) p50 / p99, µs; p99 / floor p99",
            lambda d: "{} / {}; **{:.2f}**".format(fmt(d[key]["arrival_p50"]), fmt(d[key]["arrival_p99"]),
                                                  d[key]["arrival_p99"] / tf["p99"]),
            "≤ 1.2", yes(rtd["arrival_p99"] / tf["p99"] <= 1.2))
        if "cm_window" in rtd and "window" in tf:
            row(f"{label} controller_manager's own period error p99 per 1 s window, median over the windows / the bare "
                "loop's, µs", lambda d: "{} / {} = {:.2f}".format(fmt(d[key]["cm_window"]), fmt(tf["window"]),
                                                               d[key]["cm_window"] / tf["window"]))
    cf = r.get("chain_floor" + suffix)
    if cf:
        row(f"{label} floor 2: the bare loop's datagram received by another process, the same {cf['seconds']:g} s: "
            "period error p50 / p99 / max, µs (send to receipt p50 / p99)",
            lambda d: "{} / {} / {} ({} / {})".format(*(fmt(cf[k]) for k in ("p50", "p99", "max", "latency_p50",
                                                                              "latency_p99")))
            if d is r["turret_bot"] else "–")
        row(f"{label} period error p99 / floor 2 p99", lambda d: f'{d[key]["p99"] / cf["p99"]:.2f}', "≤ 1.2",
            yes(rtd["p99"] / cf["p99"] <= 1.2))
    row(f"{label} sim_server's own period: jitter (median of 1 s windows' std dev) / worst error, µs",
        lambda d: f'{fmt(d[key]["sim_jitter"])} / {fmt(d[key]["sim_max"])}')
    row(f"{label} back-to-back states (period < 0.5 ms: catching up after a stall) / the floor's",
        lambda d: f'{d[key]["short"]} / {tf["short"] if tf else "–"}')
    # The sim counts a step missed when it ran without its controller's answer (each step, once due, waits up to
    # --answer-wait-us for it) or was dropped after a stall of more than 0.5 s; the floor counts its own late
    # wake-ups in the same seconds.
    row(f"{label} **missed cycles** (sim) / the floor's late wake-ups / states lost / cm missed",
        lambda d: "**{}** / {} / {} / {}".format(d[key]["missed"], tf["missed"] if tf else "–", d[key]["lost"],
                                                 d[key]["cm_missed"]),
        "≤ the floor's", yes(bool(tf) and rtd["missed"] <= tf["missed"]))
    row(f"{label} real-time factor sim_server reports", lambda d: f'{d[key]["rtf"]:.4f}')


def table(b):
    r, names = b.r, b.names
    rows = []

    def row(label, fn, goal="", met=""):
        cells = []
        for n in names:
            try:
                cells.append(fn(r[n]))
            except (KeyError, TypeError):
                cells.append("–")
        rows.append([label] + cells + [goal, met])

    def yes(ok):
        return "yes" if ok else "**no**"

    ph = {n: r[n]["physics"] for n in names if "physics" in r.get(n, {})}
    row("joints (actuated)", lambda d: str(d["physics"]["ndof"]))
    row("1. bare Bullet stepSimulation, µs/step", lambda d: fmt(d["physics"]["bare"]))
    row("1. full sim step (actuators + Bullet), µs/step", lambda d: fmt(d["physics"]["full"]))
    ok = all(v["ratio"] <= 1.3 for v in ph.values())
    row("1. **physics overhead full/bare** (p25–p75 of the rounds)",
        lambda d: f'**{d["physics"]["ratio"]:.2f}** ({d["physics"]["ratio_lo"]:.2f}–{d["physics"]["ratio_hi"]:.2f})',
        "≤ 1.3", yes(ok))
    st = r.get("stiff")
    if st:
        row("1b. stiff D on a light link at 1 ms (`bench_stiff`), I = " +
            ", ".join(f'{x["inertia"]:g}' for x in st) + " kg m²: largest stable explicit d / bound 2·I/dt; "
            "implicit (sim_server's PID) stable up to; effort with its damping (controller_manager's effort PIDs) stable up to",
            lambda d: "; ".join(f'{x["explicit"]:.3g} / {x["bound"]:.3g} = **{x["explicit"] / x["bound"]:.2f}**, '
                                f'{x["implicit"]:.3g} ({x["implicit"] / x["bound"]:.0f}x)'
                                + ("" if x["implicit_stable"] else " **unstable**")
                                + f', {x["damped_effort"]:.3g} ({x["damped_effort"] / x["bound"]:.0f}x)'
                                + ("" if x["damped_effort_stable"] else " **unstable**") for x in st)
            if d is r[names[0]] else "–",
            "explicit ≤ 1.0x the bound; both implicit stable",
            yes(all(x["implicit_stable"] and x["damped_effort_stable"] for x in st)))
    a = r.get("async")
    if a:
        row("1c. a 20 ms update at 1 kHz (`bench_async`): cycle p50 / p99 / max µs, without it; is_async; in the loop",
            lambda d: "; ".join("{} / **{}** / {}".format(fmt(a[k]["p50"]), fmt(a[k]["p99"]), fmt(a[k]["max"]))
                                for k in ("none", "async", "sync")) if d is r[names[0]] else "–",
            "is_async p99 ≤ 1.5x without it",
            yes(a["async"]["p99"] <= 1.5 * a["none"]["p99"]))
    g = r.get("goal_intake")
    if g:
        gr, gc = g["rows"], g["cost"]
        # The loop's jitter budget: its periods without goals (the same scheduler, in the same run) plus one pass of
        # the socket (250 µs). SCHED_FIFO where permitted, as the program runs with --rt-priority.
        off, base = ("off_loop_fifo", "none_fifo") if "off_loop_fifo" in gr else ("off_loop", "none")
        row("1d. 100,000-point goals (3.6 MB), 4/s, at 1 kHz (`bench_goal_intake`): loop busy per period p50 / p99 / max "
            "µs and periods over 1 ms, without goals; off the loop; in the loop; on SCHED_FIFO without goals and off "
            "the loop, where permitted (one goal: decode + plan ms)",
            lambda d: "; ".join("{} / **{}** / {} ({})".format(fmt(gr[k]["p50"]), fmt(gr[k]["p99"]), fmt(gr[k]["max"]),
                                                              gr[k]["over_1ms"])
                                for k in ("none", "off_loop", "in_loop", "none_fifo", "off_loop_fifo") if k in gr)
            + " ({} + {})".format(fmt(gc["decode_ms"]), fmt(gc["plan_ms"])) if d is r[names[0]] else "–",
            "off the loop: p99 ≤ without goals + 250 µs, every goal taken",
            yes(gr[off]["p99"] <= gr[base]["p99"] + 250 and gr[off]["taken"] == gr[off]["sent"] > 0))
    row("2. payload state / command, bytes", lambda d: "{} / {}".format(*d["rtt"]["sizes"]))

    def mpp(k):
        return lambda d: "{} / {} / {}".format(*(fmt(d["rtt"][k][s]) for s in ("min", "p50", "p99")))
    row("2. one core (every process pinned to the same CPU): raw UDP round trip min / p50 / p99, µs", mpp("udp"))
    row("2. one core: bare LCM round trip min / p50 / p99, µs", mpp("lcm"))
    row("2. one core: our loop (state → controller_manager → command) min / p50 / p99, µs", mpp("ours"))
    rt = {n: r[n]["rtt"] for n in names if "rtt" in r.get(n, {})}
    ok = all(v["ours/lcm"]["min"] <= 1.2 and v["ours/lcm"]["p50"] <= 1.2 for v in rt.values())
    row("2. one core: **ours / bare LCM** min / p50 / p99", lambda d: "**{:.2f}** / **{:.2f}** / {:.2f}".format(
        *(d["rtt"]["ours/lcm"][s] for s in ("min", "p50", "p99"))), "≤ 1.2 (min, p50)", yes(ok))
    row("2. one core: bare LCM / raw UDP min / p50 / p99", lambda d: "{:.2f} / {:.2f} / {:.2f}".format(
        *(d["rtt"]["lcm/udp"][s] for s in ("min", "p50", "p99"))))
    row("2. one core: our loop + a `clock` message every step (sim_server `--clock-rate 0`; default 100 Hz), min / p50 / p99, µs", mpp("clock"))
    row("2. one core: (ours + clock) / ours min / p50 / p99", lambda d: "{:.2f} / {:.2f} / {:.2f}".format(
        *(d["rtt"]["clock/ours"][s] for s in ("min", "p50", "p99"))))
    row("2. two cores (echo servers and controller_manager on one CPU, hardware side on the other): bare LCM min / p50 / p99, µs",
        lambda d: "{} / {} / {}".format(*(fmt(d["rtt2"]["lcm"][s]) for s in ("min", "p50", "p99"))))
    row("2. two cores: ours / bare LCM min / p50 / p99", lambda d: "{:.2f} / {:.2f} / {:.2f}".format(
        *(d["rtt2"]["ours/lcm"][s] for s in ("min", "p50", "p99"))))
    row("2. two cores: (ours + clock) / ours min / p50 / p99", lambda d: "{:.2f} / {:.2f} / {:.2f}".format(
        *(d["rtt2"]["clock/ours"][s] for s in ("min", "p50", "p99"))))
    row("3. lockstep: wall time, s / sim time, s", lambda d: f'{fmt(d["lockstep"]["wall"])} / {d["lockstep"]["duration"]:g}')

    # Each repetition's run over shared memory (shm_us a step), the LCM run next to it (lcm_us) and the floor
    # measured seconds after it: issue 34's floor, the bare futex round trip p50 + the bare Bullet step.
    def pair_floor(p):
        return p["futex"] + p["bare"]

    def futex_floor(d):
        return median([pair_floor(p) for p in d["lockstep_shm"]["pairs"]])

    def lcm_ratio(d):  # shared memory's real-time factor ÷ LCM's (direct reader), the median of the repetitions'
        return median([p["lcm_us"] / p["shm_us"] for p in d["lockstep_shm"]["pairs"]])

    def floor_ratio(d):
        return median([p["shm_us"] / pair_floor(p) for p in d["lockstep_shm"]["pairs"]])

    def per_step(d):
        us = us_per_step(d["lockstep"])
        floor = d["rtt"]["lcm"]["p50"] + d["physics"]["full"]
        return f"{fmt(us)} / {fmt(floor)} = {us / floor:.2f}"
    row("3. µs per lockstep step / floor (one-core bare LCM p50 + full sim step) = ratio", per_step)
    goals = {"turret_bot": 25, "chain100": 5}
    ls = {n: r[n]["lockstep"]["rtf"] for n in names if "lockstep" in r.get(n, {})}
    ok = all(ls[n] >= g for n, g in goals.items() if n in ls)
    row("3. **lockstep real-time factor**, sim_server + controller_manager on one CPU as launch runs them (range)",
        lambda d: "**{:.1f}x** ({:.1f}–{:.1f})".format(
        d["lockstep"]["rtf"], d["lockstep"]["rtf_lo"], d["lockstep"]["rtf_hi"]),
        "turret ≥ 25x, chain100 ≥ 5x",
        "; ".join(f"{n.replace('_bot', '')} {yes(ls[n] >= g)}" for n, g in goals.items() if n in ls))
    row("3. lockstep real-time factor through LCM's receive thread (`--hardware-reader lcm` on both, the way before) "
        "/ direct ÷ that",
        lambda d: "{:.1f}x / {:.2f}".format(d["lockstep_lcm"]["rtf"], d["lockstep"]["rtf"] / d["lockstep_lcm"]["rtf"]))
    # Issue 34: the hardware loop over shared memory, against LCM (direct reader) in the same run, and its floor.
    shm = {n: r[n] for n in names if "lockstep_shm" in r.get(n, {}) and "lockstep" in r[n]}
    shm_goals = {"turret_bot": (100, 2.5), "chain100": (None, 1.5)}
    shm_met = []
    for n, (rtf_goal, ratio_goal) in shm_goals.items():
        if n in shm:
            rtf, ratio = shm[n]["lockstep_shm"]["rtf"], lcm_ratio(shm[n])
            ok = ratio >= ratio_goal and (rtf_goal is None or rtf >= rtf_goal)
            shm_met.append(f"{n.replace('_bot', '')} {yes(ok)}")
    row("3. **lockstep over shared memory** (`--hardware-url shm`, both on one CPU as launch runs them; range) / "
        "÷ over LCM (direct reader, the row above; each repetition's pair of runs, the median)",
        lambda d: "**{:.1f}x** ({:.1f}–{:.1f}) / **{:.2f}**".format(
            d["lockstep_shm"]["rtf"], d["lockstep_shm"]["rtf_lo"], d["lockstep_shm"]["rtf_hi"], lcm_ratio(d)),
        "turret ≥ 100x and ≥ 2.5x; chain100 ≥ 1.5x", "; ".join(shm_met))

    def shm_floor(d):
        each = "; ".join(f"{fmt(p['shm_us'])} / ({fmt(p['futex'])} + {fmt(p['bare'])}) = {p['shm_us'] / pair_floor(p):.2f}"
                         for p in d["lockstep_shm"]["pairs"])
        return f"{each}; median **{floor_ratio(d):.2f}**"
    floor_ok = list(shm)
    row("3. over shared memory: µs per step / floor (bare futex ping-pong p50 between two processes on that CPU, "
        "the state's and command's bytes copied, + bare Bullet step; both measured seconds after each run, as the "
        "machine's speed drifts) = ratio, each repetition", shm_floor, "≤ 1.3",
        "; ".join(f"{n.replace('_bot', '')} " + yes(floor_ratio(r[n]) <= 1.3) for n in floor_ok))
    row("3. floor: bare futex ping-pong min / p50 / p99, µs", lambda d: "{} / {} / {}".format(
        *(fmt(d["futex"][k]) for k in ("min", "p50", "p99"))))

    # Where a step over shared memory goes, and what no transport can remove: the physics as it runs in the loop
    # (sim_server's own mean; most likely slower than alone because the other process evicts its caches).
    def in_loop(d):
        return "{} / {}; **{:.2f}**".format(fmt(d["lockstep"]["physics_us"]), fmt(d["lockstep_shm"]["physics_us"]),
                                            d["lockstep_shm"]["physics_us"] / d["physics"]["full"])

    def least_us(d):  # a step over shared memory if our code and the controller manager took no time
        return d["lockstep_shm"]["physics_us"] + median([p["futex"] for p in d["lockstep_shm"]["pairs"]])

    def at_floor(d):  # a step exactly at the floor: its real-time factor, and that ÷ the LCM figure
        floor = futex_floor(d)
        return 1e3 / floor, median([p["lcm_us"] for p in d["lockstep_shm"]["pairs"]]) / floor

    def within_reach(n):
        rtf, ratio = at_floor(r[n])
        rtf_goal, ratio_goal = shm_goals[n]
        out = []
        if rtf_goal is not None and rtf < rtf_goal:
            out.append(f"{rtf_goal}x")
        if ratio < ratio_goal:
            out.append(f"{ratio_goal}x the LCM figure")
        return f"{n.replace('_bot', '')} " + (f"**no: {' and '.join(out)} out of reach**" if out else "yes")

    def least_floor(d):
        return least_us(d) / futex_floor(d)
    phys = [n for n in shm if "physics_us" in r[n]["lockstep_shm"] and "physics" in r[n] and "futex" in r[n]]
    if phys:
        row("3. the physics step inside the loop (sim_server's own mean: actuators and Bullet), µs: over LCM / over "
            "shared memory; the latter ÷ the same step alone (section 1's full step)", in_loop)
        row("3. a step exactly at the floor (bare futex round trip p50 + bare Bullet step) would give: real-time "
            "factor / ÷ over LCM (direct reader) in this run",
            lambda d: "{:.1f}x / {:.2f}".format(*at_floor(d)), "within reach of turret ≥ 100x and ≥ 2.5x; chain100 "
            "≥ 1.5x", "; ".join(within_reach(n) for n in shm_goals if n in phys))
        row("3. the least the floor ratio could be in this run: (the physics step inside the shared-memory loop + "
            "the bare futex round trip p50) ÷ (the same round trip + the bare Bullet step)",
            lambda d: "**{:.2f}**".format(least_floor(d)), "≤ 1.3",
            "; ".join(f"{n.replace('_bot', '')} " + ("yes" if least_floor(r[n]) <= 1.3 else "**no: out of reach**")
                      for n in phys))

    def shm_loop_floor(d):
        us = us_per_step(d["lockstep_shm"])
        f = d["futex_loop"]
        return f"{fmt(us)} / {fmt(f['loop'])} = **{us / f['loop']:.2f}** (bare step alone there {fmt(f['bare'])})"
    if any("futex_loop" in r[n] and "lockstep_shm" in r[n] for n in r):
        row("3. over shared memory: µs per step / the same floor as one loop on that CPU (a bare Bullet step, then the "
            "bare futex round trip to a forked echo: `bench_physics --futex-loop`; the physics pays for the switches "
            "in caches and TLB as in the loop) = ratio", shm_loop_floor)
    row("3. lockstep real-time factor, not pinned (launch's `cpu: none`; one run)",
        lambda d: "{:.1f}x".format(d["lockstep_unpinned"]["rtf"]))
    if any("lockstep_shm_unpinned" in r.get(n, {}) for n in names):
        row("3. lockstep over shared memory, not pinned (launch's `cpu: none`: with two CPUs free each process has "
            "one, and each wait spins on sched_yield for up to 1 ms; one run)",
            lambda d: "{:.1f}x".format(d["lockstep_shm_unpinned"]["rtf"]))
    for key, label, how in (("realtime", "4.", ""),
                            ("realtime_fifo", "4c.", f" as `launch --rt-priority {b.RT_PRIORITY}` runs it (SCHED_FIFO "
                                                     f"{b.RT_PRIORITY} and `--spin-us {b.SPIN_US}` on both; the "
                                                     "listener and both floors at the same priority)")):
        realtime_rows(r, row, yes, key, label, how)
    q = r.get("turret_bot", {}).get("quiet")
    if q:
        def quiet(way, fn):
            return lambda d: "; ".join(fn(x) for x in q["runs"][way]) if d is r["turret_bot"] else "–"

        def verdict(runs, holds, median_holds):
            """Decided by the median run, so that one run a VM stall spoiled does not decide; how many held beside."""
            return f"{yes(median_holds)} ({sum(1 for x in runs if holds(x))} of {len(runs)} runs)"
        ways = {"shipped": "as shipped", "shm": "over shared memory (`--hardware-url shm`), as shipped otherwise",
                "spin": f"`--spin-us {b.SPIN_US}` on both",
                "fifo": f"`launch --rt-priority {b.RT_PRIORITY}` (SCHED_FIFO {b.RT_PRIORITY} and `--spin-us "
                        f"{b.SPIN_US}` on both; the bare loop at SCHED_FIFO {b.RT_PRIORITY} too)"}
        for way, how in ways.items():
            runs = q["runs"].get(way, [])
            if not runs:
                continue
            row(f"4b. the hardware loop on its own URL, {how}, {q['duration']:g} s runs ({len(runs)}, alternated): "
                "period error p99 per 1 s window, median over the windows, µs: controller_manager / sim_server / bare "
                "loop", quiet(way, lambda x: f'{fmt(x["cm"])}, {fmt(x["sim"])}, {fmt(x["floor"])}'))
            ratio = statistics.median(x["cm"] / x["floor"] for x in runs)
            row(f"4b. {how}: **controller_manager / bare loop**, sim_server / bare loop (each run; the median of the "
                "first decides)",
                quiet(way, lambda x: f'**{x["cm"] / x["floor"]:.2f}**, {x["sim"] / x["floor"]:.2f}'), "≤ 1.2",
                verdict(runs, lambda x: x["cm"] <= 1.2 * x["floor"], ratio <= 1.2))
            over = statistics.median(x["missed"] - x["floor_missed"] for x in runs)
            row(f"4b. {how}: **missed cycles** (sim) / the floor's late wake-ups / cm missed (each run; the median "
                "of the excess decides)",
                quiet(way, lambda x: f'**{x["missed"]}** / {x["floor_missed"]} / {x["cm_missed"]}'),
                "≤ the floor's", verdict(runs, lambda x: x["missed"] <= x["floor_missed"], over <= 0))
    if q and q["runs"].get("shm") and q["runs"].get("shipped"):
        shm_cm = statistics.median(x["cm"] for x in q["runs"]["shm"])
        lcm_cm = statistics.median(x["cm"] for x in q["runs"]["shipped"])
        row("4b. real time 1 kHz **over shared memory against LCM** (its own URL), as shipped, the same minutes: "
            "controller_manager's period error p99 per window, median over the runs, µs: shm / LCM = ratio",
            lambda d: f"{fmt(shm_cm)} / {fmt(lcm_cm)} = **{shm_cm / lcm_cm:.2f}**" if d is r["turret_bot"] else "–",
            "≤ 1", yes(shm_cm <= lcm_cm))
    row("5. peak RSS sim_server (lockstep run), MB", lambda d: f'{d["memory"]["sim_kb"] / 1024:.1f}')
    row("5. peak RSS controller_manager, MB", lambda d: f'{d["memory"]["cm_kb"] / 1024:.1f}')
    if r.get("floor_rss_kb"):
        row("5. floor: peak RSS of a bare LCM echo process, MB",
            lambda d: f'{r["floor_rss_kb"] / 1024:.1f}' if d is r[names[0]] else "–")
    header = ["figure"] + names + ["goal", "met"]
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)
