"""Checks for the script tests (tests/*_tests.py): each check prints one line,
and a failed one is remembered; finish() prints the count and exits 1 if any
failed."""
import sys

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def finish(name):
    print(f"{name}: {len(failures)} failed")
    sys.exit(1 if failures else 0)
