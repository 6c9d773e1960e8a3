"""What the README's test command costs: wall time and CPU time (user + system).

Runs ``python3 -m pytest -q -n 2`` (the README's command; extra arguments are passed on)
from the repository under ``/usr/bin/time -v``, which counts the CPU time of pytest, its
xdist workers and every subprocess they wait for. ``--cold`` points ``NUMBA_CACHE_DIR``
at an empty folder, as on a fresh machine (numba then compiles the engines once, about
20 s of CPU); by default the cache the package uses is kept (a second run), and so is
Python's bytecode (``PYTHONDONTWRITEBYTECODE`` is removed unless ``--no-bytecode``).
Printed: the wall and CPU times, the load average before and after (CPU time is the figure a busy
machine changes least: other work lengthens the wall time, much less the CPU time), the
number of cores, and pytest's last lines, with the tests and the test files that used the
most CPU (``--cpu-durations``, tests/conftest.py).

    python3 benchmarks/suite_cost.py [--cold] [--no-bytecode] [--top 15] [--list FILE]
                                     [--compiles FILE] [-- PYTEST ARGUMENTS]

``--compiles FILE`` lists every numba compile in the test processes (tests/conftest.py: the
test that asked for it, its CPU time and argument types; a function numba loads from its
cache is no compile): in a cold run, what the engines' warm-up leaves to the tests.

Target: at most 300 s of CPU on 2 cores.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[1]


def _time_field(report: str, label: str) -> str:
    match = re.search(rf"^\s*{re.escape(label)}: (.+)$", report, flags=re.MULTILINE)
    return match.group(1).strip() if match else "?"


def _wall_seconds(text: str) -> float:
    parts = [float(part) for part in text.split(":")]
    seconds = 0.0
    for part in parts:
        seconds = 60 * seconds + part
    return seconds


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cold", action="store_true",
                        help="an empty numba cache (a fresh machine: the engines compile)")
    parser.add_argument("--no-bytecode", action="store_true",
                        help="keep PYTHONDONTWRITEBYTECODE from the environment (by default "
                             "it is removed: Python then writes bytecode, and a second run "
                             "reads it)")
    parser.add_argument("--top", type=int, default=15,
                        help="list the tests that used the most CPU time (default 15)")
    parser.add_argument("--list", metavar="FILE",
                        help="write every test's CPU time to FILE (seconds, tab, test id; "
                             "most first), to compare two runs test by test")
    parser.add_argument("--compiles", metavar="FILE",
                        help="write every numba compile in the test processes to FILE (CPU "
                             "seconds, depth, function, argument types, test; most first)")
    parser.add_argument("pytest_arguments", nargs="*",
                        help="more pytest arguments (after --), e.g. -p no:randomly")
    args = parser.parse_args(argv)
    time = shutil.which("time", path="/usr/bin") or "/usr/bin/time"
    if not os.path.exists(time):
        print("needs GNU time (/usr/bin/time)", file=sys.stderr)
        return 2
    environment = dict(os.environ)
    # Python's default: modules' bytecode written to __pycache__ and read back by every later
    # process, as on a user's machine. With PYTHONDONTWRITEBYTECODE set and no __pycache__
    # yet (a fresh checkout), every worker and subprocess compiles the package's and the
    # tests' sources again (and pytest rewrites the tests' asserts again): about 3 s of CPU
    # per worker and 0.25 s per subprocess importing shaketable.
    if not args.no_bytecode:
        environment.pop("PYTHONDONTWRITEBYTECODE", None)
    bytecode = "not written" if environment.get("PYTHONDONTWRITEBYTECODE") else "kept"
    scratch = tempfile.mkdtemp(prefix="suite-cost-")
    if args.cold:
        environment["NUMBA_CACHE_DIR"] = os.path.join(scratch, "numba")
    if args.list:
        environment["SHAKETABLE_CPU_LIST"] = os.path.abspath(args.list)
    if args.compiles:
        environment["SHAKETABLE_COMPILE_LIST"] = os.path.abspath(args.compiles)
    log = os.path.join(scratch, "time.txt")
    command = [time, "-v", "-o", log, sys.executable, "-m", "pytest", "-q", "-n", "2",
               "-p", "no:cacheprovider", f"--cpu-durations={args.top}", *args.pytest_arguments]
    load_before = os.getloadavg()
    done = subprocess.run(command, cwd=REPOSITORY, env=environment, capture_output=True,
                          text=True)
    load_after = os.getloadavg()
    report = Path(log).read_text()
    shutil.rmtree(scratch, ignore_errors=True)
    user = float(_time_field(report, "User time (seconds)"))
    system = float(_time_field(report, "System time (seconds)"))
    wall = _wall_seconds(_time_field(report, "Elapsed (wall clock) time (h:mm:ss or m:ss)"))
    lines = done.stdout.splitlines()
    start = next((i for i, line in enumerate(lines) if "using the most CPU" in line),
                 max(0, len(lines) - 10))
    if done.returncode == 0:   # the progress dots say nothing; the tables do
        lines = [line for line in lines[:start] if "random order" in line] + lines[start:]
    print("\n".join(lines))   # a failing run keeps its tracebacks
    print(f"\ncommand: {' '.join(command[3:])}  (numba cache: {'empty' if args.cold else 'kept'}; "
          f"bytecode: {bytecode})")
    print(f"cores: {os.cpu_count()}, load average (1 min) before {load_before[0]:.1f}, "
          f"after {load_after[0]:.1f}")
    print(f"wall {wall:.0f} s ({wall / 60:.1f} min); CPU {user + system:.0f} s "
          f"(user {user:.0f} s, system {system:.0f} s); exit status {done.returncode}")
    return done.returncode


if __name__ == "__main__":
    sys.exit(main())
