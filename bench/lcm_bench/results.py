"""bench/RESULTS.md: each run at the top (newest first, older runs kept below), with the machine, the commit and the
load it ran under."""
import datetime
import os
import platform
import subprocess

from . import HERE, REPO
from .figures import median

RESULTS_MARKER = "<!-- bench/run: newest run first -->"


def machine():
    cpu, cores = "?", 0
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name") and cpu == "?":
                cpu = line.split(":", 1)[1].strip()
            if line.startswith("processor"):
                cores += 1
    mem = "?"
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemTotal:"):
                mem = f"{int(line.split()[1]) / 1024 / 1024:.1f} GiB"
    u = platform.uname()
    return f"{cpu}, {cores} logical CPUs, {mem} RAM; {u.system} {u.release} {u.machine}"


def write_results(b, tab, build_s, build_kind):
    path = os.path.join(HERE, "RESULTS.md")
    old = ""
    if os.path.exists(path):
        with open(path) as f:
            text = f.read()
        if RESULTS_MARKER in text:
            old = text.split(RESULTS_MARKER, 1)[1].strip("\n")
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    load = b.load
    head = ["# Benchmark results", "",
            "Written by `bench/run` (see [README.md](README.md) for what each figure measures). Newest run first; "
            "older runs stay below so a regression shows in review. Absolute µs drift ±25 % between runs on a "
            "shared VM: compare the ratios.", "", RESULTS_MARKER, ""]
    body = [f"## {now}", "",
            f"- machine: {machine()}",
            f"- commit: {git_commit()}",
            f"- load average (1 min) during the run: min {min(load):.2f}, median {median(load):.2f}, "
            f"max {max(load):.2f} (sampled every 5 s)",
            f"- `bench/run`: build {build_s:.0f} s ({build_kind}), benchmarks {b.run_s:.0f} s", "",
            tab, ""]
    with open(path, "w") as f:
        f.write("\n".join(head + body) + ("\n" + old + "\n" if old else ""))
    return path


def write_section(title, script, run_s, tab):
    """Puts one run of another bench script (bench/robots, bench/dashboard) at the top of RESULTS.md, under
    `## <now>: <title>`; returns the file's path."""
    path = os.path.join(HERE, "RESULTS.md")
    with open(path) as f:
        text = f.read()
    head, old = text.split(RESULTS_MARKER, 1)
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    body = [f"## {now}: {title}", "",
            f"- machine: {machine()}",
            f"- commit: {git_commit()}",
            f"- `{script}`: {run_s:.0f} s", "", tab, ""]
    with open(path, "w") as f:
        f.write(head + RESULTS_MARKER + "\n\n" + "\n".join(body) + "\n" + old.strip("\n") + "\n")
    return path


def git_commit():
    try:
        out = subprocess.run(["git", "-C", REPO, "log", "-1", "--format=%h %s"], capture_output=True, text=True,
                             timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--", "control", "rt", "description", "bus", "cli", "lcmtypes", "sim_server",
                                "controller_manager", "tools", "bench"], capture_output=True, text=True,
                               timeout=10).stdout.strip()
        return f"`{out[:80] or '?'}`" + (" + uncommitted changes in the working tree" if dirty else "")
    except Exception:
        return "?"
