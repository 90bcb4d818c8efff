"""How the benchmarks reduce their samples, and how a figure is printed."""
import statistics


def quantile(xs, f):
    xs = sorted(x for x in xs if x == x)
    return xs[min(len(xs) - 1, int(f * (len(xs) - 1) + 0.5))] if xs else float("nan")


def median(xs):
    xs = [x for x in xs if x == x]
    return statistics.median(xs) if xs else float("nan")


def us_per_step(run):
    """A lockstep run's wall time per step of sim time (1 kHz), µs."""
    return run["wall"] / (run["duration"] * 1000) * 1e6


def fmt(x, digits=3):
    if x is None or x != x:
        return "–"
    if abs(x) >= 100:
        return f"{x:.0f}"
    return f"{x:.{digits}g}"
