"""Full work-precision study: writes benchmarks/RESULTS.md, benchmarks/work_precision.csv
and docs/figures/work_precision.png (about 1-2 minutes on 2 cores).

    python3 benchmarks/work_precision.py [--quick]
"""

import argparse
import sys
from pathlib import Path

from shaketable.bench import run_study

ROOT = Path(__file__).resolve().parent.parent


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        description="Full work-precision study (the committed benchmarks/RESULTS.md, "
                    "benchmarks/work_precision.csv and docs/figures/work_precision.png).")
    parser.add_argument("--quick", action="store_true",
                        help="fewer settings, the long record cut to 20 s, 3 repeats "
                             "(not for the committed files)")
    args = parser.parse_args(argv)
    run_study(quick=args.quick, repeats=3 if args.quick else 5, out=ROOT / "benchmarks",
              figure_path=ROOT / "docs" / "figures" / "work_precision.png",
              markdown_figure="../docs/figures/work_precision.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
