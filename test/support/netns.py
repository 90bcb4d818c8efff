"""What the tests that build hosts out of network namespaces share: the skip
convention (exit 77, which ctest reads through SKIP_RETURN_CODE) and a
bounded run of a command."""
import subprocess
import sys

SKIP = 77


def skip(why):
    print(f"SKIPPED: {why}")
    sys.exit(SKIP)


def run(*argv, check=True):
    return subprocess.run(argv, check=check, capture_output=True, text=True, timeout=30)
