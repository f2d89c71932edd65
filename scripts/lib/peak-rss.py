#!/usr/bin/env python3
"""Runs a command and records its peak resident memory and its time.

    peak-rss.py LOG CMD [ARGS...]

Runs CMD, appends "<peak KiB> <CMD's file name> <wall seconds> <CPU seconds>" to LOG (the
peak: the largest resident set of CMD and of every process it waited for, getrusage's
RUSAGE_CHILDREN; the CPU seconds, user and system, of the same processes) and exits with CMD's
status. scripts/test.sh makes it cargo's runner for the test binaries, so each test
process's peak and time are known (docs/benchmarks.md, "The test command").
"""

import os
import resource
import subprocess
import sys
import time


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    log, cmd = sys.argv[1], sys.argv[2:]
    start = time.monotonic()
    status = subprocess.call(cmd)
    seconds = time.monotonic() - start
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = usage.ru_utime + usage.ru_stime
    with open(log, "a", encoding="utf-8") as f:
        f.write(f"{usage.ru_maxrss} {os.path.basename(cmd[0])} {seconds:.0f} {cpu:.0f}\n")
    return status if status >= 0 else 128 - status


if __name__ == "__main__":
    sys.exit(main())
