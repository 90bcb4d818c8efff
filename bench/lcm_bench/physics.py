"""1. Physics overhead: the full sim step (actuators + Bullet) against bare stepSimulation, in process
(bench_physics)."""
from .figures import median, quantile
from .processes import run as run_process


def run(b):
    b.sample_load()
    argv = [b.exe("bench_physics")]
    argv += ["--rounds", "1", "--sub-blocks", "2", "--block-ms", "0.2", "--min-steps", "2"] if b.smoke else \
        ["--rounds", "51", "--sub-blocks", "8", "--block-ms", "0.5"]
    for name in b.names:
        urdf, config, _ = b.models[name]
        argv += [name, urdf, config]
    out = run_process(argv, 60 if b.smoke else 240)
    per = {}
    for line in out.splitlines():
        f = line.split()
        if f and f[0] == "physics":
            d = per.setdefault(f[1], {"ndof": int(f[2]), "bare": [], "full": []})
            d["bare"].append(float(f[4]))
            d["full"].append(float(f[5]))
        elif f and f[0] == "physics-check" and f[2] != "ok":
            raise RuntimeError(f"bench_physics: {line}")
    for name, d in per.items():
        ratios = [fu / ba for ba, fu in zip(d["bare"], d["full"])]
        b.r.setdefault(name, {})["physics"] = {
            "ndof": d["ndof"], "bare": median(d["bare"]), "full": median(d["full"]), "ratio": median(ratios),
            "ratio_lo": quantile(ratios, 0.25), "ratio_hi": quantile(ratios, 0.75)}
