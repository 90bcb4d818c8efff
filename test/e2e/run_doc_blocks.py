#!/usr/bin/env python3
"""Runs every ```sh block of a Markdown guide, as a user would paste it.

The blocks run with bash from a scratch folder that looks like the repository
root (config/, docs/, python/, scripts/, test/ and build/bin, build/share linked to this build),
with LCM_DEFAULT_URL set to a bus of this run's own, next to a running
turret_bot (launch config/turret_bot.launch.yaml, with j2 driven by turret-cmd).

Conventions in the guide (a block's leading `#` lines are its directives):
  * `# runs until Ctrl-C`: the block is started in the background, must still
    run after a few seconds, and is then stopped with SIGINT (as Ctrl-C would);
  * `# exit N`: the block must exit with N (default 0);
  * a block that starts a whole robot (`build/bin/launch FILE` without
    --dry-run; with --robots N, the robots r0 .. rN-1) runs on a bus of its own, not next to the running turret_bot
    (one robot per bus). Started with `# runs until Ctrl-C`, that robot stays
    up for the rest of its section (up to the next heading): the runner waits
    until `cmctl list` shows its controllers running, the section's next
    blocks run on its bus, and it is stopped with SIGINT at the section's end;
  * a ```text block right after a ```sh block is expected output: each of its
    lines must appear in what the block printed;
  * `# figures vary from run to run`: numbers (goal ids, measured errors)
    are not compared, the rest of each expected line is.
Exit code 0 when every block behaved; 1 with one line per failure otherwise.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench"))
from lcm_bench.ports import lcm_url  # noqa: E402  (the benchmarks' port picker)

BACKGROUND_S = 3.0


def blocks(markdown):
    """[(lang, text, line)] of the fenced blocks."""
    out = []
    for m in re.finditer(r"^```(\w*)\n(.*?)^```\s*$", markdown, re.M | re.S):
        out.append((m.group(1), m.group(2), markdown.count("\n", 0, m.start()) + 1))
    return out


def heading_lines(markdown):
    """Line numbers (from 1) of the Markdown headings outside fenced blocks."""
    out, fenced = [], False
    for n, line in enumerate(markdown.splitlines(), 1):
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and re.match(r"#{1,6} ", line):
            out.append(n)
    return out


def contents_problems(markdown):
    """What a `## Contents` list misses or links wrongly: it links every other `## ` heading by its GitHub anchor."""
    sections, fenced = [], False
    for line in markdown.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and line.startswith("## "):
            sections.append(line[3:].strip())
    if "Contents" not in sections:
        return []
    body = markdown.split("## Contents", 1)[1].split("\n## ", 1)[0]
    links = re.findall(r"\]\(#([^)]+)\)", body)
    anchors = {h: re.sub(r"[^\w\- ]", "", h.lower()).replace(" ", "-") for h in sections if h != "Contents"}
    return (["## Contents does not link '## %s' (#%s)" % (h, a) for h, a in anchors.items() if a not in links]
            + ["## Contents links #%s, which no heading has" % a for a in links if a not in anchors.values()])


def directives(text):
    """The leading `#` comment lines of a block, stripped."""
    out = []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        out.append(line.strip())
    return out


def without_numbers(text):
    return re.sub(r"-?\d+(\.\d+)?([eE][-+]?\d+)?", "0", text)


def wait_controllers_running(root, env, timeout_s=40, namespaces=("",)):
    """True once `cmctl list` on env's bus shows controllers, all running ("active" as ROS 2 says it for a robot
    from ROS 2's files), in each namespace."""
    deadline = time.time() + timeout_s
    left = list(namespaces)
    while left and time.time() < deadline:
        ns = left[0]
        r = subprocess.run(["build/bin/cmctl", "list"] + (["--namespace", ns] if ns else []), cwd=root, env=env,
                           capture_output=True, text=True)
        states = [l.split()[2] for l in r.stdout.splitlines()[1:] if len(l.split()) >= 3 and not l.startswith("hardware:")]
        if r.returncode == 0 and states and all(st in ("running", "active") for st in states):
            left.pop(0)
        else:
            time.sleep(0.5)
    return not left


def free_url():
    """An LCM URL on a port no running test uses, as bench/run picks them (below the ephemeral range)."""
    return lcm_url()


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
        markdown = f.read()
    found = blocks(markdown)
    headings = heading_lines(markdown)
    root = tempfile.mkdtemp(prefix="lcm_control_docs_")
    os.makedirs(os.path.join(root, "build"))
    for name in ("config", "docs", "python", "scripts", "test"):
        os.symlink(os.path.join(args.source_dir, name), os.path.join(root, name))
    os.symlink(args.bin_dir, os.path.join(root, "build", "bin"))
    os.symlink(os.path.join(os.path.dirname(args.bin_dir), "share"), os.path.join(root, "build", "share"))
    env = dict(os.environ, LCM_DEFAULT_URL=free_url())
    print("guide %s: %d blocks, bus %s, in %s" % (args.guide, len(found), env["LCM_DEFAULT_URL"], root))

    failures = contents_problems(markdown)
    robot = start("build/bin/launch config/turret_bot.launch.yaml", root, env)
    driver = None
    section_robot = None  # (process, env, line of the section's end) of a robot kept up for its section
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
            if section_robot and line > section_robot[2]:
                code, _ = stop(section_robot[0])
                print("     section robot stopped by SIGINT (exit %s)" % code)
                section_robot = None
            ran += 1
            flags = directives(text)
            expected = None
            if k + 1 < len(found) and found[k + 1][0] == "text":
                expected = [l.rstrip() for l in found[k + 1][1].splitlines() if l.strip()]
            want_code = 0
            for d in flags:
                m = re.match(r"# exit (\d+)$", d)
                if m:
                    want_code = int(m.group(1))
            t0 = time.time()
            block_env = section_robot[1] if section_robot else env
            starts_robot = "build/bin/launch " in text and "--dry-run" not in text
            if starts_robot:
                block_env = dict(env, LCM_DEFAULT_URL=free_url())
            if "# runs until Ctrl-C" in flags:
                p = start(text, root, block_env)
                time.sleep(BACKGROUND_S)
                alive = p.poll() is None
                ok = alive
                if alive and starts_robot and section_robot is None:
                    m = re.search(r"--robots (\d+)", text)  # launch --robots N: namespaces r0 .. rN-1
                    ok = wait_controllers_running(root, block_env,
                                                  namespaces=["r%d" % k for k in range(int(m.group(1)))] if m else [""])
                    end = min([h for h in headings if h > line] or [len(markdown.splitlines()) + 1])
                    section_robot = (p, block_env, end)
                    what = "robot up%s, kept for its section (to line %d)" % (
                        "" if ok else " but its controllers did not all run within 40 s", end)
                    out = ""
                else:
                    code, out = stop(p)
                    what = "still running after %.0f s, stopped by SIGINT (exit %s)" % (BACKGROUND_S, code)
                if not alive:
                    code, out = stop(p)
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
            if "# figures vary from run to run" in flags:
                missing = [l for l in (expected or []) if without_numbers(l) not in without_numbers(out)]
            else:
                missing = [l for l in (expected or []) if l not in out]
            if missing:
                ok = False
                what += "; expected output not found: %r" % missing
            print("%s line %d: %s, %.1f s" % ("ok  " if ok else "FAIL", line, what, time.time() - t0))
            if not ok:
                failures.append("line %d: %s\n--- block:\n%s--- output:\n%s" % (line, what, text, out[-3000:]))
        print("%d sh blocks run, %d failed" % (ran, len(failures)))
    finally:
        if section_robot:
            stop(section_robot[0])
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
