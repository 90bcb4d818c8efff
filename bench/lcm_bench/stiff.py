"""1b. Stiff D gains on a light link (bench_stiff, in process): the largest stable explicit d for a link inertia I at
a 1 ms step against the explicit bound 2*I/dt, and the largest implicit d tried (sim_server's ImplicitJointDamper): as
the simulator's position PID, and as the damping an effort command holds (controller_manager's effort PIDs)."""
from .processes import run as run_process


def run(b):
    out = run_process([b.exe("bench_stiff")] + (["--smoke"] if b.smoke else []), 60)
    rows = []
    for line in out.splitlines():
        f = line.split()
        if f and f[0] == "stiff":
            rows.append({"inertia": float(f[1]), "bound": float(f[2]), "explicit": float(f[3]),
                         "implicit": float(f[4]), "implicit_stable": f[5] == "1",
                         "damped_effort": float(f[6]), "damped_effort_stable": f[7] == "1"})
    if not rows:
        raise RuntimeError(f"bench_stiff printed no figures: {out}")
    b.r["stiff"] = rows
