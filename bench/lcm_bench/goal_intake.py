"""1d. Trajectory goals of 100,000 points (bench_goal_intake, in process): four a second over real LCM to a trajectory
controller at 1 kHz real time, taken in off the loop (the intake's thread, as the controller manager program does)
against in the loop (as before), and without goals; the loop thread's busy time per period and its CPU time in it;
also without goals and off the loop with the loop's thread on SCHED_FIFO (the program's --rt-priority) where
permitted, and on a CPU of its own (--cpu)."""
from .processes import run as run_process


def run(b):
    out = run_process([b.exe("bench_goal_intake")] + (["--smoke"] if b.smoke else []), 90)
    rows = {}
    cost = None
    for line in out.splitlines():
        f = line.split()
        if len(f) == 13 and f[0] == "goal_intake" and f[9] == "cpu":
            rows[f[1]] = {"periods": int(f[2]), "p50": float(f[3]), "p99": float(f[4]), "max": float(f[5]),
                          "over_1ms": int(f[6]), "sent": int(f[7]), "taken": int(f[8]),
                          "cpu_p99": float(f[10]), "cpu_max": float(f[11]), "cpu_over_1ms": int(f[12])}
        elif len(f) == 5 and f[0] == "goal_cost":
            cost = {"points": int(f[1]), "bytes": int(f[2]), "decode_ms": float(f[3]), "plan_ms": float(f[4])}
    if not {"none", "off_loop", "in_loop"} <= set(rows) or cost is None:
        raise RuntimeError(f"bench_goal_intake printed no figures: {out}")
    b.r["goal_intake"] = {"rows": rows, "cost": cost}
