"""
Artificial records: frequency content, PGA and strong-motion duration
======================================================================

The presets "A-1", "B-1" and "olive-view" of :data:`shaketable.ground.generators.PRESETS`
are SUBSTITUTES in the spirit of the records of Section 4.1 of the report, not
the originals (which are not available). This script draws, for seeds 0-2, the
acceleration with its 5-95 % Arias window, the 5 %-damped response spectrum and
the Fourier amplitude spectrum (:func:`shaketable.plots.ground.plot_artificial_presets`)
and prints the measures (:func:`shaketable.plots.ground.preset_measures`).

Run from anywhere::

    python examples/plot_artificial_presets.py [--out artificial_presets.png]

Without ``--out`` the figure is only drawn (and shown in the documentation's gallery).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from shaketable.plots.ground import plot_artificial_presets, preset_measures

SEEDS = (0, 1, 2)
PRESETS = ("A-1", "B-1", "olive-view")


def main(argv=None):
    parser = argparse.ArgumentParser(description="Draw the artificial presets and print their measures.")
    parser.add_argument("--out", type=Path, default=None,
                        help="PNG file to write (default: none, the figure is only drawn)")
    args = parser.parse_args(argv)
    table = preset_measures(PRESETS, SEEDS)
    with_columns = ["preset", "seed", "pga [g]", "D5-95 [s]", "t5 [s]", "t95 [s]",
                    "predominant frequency [Hz]"]
    print(table[with_columns].to_string(index=False, float_format=lambda x: f"{x:.2f}"))
    fig = plot_artificial_presets(PRESETS, SEEDS)
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.out, dpi=110)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
