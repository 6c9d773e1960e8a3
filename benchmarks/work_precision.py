"""Full work-precision study: writes benchmarks/RESULTS.md, benchmarks/work_precision.csv
and docs/figures/work_precision.png (about 1-2 minutes on 2 cores).

    python3 benchmarks/work_precision.py [--quick]
"""

import sys
from pathlib import Path

from shaketable.bench import run_study

ROOT = Path(__file__).resolve().parent.parent

if __name__ == "__main__":
    quick = "--quick" in sys.argv[1:]
    run_study(quick=quick, repeats=3 if quick else 5, out=ROOT / "benchmarks",
              figure_path=ROOT / "docs" / "figures" / "work_precision.png",
              markdown_figure="../docs/figures/work_precision.png")
