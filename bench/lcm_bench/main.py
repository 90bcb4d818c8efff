"""bench/run's command line, and script_main for the bench scripts beside it: flags, the Release build, the run,
the table, the results file."""
import argparse
import os
import shutil
import signal
import subprocess
import sys
import time

from . import REPO
from .processes import PROCESS_TARGET, stop_all, use_build_dir
from .results import write_results, write_section
from .session import Bench
from .table import table

TARGETS = ["sim_server", "controller_manager", "cmctl", "bench_physics", "bench_stiff", "bench_async", "bench_goal_intake", "bench_loop", "bench_realtime",
           "bench_pingpong"]


def script_main(doc, script, targets, bench_class, table, title):
    """main() of a bench script beside bench/run: --smoke, --build-dir, --no-build, --no-write; builds `targets` in
    the Release build, runs bench_class(args).run(), prints table(bench) and, unless --smoke or --no-write, writes it
    into RESULTS.md as `title`. Returns the exit code."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--smoke", action="store_true")
    ap.add_argument("--build-dir", default=os.path.join(REPO, "build-release"))
    ap.add_argument("--no-build", action="store_true")
    ap.add_argument("--no-write", action="store_true")
    args = ap.parse_args()
    signal.signal(signal.SIGTERM, lambda s, f: (_ for _ in ()).throw(KeyboardInterrupt(f"signal {s}")))
    try:
        if not args.no_build:
            build(args.build_dir, targets)
        use_build_dir(args.build_dir)
        b = bench_class(args)
        try:
            b.run()
        finally:
            stop_all()
            shutil.rmtree(b.tmp, ignore_errors=True)
        tab = table(b)
        print(tab)
        if not args.smoke and not args.no_write:
            print(f"{script}: wrote {write_section(title, script, b.run_s, tab)}", file=sys.stderr)
        return 0
    except KeyboardInterrupt as e:
        stop_all()
        print(f"{script}: interrupted ({e})", file=sys.stderr)
        return 130
    except Exception as e:
        stop_all()
        print(f"{script}: error: {e}", file=sys.stderr)
        return 1


def build(build_dir, targets=TARGETS):
    t0 = time.monotonic()
    subprocess.run(["cmake", "-S", REPO, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release"], check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build_dir, "-j", str(os.cpu_count() or 2), "--target"] + targets +
                   [PROCESS_TARGET], check=True, stdout=subprocess.DEVNULL)
    return time.monotonic() - t0


def main(doc):
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--smoke", action="store_true", help="a few iterations of each benchmark; nothing written")
    ap.add_argument("--build-dir", default=os.path.join(REPO, "build-release"))
    ap.add_argument("--no-build", action="store_true", help="use the programs already built in --build-dir")
    ap.add_argument("--no-write", action="store_true", help="do not write bench/RESULTS.md")
    args = ap.parse_args()

    def on_signal(sig, _frame):
        raise KeyboardInterrupt(f"signal {sig}")
    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGALRM, on_signal)
    signal.alarm(60 if args.smoke else 1800)  # a bound on everything, build included

    t_start = time.monotonic()
    build_s = 0.0
    build_kind = "none (--no-build)"
    if not args.no_build and not args.smoke:
        build_kind = "incremental" if os.path.exists(os.path.join(args.build_dir, "bin", "sim_server")) else "fresh"

        print(f"bench: building {', '.join(TARGETS)} in Release in {args.build_dir}", file=sys.stderr, flush=True)
        build_s = build(args.build_dir)
        print(f"bench: build took {build_s:.0f} s", file=sys.stderr, flush=True)
    use_build_dir(args.build_dir)
    b = Bench(args)
    try:
        b.run_all()
    finally:
        stop_all()
        shutil.rmtree(b.tmp, ignore_errors=True)
    tab = table(b)
    total = time.monotonic() - t_start
    print(tab)
    print(f"\nbench: build {build_s:.0f} s + benchmarks {b.run_s:.0f} s = {total:.0f} s; "
          f"load average {min(b.load):.2f}–{max(b.load):.2f}", flush=True)
    if not args.smoke and not args.no_write:
        path = write_results(b, tab, build_s, build_kind)
        print(f"bench: wrote {path}", file=sys.stderr)
    return 0


def entry(doc):
    """bench/run's process: main(doc), with its exit code for an interruption (130) or an error (1)."""
    try:
        sys.exit(main(doc))
    except KeyboardInterrupt as e:
        stop_all()
        print(f"bench: interrupted ({e})", file=sys.stderr)
        sys.exit(130)
    except Exception as e:
        stop_all()
        print(f"bench: error: {e}", file=sys.stderr)
        sys.exit(1)
