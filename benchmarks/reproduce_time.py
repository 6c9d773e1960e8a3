"""``shaketable reproduce --all``: wall and CPU time, and the CPU of
each scene, from which the two-process wall time on two free cores follows.

Runs the whole reproduction (warm numba cache) into a temporary folder (or ``--keep``)
as the command does, timing wall clock and CPU (``resource.getrusage`` of this process
and its worker processes), the CPU of each worker process (start-up included) and of
this process, and from them the wall time on two quiet cores: the busiest worker plus
this process's own CPU (imports, scheduling, assembling the report), whatever else a
shared machine runs. With ``--per-scene``, each scene alone in this process, CPU seconds
each, and the time two workers need when they take the scenes in the pool's order
(longest expected first, ``shaketable.scenes.catalog.SCENE_CPU``), each the next one when
free. Target: <= 30 s wall on 2 cores.

    python3 benchmarks/reproduce_time.py [--per-scene] [--keep DIR]

A faster reproduction must write the same files: ``--keep`` a run before and after, then
``python3 benchmarks/compare_reproduce.py BEFORE AFTER``.
"""

from __future__ import annotations

import argparse
import heapq
import json
import os
import resource
import tempfile
import time
from pathlib import Path


def cpu_with_children() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-scene", action="store_true",
                        help="also time each scene alone (one more full pass, in-process)")
    parser.add_argument("--keep", default=None, help="write the reproduction here, not in a "
                        "temporary folder (to compare it with another)")
    args = parser.parse_args(argv)
    imports = time.process_time()

    from shaketable.reproduce import WORKER_CPU, _scene_outcome, _worker_count, reproduce
    from shaketable.scenes.catalog import expected_cost, scene_names

    names = list(scene_names())
    imports = time.process_time() - imports
    out: dict = {"scenes": len(names), "processes": _worker_count(len(names))}
    with tempfile.TemporaryDirectory() as folder:
        wall, cpu, own = time.perf_counter(), cpu_with_children(), time.process_time()
        reproduce(names, out=Path(args.keep or Path(folder) / "all"), progress=False)
        out["wall [s]"] = time.perf_counter() - wall
        out["CPU, with the worker processes [s]"] = cpu_with_children() - cpu
        own = time.process_time() - own + imports
        out["CPU of this process, imports included [s]"] = own
        workers = sorted(WORKER_CPU.values(), reverse=True)
        out["CPU of each worker process, start-up included [s]"] = workers
        if workers:
            out["wall on two quiet cores (busiest worker + this process) [s]"] = \
                workers[0] + own
        if args.per_scene:
            seconds = {}
            for name in names:
                start = time.process_time()
                _scene_outcome(name, Path(folder) / "one")
                seconds[name] = time.process_time() - start
            workers = [0.0] * 2
            heapq.heapify(workers)
            # the pool's order (longest expected first); each takes the next when free
            for name in sorted(names, key=expected_cost, reverse=True):
                heapq.heappush(workers, heapq.heappop(workers) + seconds[name])
            out["CPU of the scenes, one process [s]"] = sum(seconds.values())
            out["two free cores, scenes as the pool schedules them [s]"] = max(workers)
            out["slowest scenes [s]"] = dict(sorted(seconds.items(), key=lambda item:
                                                    -item[1])[:8])
    out["target wall [s]"] = 30
    out["load average"] = os.getloadavg()
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
