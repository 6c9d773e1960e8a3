"""``shaketable assess`` on the three bundled example objects: wall and CPU time of each.

Each object is assessed in this process (warm numba cache: run once before to compile the
planar engine) into a temporary folder, with its figures, as the command does. Target:
under a minute each on 2 cores.

    python3 benchmarks/assess_time.py [--repeat N]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from shaketable.assessment import assess
from shaketable.scenes.catalog import experiments_folder

EXAMPLES = ("shielding-block", "lab-cabinet", "transformer")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        for name in EXAMPLES:
            for repeat in range(args.repeat):
                wall, cpu = time.perf_counter(), time.process_time()
                result = assess(experiments_folder() / "assess" / f"{name}.toml",
                                Path(folder) / f"{name}-{repeat}")
                wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
                runs = len(result.runs)
                print(f"{name}: {wall:.1f} s wall, {cpu:.1f} s CPU ({runs} planar runs): "
                      f"{result.recommendation['choice']}")


if __name__ == "__main__":
    main()
