"""``shaketable risk --figure`` with several panels: one legend for the figure, one range
of annual rates on every panel with the whole hazard curve inside it, and the integrand's
legend entry saying that it is a rate drawn on the rate axis."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from shaketable.cli import main


def _sweep_folder(path):
    """A finished sweep written by hand: two blocks, 16 runs each on 16 PGV levels, the
    weak block overturning from 0.3 m/s on (one reversal so that the fit is not separated),
    the strong one from 0.7 m/s on."""
    pgv = np.geomspace(0.1, 1.5, 16)
    rows = []
    for block, edge in (("weak 20 x 5 in", 0.3), ("strong 40 x 10 in", 0.7)):
        fell = pgv > edge
        first = int(np.flatnonzero(fell)[0])
        fell[first], fell[first - 1] = False, True
        for k in range(16):
            rows.append({"run": len(rows), "record": f"r{k % 4}", "block": block,
                         "cor [-]": 0.9, "status": "completed", "pgv [m/s]": pgv[k],
                         "overturned": bool(fell[k])})
    path.mkdir()
    pd.DataFrame(rows).to_csv(path / "results.csv", index=False)
    (path / "manifest.json").write_text(json.dumps({"format": "csv", "n_chunks": 1,
                                                   "n_runs": len(rows)}))
    return path


def test_a_risk_figure_of_several_panels_has_one_legend_and_one_rate_range(tmp_path,
                                                                           monkeypatch):
    import shaketable.plots.base as base
    from shaketable.commands.risk import hazard_path
    from shaketable.sweeps.risk import read_hazard_curve

    drawn = []
    monkeypatch.setattr(base, "save", lambda figure, target: drawn.append(figure))
    folder = _sweep_folder(tmp_path / "sweep")
    assert main(["risk", str(folder), "--hazard", "example", "--figure",
                 str(tmp_path / "risk.png")]) == 0
    (figure,) = drawn
    panels = [axis for axis in figure.axes if hasattr(axis, "fragility_axis")]
    assert len(panels) == 2
    legends = [axis.get_legend() for axis in figure.axes if axis.get_legend() is not None]
    assert len(legends) + len(figure.legends) == 1
    limits = {axis.get_ylim() for axis in panels}
    assert len(limits) == 1, limits
    rates = np.asarray(read_hazard_curve(hazard_path("example")).rate)
    (low, high), = limits
    assert low < rates.min() and rates.max() < high   # the whole hazard curve is drawn
    labels = [text.get_text() for text in legends[0].get_texts()]
    integrand = [label for label in labels if "integrand" in label]
    assert integrand and "rate" in integrand[0] and "left axis" in integrand[0], labels
    assert len(labels) == len(set(labels))
    # each panel's own fit is in its title, since the legend is shared
    for axis in panels:
        assert "median" in axis.get_title() and "β" in axis.get_title()
    import matplotlib.pyplot as plt

    plt.close(figure)
