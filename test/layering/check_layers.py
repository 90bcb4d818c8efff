#!/usr/bin/env python3
"""The libraries' layering as docs/ARCHITECTURE.md states it, checked against the includes.

Reads the table "Libraries, lowest first" (folder, target, uses) and every source file under a library's folder
(the longest folder that holds it). An include of another library's header ("bus/bus.hpp", or "lcm_control/..."
for the generated types) must name a library this one uses, directly or through those it uses; a library never
includes a test, bench or program header. Exits 1 naming each file:line and the include that breaks the table.

  check_layers.py --source-dir DIR [--pretend FILE:HEADER]...

--pretend adds an include to a file as if it were written there (the test that the check fails on a back include).
"""
import argparse
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def read_table(path):
    """{folder: (target, [targets it uses])}, from the table under '## Libraries, lowest first'."""
    libs = {}
    in_section = False
    with open(path) as f:
        for line in f:
            if line.startswith("## "):
                in_section = line.strip() == "## Libraries, lowest first"
                continue
            if not in_section or not line.startswith("| `"):
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            folder = cells[0].strip("`").rstrip("/")
            target = cells[1].strip("`")
            uses = re.sub(r"\([^)]*\)", "", cells[-1])
            libs[folder] = (target, [u.strip() for u in uses.split(",") if u.strip() and u.strip() not in "—-"])
    if not libs:
        raise SystemExit(f"check_layers: no library table in {path} (the heading '## Libraries, lowest first')")
    return libs


def closure(libs):
    """{target: every target it may include, itself too}."""
    uses = {t: set(u) for t, u in libs.values()}
    allowed = {}
    for t in uses:
        seen, todo = {t}, list(uses[t])
        while todo:
            u = todo.pop()
            if u not in uses:
                raise SystemExit(f"check_layers: '{t}' uses '{u}', which is no library of the table")
            if u not in seen:
                seen.add(u)
                todo.extend(uses[u])
        allowed[t] = seen
    return allowed


def owner(path, folders):
    """The library folder that holds `path` (the longest match), or None."""
    best = None
    for folder in folders:
        if (path == folder or path.startswith(folder + "/")) and (best is None or len(folder) > len(best)):
            best = folder
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--pretend", action="append", default=[])
    a = ap.parse_args()
    root = os.path.abspath(a.source_dir)
    libs = read_table(os.path.join(root, "docs/ARCHITECTURE.md"))
    allowed = closure(libs)
    folders = list(libs)
    target_of = {folder: t for folder, (t, _) in libs.items()}
    foreign = ("test/", "bench/", "tools/", "dashboard/", "sim_server/", "controller_manager/")
    pretend = {}
    for p in a.pretend:
        f, h = p.split(":", 1)
        pretend.setdefault(f, []).append(h)
    problems, files = [], 0
    for folder in folders:
        for dirpath, dirnames, names in os.walk(os.path.join(root, folder)):
            dirnames[:] = [d for d in dirnames if d not in ("node_modules", "page")]
            for name in sorted(names):
                if not name.endswith((".hpp", ".cpp", ".h")):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, name), root)
                mine = owner(rel, folders)
                if mine != folder:
                    continue  # a nested library's file: checked as that library's
                if name == "main.cpp":
                    continue  # a program's (sim_server, controller_manager, dashboard): it uses what it links
                files += 1
                with open(os.path.join(root, rel), errors="replace") as f:
                    lines = [(n, m.group(1)) for n, text in enumerate(f, 1) if (m := INCLUDE.match(text))]
                lines += [(0, h) for h in pretend.get(rel, [])]
                for n, header in lines:
                    if header.startswith("lcm_control/"):
                        theirs = "lcmtypes"
                    else:
                        theirs = owner(header, folders)
                    if theirs is None:
                        if header.startswith(foreign) or header.startswith(("test/", "bench/")):
                            problems.append(f"{rel}:{n}: includes \"{header}\": a library includes no test, bench or "
                                            f"program header")
                        continue  # a header of its own folder written relative to it, or a system one
                    t, u = target_of[mine], target_of[theirs]
                    if u not in allowed[t]:
                        problems.append(f"{rel}:{n}: includes \"{header}\" of library '{u}', which '{t}' does not use "
                                        f"(docs/ARCHITECTURE.md: '{t}' uses {', '.join(sorted(allowed[t] - {t})) or 'nothing'})")
    for p in problems:
        print(f"check_layers: {p}", file=sys.stderr)
    print(f"check_layers: {files} files of {len(folders)} libraries read, {len(problems)} include(s) against the table")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
