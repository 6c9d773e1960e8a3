"""Redraw the sweep figures of ``docs/sweeps.md`` from the bundled sweep specs.

Run from the repository: ``python docs/tools/sweep_figures.py`` (about a minute on two
cores). Each bundled sweep runs into a temporary folder; the figures the docs show are
written to ``docs/figures/`` (sweep_map.png, sweep_spectrum.png, sweep_fragility.png,
sweep_pitch.png), nothing else is kept.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import shaketable.scenes.catalog as catalog
from shaketable.plots.base import pyplot, save
from shaketable.plots.sweeps import (
    fragility_curve,
    overturning_map,
    pitch_phase_spread,
    rocking_spectrum,
)
from shaketable.sweeps.execute import run_sweep
from shaketable.sweeps.spec import load_spec

FIGURES = Path(__file__).resolve().parents[1] / "figures"


def main() -> None:
    plt = pyplot()
    with tempfile.TemporaryDirectory() as scratch:
        def table(name):
            spec = load_spec(catalog.resolve_sweep_path(name))
            return run_sweep(spec, Path(scratch) / name, progress=False).table

        pacoima = table("pacoima-overturning-map")
        figure, axes = plt.subplots(1, 2, figsize=(13, 5), constrained_layout=True)
        for axis, record in zip(axes, ("pacoima-dam-s16e", "pacoima-dam-s74w")):
            overturning_map(pacoima, record=record, cor=0.9, ax=axis, length_unit="ft")
            axis.set_title(f"{record}, COR 0.9", fontsize=9)
        save(figure, FIGURES / "sweep_map.png")
        figure, axis = plt.subplots(figsize=(8, 4.5), constrained_layout=True)
        rocking_spectrum(pacoima, record="pacoima-dam-s16e", cor=0.9, ax=axis)
        save(figure, FIGURES / "sweep_spectrum.png")

        figure, axis = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
        fragility_curve(table("artificial-fragility"), cor=0.9, ax=axis)
        save(figure, FIGURES / "sweep_fragility.png")

        pitch = table("pitch-phase-repeatability")
        figure, axis = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
        pitch_phase_spread(pitch, record="olive-view", ax=axis)
        save(figure, FIGURES / "sweep_pitch.png")
    print(f"wrote sweep_map.png, sweep_spectrum.png, sweep_fragility.png, sweep_pitch.png "
          f"in {FIGURES}")


if __name__ == "__main__":
    main()
