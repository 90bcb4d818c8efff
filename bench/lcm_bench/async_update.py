"""1c. An is_async controller (bench_async, in process): a controller whose update sleeps 20 ms beside the turret_bot's
controllers at 1 kHz real time, on its own thread, against the same loop without it and with it in the loop."""
from .processes import run as run_process


def run(b):
    out = run_process([b.exe("bench_async")] + (["--smoke"] if b.smoke else []), 60)
    rows = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) == 9 and f[0] == "async":
            rows[f[1]] = {"cycles": int(f[2]), "p50": float(f[3]), "p99": float(f[4]), "max": float(f[5]),
                          "over_period": int(f[6]), "updates": int(f[7]), "skipped": int(f[8])}
    if set(rows) != {"none", "async", "sync"}:
        raise RuntimeError(f"bench_async printed no figures: {out}")
    b.r["async"] = rows
