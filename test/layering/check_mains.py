#!/usr/bin/env python3
"""Every program's main() parses flags and calls one library function: no main() over 60 lines, and no source file
at the top of tools/lib/ (its code lives in folders by concern).

  check_mains.py --source-dir DIR [--limit 60]

Reads every .cpp outside test/, bench/ and build folders that defines `int main(`, counts the lines from `int main(`
to its closing brace, and exits 1 naming each main over the limit with its count.
"""
import argparse
import os
import re
import sys

SKIP = ("test/", "bench/", "build", ".git/", "third_party/")


def main_length(text):
    m = re.search(r"^int main\(", text, re.M)
    if not m:
        return None
    depth, start = 0, text.index("{", m.end())
    for j in range(start, len(text)):
        depth += {"{": 1, "}": -1}.get(text[j], 0)
        if depth == 0:
            return text[m.start():j + 1].count("\n") + 1
    raise SystemExit("check_mains: an unbalanced main()")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--limit", type=int, default=60)
    a = ap.parse_args()
    failures, counted = [], 0
    for root, dirs, files in os.walk(a.source_dir):
        rel_root = os.path.relpath(root, a.source_dir)
        dirs[:] = [d for d in dirs if not (os.path.join(rel_root, d) + "/").lstrip("./").startswith(SKIP)
                   and not d.startswith((".", "build"))]
        for name in files:
            rel = os.path.normpath(os.path.join(rel_root, name))
            if rel.startswith("tools/lib/") and os.path.dirname(rel) == "tools/lib" and name.endswith((".cpp", ".hpp")):
                failures.append(f"{rel}: a source file at the top of tools/lib/; put it in the folder of its concern")
            if not name.endswith(".cpp") or rel.startswith(SKIP):
                continue
            with open(os.path.join(root, name), errors="replace") as f:
                n = main_length(f.read())
            if n is None:
                continue
            counted += 1
            if n > a.limit:
                failures.append(f"{rel}: main() is {n} lines (over {a.limit}): move its policy into its library and "
                                f"call one function")
    print(f"check_mains: {counted} programs' main() counted")
    for line in failures:
        print(line)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
