#!/usr/bin/env python3
"""Every flag the docs give one of our programs is a flag that program takes.

Scans README.md, docs/*.md and each program's own --help examples for commands
in code (fenced blocks and `inline code`): a line or `...` span whose command
is one of our programs (`build/bin/bus ...`, `bus ...`, after `VAR=value`s, a
pipe, `&&` or `;`), and checks each `--flag` and `-x` up to the end of that
command against the program's --help (for bus and cmctl, the subcommand's
--help and the program's own). Exit 0 when all are known; 1 with one line per
unknown flag: the file, the line, the program and the nearest flags it takes.
"""
import argparse
import difflib
import glob
import os
import re
import shlex
import subprocess
import sys

SEPARATORS = {"|", "||", "&&", ";", "&"}
FLAG = re.compile(r"^(--[A-Za-z][\w-]*|-[A-Za-z])(=.*)?$")
HELP_FLAG = re.compile(r"(?<![\w-])(--[A-Za-z][\w-]*|-[A-Za-z])(?![\w-])")


def programs(bin_dir):
    """Our programs: the executables of bin_dir that are not tests or benchmarks."""
    out = set()
    for path in glob.glob(os.path.join(bin_dir, "*")):
        name = os.path.basename(path)
        if os.access(path, os.X_OK) and os.path.isfile(path) and not re.search(r"_tests?$|^bench_|^reliability_", name):
            out.add(name)
    return out


class Helps:
    """The flags of `program [subcommand]`, read once from its --help."""

    def __init__(self, bin_dir):
        self.bin_dir, self.cache = bin_dir, {}

    def text(self, argv):
        key = tuple(argv)
        if key not in self.cache:
            r = subprocess.run([os.path.join(self.bin_dir, argv[0])] + argv[1:] + ["--help"], capture_output=True,
                               text=True, timeout=20)
            self.cache[key] = r.stdout + r.stderr if r.returncode == 0 else ""
        return self.cache[key]

    def subcommands(self, program):
        m = re.search(r"^Subcommands:\n((?:  .*\n?)*)", self.text([program]), re.M)
        names = re.findall(r"^  ([^ ,]+(?:, [^ ,]+)*)", m.group(1), re.M) if m else []
        return {n for line in names for n in line.split(", ")}

    def flags(self, program, sub):
        """The flags in the options of the --help (examples excluded: they are what is checked)."""
        texts = [self.text([program])] + ([self.text([program, sub])] if sub else [])
        out = set()
        for t in texts:
            options = t[t.find("Options:"):] if "Options:" in t else ""
            out |= set(HELP_FLAG.findall(options))
        return out


def code_lines(markdown):
    """(line number, text) of the commands in code: fenced block lines (continuations joined) and inline spans (which
    may run over a line break within a paragraph)."""
    out, fenced, pending, start, para, para_start = [], False, "", 0, [], 0

    def end_paragraph():
        text = " ".join(para)
        out.extend((para_start, span) for span in re.findall(r"`([^`]+)`", text))
        para.clear()

    for n, line in enumerate(markdown.splitlines(), 1):
        if line.lstrip().startswith("```"):
            end_paragraph()
            fenced = not fenced
            continue
        if fenced:
            if not pending:
                start = n
            if line.rstrip().endswith("\\"):
                pending += line.rstrip()[:-1] + " "
                continue
            out.append((start, pending + line))
            pending = ""
        elif not line.strip():
            end_paragraph()
        else:
            if not para:
                para_start = n
            para.append(line.strip())
    end_paragraph()
    return out


def words(text):
    text = text.split(" # ")[0] if not text.lstrip().startswith("#") else ""
    try:
        return shlex.split(text, posix=True)
    except ValueError:
        return text.split()


def commands(text, ours):
    """(program, [words after it]) for each of our programs a command line runs."""
    ws, out, k, at_start = words(text), [], 0, True
    while k < len(ws):
        w = ws[k]
        if w in SEPARATORS or w.startswith(("$(", "`")):
            at_start = True
        elif at_start and re.match(r"^[A-Za-z_]\w*=", w):
            pass  # VAR=value before the command
        elif at_start and w in ("sudo", "exec", "time", "nohup", "$"):
            pass
        elif at_start and os.path.basename(w) == "lcm-control" and k + 1 < len(ws) and ws[k + 1] in ours:
            pass  # the installed front command: its next word is the program
        else:
            name = os.path.basename(w)
            if (at_start or "/bin/" in w) and name in ours:
                rest = []
                for v in ws[k + 1:]:
                    if v in SEPARATORS or re.match(r"^[12]?>", v):
                        break
                    rest.append(v)
                out.append((name, rest))
                k += len(rest)
            at_start = False
        k += 1
    return out


def check(source, line, text, ours, helps, problems):
    """Adds to problems each flag of a command in `text` that its program does not take; the flags checked."""
    checked = 0
    for program, rest in commands(text, ours):
        subs = helps.subcommands(program)
        sub = next((w for w in rest if not w.startswith("-") and w in subs), "")
        known = helps.flags(program, sub)
        if not known:
            continue  # no --help to check against (not our kind of program)
        for w in rest:
            m = FLAG.match(w)
            if not m or re.match(r"^-\d", w):
                continue
            flag = m.group(1)
            checked += 1
            if flag not in known:
                near = difflib.get_close_matches(flag, sorted(known), n=3, cutoff=0.6)
                problems.append(f"{source}:{line}: {program}{' ' + sub if sub else ''} takes no {flag}"
                                f"{'; nearest: ' + ', '.join(near) if near else ''}  ({text.strip()})")
    return checked


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--bin-dir", required=True)
    ap.add_argument("--doc", action="append", default=[], help="check only these Markdown files (default: README.md "
                                                                 "and docs/*.md, and every program's --help examples)")
    args = ap.parse_args()
    ours, helps, problems = programs(args.bin_dir), Helps(args.bin_dir), []
    docs = args.doc or [os.path.join(args.source_dir, "README.md")] + sorted(
        glob.glob(os.path.join(args.source_dir, "docs", "*.md")))
    checked = 0
    for path in docs:
        with open(path, encoding="utf-8") as f:
            for line, text in code_lines(f.read()):
                checked += check(os.path.relpath(path, args.source_dir), line, text, ours, helps, problems)
    if not args.doc:
        for program in sorted(ours):
            help_text = helps.text([program])
            examples = help_text[help_text.find("Example"):] if "Example" in help_text else ""
            examples = examples[:examples.find("\nUsage:")] if "\nUsage:" in examples else examples
            for n, text in enumerate(re.sub(r"\\\n\s*", " ", examples).splitlines()[1:], 1):
                checked += check(f"{program} --help, example", n, text.strip(), ours, helps, problems)
    for p in problems:
        print(p)
    print(f"{checked} flags of {len(ours)} programs checked in {len(docs)} Markdown files"
          f"{'' if args.doc else ' and the programs’ --help examples'}: {len(problems)} unknown")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
