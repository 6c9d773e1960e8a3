"""Figure text spells Greek letters as Greek: a reader sees θ/α, ω / p and
a / (g tan α) on every figure, as on the Calcomp and teaching figures, never "theta",
"alpha" or "omega" written out.

Only what is drawn is checked (axis labels, titles, legends, colorbar labels, annotations,
tick labels): DataFrame columns and CSV headers keep their ASCII names (data contracts such
as ``"max_theta_ratio [-]"`` and ``"from a/(g tan alpha) [-]"``).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd
import pytest

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.plots import sweeps as sweep_plots
from shaketable.plots.base import pyplot
from tests.plots.test_calcomp import svg_text

ROOT = Path(__file__).resolve().parents[2]

#: Greek letters (and the square root) spelt in ASCII, as whole words: "mu_s" and "theta0"
#: count, "pitch", "alphabet" or "Mutual" do not.
ASCII_GREEK = re.compile(r"(?i)(?<![a-z])(alpha|beta|gamma|delta|zeta|theta|lambda|mu|nu|xi"
                         r"|rho|sigma|tau|phi|omega|sqrt)(?![a-z])")


def figure_texts(fig) -> list[str]:
    """Every visible, non-empty text of the figure once drawn (ticks included)."""
    fig.canvas.draw()
    return [text.get_text() for text in fig.findobj(matplotlib.text.Text)
            if text.get_visible() and text.get_text()]


def ascii_greek(fig) -> list[str]:
    """The texts of ``fig`` that spell a Greek letter in ASCII."""
    return sorted({text for text in figure_texts(fig) if ASCII_GREEK.search(text)})


def test_the_check_finds_ascii_greek_in_labels_colorbars_and_legends():
    # the check must be able to fail: ASCII in an axis label, a colorbar label and a legend
    plt = pyplot()
    fig, ax = plt.subplots()
    image = ax.pcolormesh(np.arange(4.0).reshape(2, 2))
    ax.set_xlabel("omega / p [-]")
    fig.colorbar(image, ax=ax).set_label("max |theta| / alpha [-]")
    ax.plot([0, 1], [0, 1], label="mu_s = 0.2")
    ax.legend()
    ax.set_title("pitch phases, alphabetical, ω / p")  # no Greek word spelt out here
    try:
        assert ascii_greek(fig) == ["max |theta| / alpha [-]", "mu_s = 0.2", "omega / p [-]"]
    finally:
        plt.close(fig)


def test_overturning_spectrum_figure_is_in_greek():
    from shaketable.studies.overturning_spectrum import overturning_spectrum

    # alpha = 0.25 rad, p = 2 rad/s: the block of Zhang & Makris (2001)
    block = Block.from_slenderness(3 * G / 16, 0.25)
    # a coarse scan and bisection (the default's 0.005 and 1e-8): only the labels are checked
    spectrum = overturning_spectrum(block, ["half-sine"], [1, 2], scan_step=0.05, tolerance=1e-4)
    # the data keep their ASCII column names; the figure does not
    assert "from a/(g tan alpha) [-]" in spectrum.bands and "omega/p [-]" in spectrum.bands
    ax = spectrum.plot()
    assert ascii_greek(ax.figure) == []
    text = svg_text(ax.figure)
    for expected in ("ω / p [-]", "a / (g tan α) [-]", "α = 0.25 rad", "p = 2 rad/s"):
        assert expected in text


def _map_table() -> pd.DataFrame:
    """A sweep table of 2 widths x 3 aspect ratios, one record and COR, one overturned run."""
    rows = []
    for width in (0.1, 0.2):
        for aspect, ratio in ((3.0, 0.4), (5.0, 0.7), (7.0, math.nan)):
            height = width * aspect
            R = math.hypot(width, height) / 2
            rows.append({"record": "test record", "seed": math.nan, "cor [-]": 0.9,
                         "block": f"{height:g}x{width:g}m", "block_width [m]": width,
                         "block_height [m]": height, "aspect_ratio [-]": aspect,
                         "alpha [rad]": math.atan(1 / aspect), "R [m]": R,
                         "p [rad/s]": math.sqrt(3 * G / (4 * R)), "pga [g]": 0.3,
                         "max_theta_ratio [-]": ratio * width / 0.1,
                         "overturned": math.isnan(ratio)})
    return pd.DataFrame(rows)


def _fragility_table() -> pd.DataFrame:
    """Four records at four PGA levels: record k overturns from level k on."""
    levels = (0.2, 0.4, 0.6, 0.8)
    rows = [{"record": f"record {k}", "seed": math.nan, "cor [-]": 0.9, "block": "1x0.25m",
             "pga [g]": pga, "overturned": pga > 0.1 + 0.2 * k}
            for k in range(4) for pga in levels]
    return pd.DataFrame(rows)


def _pitch_table() -> pd.DataFrame:
    rows = [{"record": "test record", "seed": math.nan, "cor [-]": 0.9, "block": "1x0.25m",
             "pga [g]": pga, "pitch_phase [rad]": phase,
             "max_theta_ratio [-]": math.nan if pga > 0.5 and phase > 3 else 0.2 + pga,
             "overturned": bool(pga > 0.5 and phase > 3)}
            for pga in (0.3, 0.6) for phase in np.linspace(0, 2 * np.pi, 4, endpoint=False)]
    return pd.DataFrame(rows)


@pytest.mark.parametrize("figure", ["map", "map over alpha", "rocking spectrum", "fragility",
                                    "pitch spread"])
def test_sweep_figures_are_in_greek(figure):
    plt = pyplot()
    if figure == "map":
        ax = sweep_plots.overturning_map(_map_table())
        colorbar = ax.figure.axes[-1]
        assert colorbar.get_ylabel() == "max |θ|/α [-]  (red, F: overturned)"
    elif figure == "map over alpha":
        ax = sweep_plots.overturning_map(_map_table(), x="alpha")
        assert ax.get_xlabel() == "α [rad]"
    elif figure == "rocking spectrum":
        ax = sweep_plots.rocking_spectrum(_map_table())
        assert ax.get_ylabel() == "max |θ|/α [-]"
        assert "p = √(3g/4R)" in ax.get_xlabel()
    elif figure == "fragility":
        ax = sweep_plots.fragility_curve(_fragility_table())
        assert any("β" in text.get_text() for text in ax.get_legend().get_texts())
    else:
        ax = sweep_plots.pitch_phase_spread(_pitch_table())
    try:
        assert ascii_greek(ax.figure) == []
    finally:
        plt.close("all")


def test_work_precision_figure_is_in_greek():
    from shaketable.plots.bench import work_precision_figure

    frame = pd.read_csv(ROOT / "benchmarks" / "work_precision.csv")
    fig = work_precision_figure(frame, cases=["free-rocking", "stiff-rods"], columns=2)
    try:
        assert ascii_greek(fig) == []
        assert "max |θ| (solid; not drawn where the case fixes it)" in figure_texts(fig)
    finally:
        pyplot().close(fig)


def test_calibration_and_sliding_figures_are_in_greek():
    import shaketable as st
    from shaketable.calibration.fit import calibrate
    from shaketable.calibration.free_rocking import virtual_free_rocking_record
    from shaketable.plots.sliding import sliding_vs_rocking_figure
    from shaketable.studies.sliding import teaching_pair

    block = st.Block.parse("30x6in")
    record, _ = virtual_free_rocking_record(block, 0.925, 0.5 * block.alpha, before=0.5,
                                            duration=6.0)
    calibration = calibrate(record, block)
    fig = calibration.plot()
    try:
        assert ascii_greek(fig) == []
        assert any(text.startswith("exact, fitted R = ") and ", α = " in text
                   for text in figure_texts(fig))
    finally:
        pyplot().close(fig)
    fig = sliding_vs_rocking_figure(*teaching_pair())
    try:
        assert ascii_greek(fig) == []
        assert fig.axes[2].get_ylabel() == "θ/α [-]"
    finally:
        pyplot().close(fig)
