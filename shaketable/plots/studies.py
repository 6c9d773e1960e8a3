"""Figures of the report's studies: Section 2 (Figs. 2.3-2.6, Section 4.3 (4)), Fig. 3.6
and the Section 3.7 (2) pitch repeatability.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.plots.base import place_legend, pyplot


def section_2_figure(frame, figure: str):
    """Figs. 2.3-2.6: the report's closed forms against the engine.

    Parameters
    ----------
    frame : pandas.DataFrame
        From :func:`shaketable.studies.section2.figure_2_3` (``figure="2.3"``),
        ``figure_2_4`` (``"2.4"``), ``figure_2_5`` (``"2.5"``) or ``figure_2_6``
        (``"2.6"``).
    figure : str

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    fig, axis = plt.subplots(figsize=(6.5, 4.5))
    if figure == "2.3":
        from matplotlib.lines import Line2D

        # the exact curve wide and pale, Eq. 2-5 dashed on top: the two nearly coincide and
        # each must stay visible; one legend entry per block (colour) and per curve (style)
        handles = []
        for (name, group), color in zip(frame.groupby("block", sort=False),
                                        plt.rcParams["axes.prop_cycle"].by_key()["color"]):
            axis.plot(group["theta0/alpha [-]"], group["exact [s]"], "-", color=color, lw=3.0,
                      alpha=0.4)
            axis.plot(group["theta0/alpha [-]"], group["Eq. 2-5 [s]"], "--", color=color,
                      lw=1.0, zorder=3)
            axis.plot(group["theta0/alpha [-]"], group["engine [s]"], "o", color=color, ms=3,
                      zorder=4)
            handles.append(Line2D([], [], color=color, lw=3.0, alpha=0.6, label=name))
        handles += [Line2D([], [], color="0.3", lw=3.0, alpha=0.4, label="exact"),
                    Line2D([], [], color="0.3", lw=1.0, ls="--", label="Eq. 2-5"),
                    Line2D([], [], color="0.3", ls="none", marker="o", ms=3,
                           label="engine, COR 1")]
        axis.set_xlabel("amplitude θ0/α [-]")
        axis.set_ylabel("period T [s]")
        axis.set_title("Fig. 2.3: period of free rocking", fontsize=10)
        axis.grid(True, lw=0.3, alpha=0.6)
        fig.tight_layout()
        place_legend(axis, handles=handles, fontsize=7, frameon=False)
        return fig
    elif figure == "2.4":
        axis.plot(frame["a/(g alpha) [-]"], frame["Eq. 2-7 t1 [s]"], "--", label="Eq. 2-7")
        axis.plot(frame["a/(g alpha) [-]"], frame["engine t1 [s]"], "o-", label="engine (exact)")
        axis.set_xlabel("a / (g α) [-]")
        axis.set_ylabel("duration t1 that overturns [s]")
        axis.set_title("Fig. 2.4: constant acceleration of duration t1 (16 x 4 ft)", fontsize=10)
    elif figure == "2.5":
        colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        for (acceleration, group), color in zip(frame.groupby("a [g]", sort=False), colors):
            closed = group["closed form t(alpha) [s]"].where(
                np.isfinite(group["closed form t(alpha) [s]"]))
            axis.plot(group["height [m]"], closed, "--", color=color, lw=1,
                      label=f"a = {acceleration:g} g: slender closed form, t(α)")
            axis.plot(group["height [m]"], group["engine t(alpha) [s]"], "o", color=color,
                      ms=3, label=f"a = {acceleration:g} g: engine, t(α)")
            axis.plot(group["height [m]"], group["engine t(pi/2) [s]"], "s-", color=color,
                      ms=3, lw=0.8, label=f"a = {acceleration:g} g: engine, overturned")
        axis.set_xscale("log")
        axis.set_xlabel("block height H [m] (H/B = 4)")
        axis.set_ylabel("time t [s]")
        axis.set_title("Fig. 2.5: square acceleration pulse of 0.1 s (no point: the block "
                       "falls back)", fontsize=9)
    elif figure == "4.3.4":
        duration = frame["pulse duration [s]"]
        axis.plot(duration, frame["Eq. 2-9 [g]"], ":", label="Eq. 2-9 (the report's 4.6 g at 0.1 s)")
        axis.plot(duration, frame["impulse limit [g]"], "--", label="exact impulse limit")
        axis.plot(duration, frame["engine [g]"], "o-", label="engine (exact Eq. 2-13)")
        axis.set_xscale("log")
        axis.set_yscale("log")
        # plain decimal ticks on both log axes (no 4 x 10^1 labels piling up)
        from matplotlib.ticker import FixedLocator, NullFormatter, ScalarFormatter

        axis.xaxis.set_major_locator(FixedLocator([0.01, 0.02, 0.05, 0.1]))
        axis.yaxis.set_major_locator(FixedLocator([2, 3, 5, 10, 20, 30, 50]))
        for ticks in (axis.xaxis, axis.yaxis):
            ticks.set_major_formatter(ScalarFormatter())
            ticks.set_minor_formatter(NullFormatter())
        axis.set_xlabel("half-sine pulse duration Ts/2 [s]")
        axis.set_ylabel("amplitude that overturns [g]")
        axis.set_title("Section 4.3 (4): single pulse on the 16 x 4 ft block", fontsize=10)
    elif figure == "2.6":
        axis.plot(frame["omega/p [-]"], frame["Eq. 2-8 [g]"], "--", label="Eq. 2-8")
        axis.plot(frame["omega/p [-]"], frame["Eq. 2-9 [g]"], ":", label="Eq. 2-9")
        axis.plot(frame["omega/p [-]"], frame["engine [g]"], "o-",
                  label="engine: single half-sine pulse")
        axis.set_xlabel("ω / p [-]")
        axis.set_ylabel("pulse amplitude that overturns [g]")
        axis.set_title("Fig. 2.6: sinusoidal pulse (16 x 4 ft)", fontsize=10)
    else:
        raise ValueError(f"figure must be '2.3', '2.4', '2.5', '2.6' or '4.3.4', got {figure!r}")
    axis.grid(True, lw=0.3, alpha=0.6)
    fig.tight_layout()
    place_legend(axis, fontsize=7, frameon=False)
    return fig


def figure_3_6(frame, block=None):
    """Fig. 3.6: period of free rocking against amplitude, 36 x 9 in block.

    Parameters
    ----------
    frame : pandas.DataFrame
        From :func:`shaketable.studies.report_tables.table_3_1`: the report's test and
        theory periods (Table 3.1) and the virtual test's periods read the
        report's way.
    block : Block, optional
        The block of the curves (default 36 x 9 in).

    Returns
    -------
    matplotlib.figure.Figure
        Eq. (2-5) and the exact period (quadrature of the energy integral) as
        curves, the printed and virtual periods as points.
    """
    from shaketable.core import theory
    from shaketable.core.geometry import Block

    plt = pyplot()
    block = block or Block.from_inches(36, 9)
    degrees = 180.0 / np.pi
    amplitudes = np.linspace(0.02, 0.95, 80) * block.alpha
    fig, axis = plt.subplots(figsize=(6.5, 4.5))
    # the exact curve wide and pale, Eq. 2-5 dashed on top: they nearly coincide
    axis.plot(amplitudes * degrees, [theory.exact_period(block, a) for a in amplitudes], "-",
              color="C3", lw=3.0, alpha=0.45, label="exact (energy integral)")
    axis.plot(amplitudes * degrees, [theory.housner_period(block, a) for a in amplitudes], "--",
              color="0.2", lw=1, label="Eq. 2-5 (slender block)")
    axis.plot(frame["amplitude [deg]"], frame["test period [s]"], "o", color="k", ms=5,
              label="report: test (Table 3.1)")
    axis.plot(frame["amplitude [deg]"], frame["theory period [s]"], "x", color="C0", ms=6,
              label="report: theory (Table 3.1)")
    axis.plot(frame["virtual test amplitude [deg]"], frame["virtual test period [s]"], "s",
              mfc="none", color="C2", ms=6, label="virtual test, 50 samples/s, 4 x max-to-zero")
    axis.set_xlabel("amplitude θ0 [deg]")
    axis.set_ylabel("period T [s]")
    axis.set_title(f"Fig. 3.6: period against amplitude, {block.describe()} block", fontsize=10)
    axis.grid(True, lw=0.3, alpha=0.6)
    fig.tight_layout()
    place_legend(axis, fontsize=7, frameon=False)
    return fig


def plot_pitch_repeatability(result, ax=None):
    """theta/alpha of every phase (thin lines) and without pitch (black).

    ``result`` is a :class:`RepeatabilityResult`; see :meth:`RepeatabilityResult.plot`.
    """
    plt = pyplot()

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 3))
    alpha = result.without_pitch.block.alpha
    # no pitch wide and black underneath, every pitch phase thin and in one colour on top:
    # where the phases coincide with it they show as one line inside the black one
    ax.plot(result.without_pitch.t, result.without_pitch.theta / alpha, color="k", lw=2.4,
            label="no pitch")
    for index, run in enumerate(result.runs):
        ax.plot(run.t, run.theta / alpha, lw=0.6, color="tab:orange", alpha=0.7,
                label=f"each of {len(result.runs)} pitch phases" if index == 0 else None)
    # zoom on the action: to a little past the last run's end of motion (overturn or rest)
    ends = []
    for run in (*result.runs, result.without_pitch):
        moving = np.flatnonzero(run.theta != 0.0)
        ends.append(run.t[moving[-1]] if moving.size else run.t[-1])
    last = max(ends)
    ax.set_xlim(0.0, min(max(run.t[-1] for run in result.runs), last + max(0.5, 0.1 * last)))
    for level in (-1, 1):
        ax.axhline(level, color="0.4", ls="--", lw=0.8)
    if math.isfinite(result.record_end):
        ax.axvline(result.record_end, color="0.6", lw=0.8, ls=":")
    ax.set_ylim(-2.0, 2.0)
    ax.set_ylabel("θ/α [-]")
    shown = math.isfinite(result.record_end) and result.record_end <= ax.get_xlim()[1]
    ax.set_xlabel("time [s]" + (" (dotted: end of the record, then the table is at rest)"
                                if shown else ""))
    summary = result.summary()
    ax.set_title(f"{result.name}: {len(result.runs)} pitch phases, "
                 f"{100 * summary['overturned fraction']:.0f} % overturn", fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=True,
              borderaxespad=0.0)
    return ax


def pitch_repeatability_figure(cases):
    """Section 3.7 (2): one panel per case of :func:`plot_pitch_repeatability`, stacked."""
    plt = pyplot()
    figure, axes = plt.subplots(len(cases), 1, figsize=(8, 2.4 * len(cases)), squeeze=False)
    for case, axis in zip(cases, axes[:, 0]):
        plot_pitch_repeatability(case, axis)
    figure.tight_layout()
    return figure
