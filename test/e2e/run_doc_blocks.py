#!/usr/bin/env python3
"""Runs every ```sh block of a Markdown guide, as a user would paste it.

The blocks run with bash from a scratch folder that looks like the repository
root (config/, docs/, scripts/, test/ and build/bin, build/share linked to this build),
with LCM_DEFAULT_URL set to a bus of this run's own, next to a running
turret_bot (launch config/turret_bot.launch.yaml, with j2 driven by turret-cmd).

Conventions in the guide:
  * a block whose first line is `# runs until Ctrl-C` is started in the
    background, must still run after a few seconds, and is then stopped with
    SIGINT (as Ctrl-C would);
  * `# exit N` as a first line: the block must exit with N (default 0);
  * a block that starts a whole robot (`build/bin/launch FILE` without
    --dry-run) runs on a bus of its own, not next to the running turret_bot
    (one robot per bus);
  * a ```text block right after a ```sh block is expected output: each of its
    lines must appear in what the block printed.
Exit code 0 when every block behaved; 1 with one line per failure otherwise.
"""
import argparse
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

BACKGROUND_S = 3.0


def blocks(markdown):
    """[(lang, text, line)] of the fenced blocks."""
    out = []
    for m in re.finditer(r"^```(\w*)\n(.*?)^```\s*$", markdown, re.M | re.S):
        out.append((m.group(1), m.group(2), markdown.count("\n", 0, m.start()) + 1))
    return out


def free_url():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("", 0))
    port = s.getsockname()[1]
    s.close()
    return "udpm://239.255.76.67:%d?ttl=0" % port


def stop(p, grace=10.0):
    """SIGINT to the process group, then SIGKILL; returns (exit code, output)."""
    try:
        os.killpg(p.pid, signal.SIGINT)
    except ProcessLookupError:
        pass
    try:
        out, _ = p.communicate(timeout=grace)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
    return p.returncode, out


def start(cmd, cwd, env):
    return subprocess.Popen(["bash", "-c", cmd], cwd=cwd, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--guide", required=True)
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--bin-dir", required=True)
    args = ap.parse_args()

    with open(args.guide) as f:
        found = blocks(f.read())
    root = tempfile.mkdtemp(prefix="lcm_control_docs_")
    os.makedirs(os.path.join(root, "build"))
    for name in ("config", "docs", "scripts", "test"):
        os.symlink(os.path.join(args.source_dir, name), os.path.join(root, name))
    os.symlink(args.bin_dir, os.path.join(root, "build", "bin"))
    os.symlink(os.path.join(os.path.dirname(args.bin_dir), "share"), os.path.join(root, "build", "share"))
    env = dict(os.environ, LCM_DEFAULT_URL=free_url())
    print("guide %s: %d blocks, bus %s, in %s" % (args.guide, len(found), env["LCM_DEFAULT_URL"], root))

    failures = []
    robot = start("build/bin/launch config/turret_bot.launch.yaml", root, env)
    driver = None
    try:
        deadline = time.time() + 40
        ready = False
        while time.time() < deadline and robot.poll() is None:
            r = subprocess.run(["build/bin/cmctl", "list"], cwd=root, env=env, capture_output=True, text=True)
            if r.returncode == 0 and r.stdout.count("running") >= 3:
                ready = True
                break
            time.sleep(0.5)
        if not ready:
            code, out = stop(robot)
            print("turret_bot did not come up (launch exit %s):\n%s" % (code, out))
            return 1
        driver = start("build/bin/turret-cmd j2_controller '3.14*sin(i/100)' --rate 60", root, env)

        ran = 0
        for k, (lang, text, line) in enumerate(found):
            if lang != "sh":
                continue
            ran += 1
            first = text.splitlines()[0].strip() if text.strip() else ""
            expected = None
            if k + 1 < len(found) and found[k + 1][0] == "text":
                expected = [l.rstrip() for l in found[k + 1][1].splitlines() if l.strip()]
            want_code = 0
            m = re.match(r"# exit (\d+)$", first)
            if m:
                want_code = int(m.group(1))
            t0 = time.time()
            block_env = env
            if "build/bin/launch " in text and "--dry-run" not in text:
                block_env = dict(env, LCM_DEFAULT_URL=free_url())
            if first == "# runs until Ctrl-C":
                p = start(text, root, block_env)
                time.sleep(BACKGROUND_S)
                alive = p.poll() is None
                code, out = stop(p)
                ok = alive
                what = "still running after %.0f s, stopped by SIGINT (exit %s)" % (BACKGROUND_S, code)
                if not alive:
                    what = "ended before Ctrl-C with exit %s" % code
            else:
                try:
                    r = subprocess.run(["bash", "-c", text], cwd=root, env=block_env, capture_output=True, text=True,
                                       timeout=30, start_new_session=True)
                    code, out = r.returncode, r.stdout + r.stderr
                except subprocess.TimeoutExpired as e:
                    code, out = -1, "timeout\n%s" % (e.output or "")
                ok = code == want_code
                what = "exit %s (want %s)" % (code, want_code)
            missing = [l for l in (expected or []) if l not in out]
            if missing:
                ok = False
                what += "; expected output not found: %r" % missing
            print("%s line %d: %s, %.1f s" % ("ok  " if ok else "FAIL", line, what, time.time() - t0))
            if not ok:
                failures.append("line %d: %s\n--- block:\n%s--- output:\n%s" % (line, what, text, out[-3000:]))
        print("%d sh blocks run, %d failed" % (ran, len(failures)))
    finally:
        if driver is not None:
            stop(driver)
        code, out = stop(robot, 20)
        if code != 0:
            failures.append("launch exited %s at the end:\n%s" % (code, out[-3000:]))
        shutil.rmtree(root, ignore_errors=True)
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
