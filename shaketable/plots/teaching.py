"""Figures of the teaching gallery (:mod:`shaketable.studies.teaching`).

Each function takes the result object of one gallery item and returns the
matplotlib figure (or axes); matplotlib is imported through
:func:`shaketable.plots.base._pyplot`, so the backend choice stays in one place.
"""

from __future__ import annotations

import numpy as np

from shaketable.plots.base import place_legend, pyplot

_FOOT = 0.3048


def _label(block) -> str:
    """Block size in feet when it is a whole number of feet, else in inches."""
    height, width = block.height / _FOOT, block.width / _FOOT
    if abs(height - round(height)) < 1e-9 and abs(width * 2 - round(width * 2)) < 1e-9:
        return f"{height:g} x {width:g} ft"
    return block.describe()


def _active_until(t, ratio, level=0.02, margin=3.0) -> float:
    """Last time |ratio| exceeds ``level`` plus a margin [same unit as t]."""
    active = np.flatnonzero(np.abs(ratio) > level)
    return float(t[-1]) if active.size == 0 else min(float(t[-1]), float(t[active[-1]]) + margin)


def _finish(axis, title=None):
    axis.grid(True, lw=0.3, alpha=0.6)
    if title:
        axis.set_title(title, fontsize=9)


def plot_period_amplitude(item, ax=None):
    """Period of free rocking against amplitude: Eq. (2-5), exact, engine, linear oscillator.

    Parameters
    ----------
    item : shaketable.studies.teaching.PeriodAmplitude
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    plt = pyplot()
    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4.3))
    ratios = item.amplitude_ratios
    fine = np.linspace(0.002, 0.98, 300)
    block = item.block
    from shaketable.core import theory

    ax.plot(fine, [theory.exact_period(block, r * block.alpha) for r in fine], "-",
            color="k", lw=1.3, label="exact period, energy integral of Eq. 2-3")
    ax.plot(fine, [theory.housner_period(block, r * block.alpha) for r in fine], "--",
            color="tab:orange", lw=1.1, label="Eq. 2-5 (slender block)")
    ax.plot(ratios, item.engine_period, "o", color="tab:blue", ms=4,
            label="engine, COR 1: 4 × time to first impact")
    ax.axhline(item.linear_period, color="tab:green", lw=1.2, ls="-.",
               label=f"linear oscillator (T = {item.linear_period:.2f} s at every amplitude)")
    ax.plot([item.reference_ratio], [item.linear_period], "s", color="tab:green", ms=5)
    ax.set_xlabel("release amplitude θ0/α [-]")
    ax.set_ylabel("period T [s]")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, min(1.1 * float(np.max(item.exact_period)), 4 * item.linear_period))
    ax.legend(fontsize=7.5, frameon=False, loc="upper left")
    _finish(ax, f"The rocking period grows with amplitude ({_label(block)}, "
                f"p = {block.p:.2f} rad/s)")
    ax.figure.tight_layout()
    return ax


def plot_cor_sweep(item, fig=None):
    """Max theta/alpha against COR beside the time histories of two CORs.

    Parameters
    ----------
    item : shaketable.studies.teaching.CorSweep
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(10, 4.2))
    left, right = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1, 1.3]})
    left.plot(item.cors, item.max_theta_ratio, "o-", color="k", ms=3.5, lw=0.8,
              label="engine, bundled record")
    if np.any(item.overturned):
        top = np.nanmax(item.max_theta_ratio) if np.any(~item.overturned) else 1.0
        left.plot(item.cors[item.overturned], np.full(item.overturned.sum(), 1.05 * top), "x",
                  color="tab:red", label="overturns (F)")
    for cor, ratio in item.report_points:
        left.plot([cor], [ratio], "D", color="tab:purple", ms=6, mfc="none")
    if item.report_points:
        left.plot([], [], "D", color="tab:purple", mfc="none",
                  label="report, Tables 4.2/4.3 (original digitisation)")
    worst = item.worst_cor
    index = int(np.flatnonzero(item.cors == worst)[0])
    left.annotate(f"COR {worst:g}: {item.max_theta_ratio[index]:.2f}",
                  (worst, item.max_theta_ratio[index]), textcoords="offset points",
                  xytext=(8, 4), fontsize=8)
    left.set_xlabel("coefficient of restitution ν [-]")
    left.set_ylabel("max |θ|/α [-]")
    left.invert_xaxis()
    left.set_ylim(0, None)
    left.legend(fontsize=7, frameon=False, loc="lower left")
    _finish(left, "Peak response against COR (more damping to the right)")
    colors = ("tab:blue", "tab:red")
    for (cor, (t, ratio)), color in zip(item.histories.items(), colors):
        right.plot(t, ratio, color=color, lw=0.8, label=f"COR {cor:g}: max {np.max(np.abs(ratio)):.2f}")
    for sign in (1, -1):
        right.axhline(sign, color="tab:gray", ls="--", lw=0.8)
    t_worst, ratio_worst = item.histories[item.worst_cor]
    right.set_xlim(0, _active_until(t_worst, ratio_worst, margin=5.0))
    right.set_xlabel("time [s]")
    right.set_ylabel("θ/α [-]")
    right.set_ylim(-1.2, 1.2)
    right.legend(fontsize=7.5, frameon=False, loc="upper right")
    _finish(right, "θ/α: the lower COR rocks higher")
    fig.suptitle(f"A lower COR can raise the peak: {_label(item.block)} block\n"
                 f"{item.motion_name} (Section 4.3 (3), Figs. 4.13-4.14)", fontsize=10)
    fig.tight_layout()
    return fig


def plot_similar_blocks(item, fig=None):
    """Max theta/alpha against size for similar blocks, and the p t scaling law.

    Parameters
    ----------
    item : shaketable.studies.teaching.SimilarBlocks
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(10, 4.2))
    left, right = fig.subplots(1, 2)
    heights_ft = item.heights / _FOOT
    survived = ~item.overturned
    left.plot(heights_ft[survived], item.max_theta_ratio[survived], "o-", color="k", ms=4,
              lw=0.9, label="survives: max |θ|/α")
    if np.any(item.overturned):
        left.plot(heights_ft[item.overturned], np.ones(item.overturned.sum()), "x",
                  color="tab:red", ms=8, mew=2, label="overturns (F)")
    for height, ratio, fell in zip(heights_ft, item.max_theta_ratio, item.overturned):
        text = "F" if fell else f"{ratio:.2f}"
        left.annotate(text, (height, 1.0 if fell else ratio), textcoords="offset points",
                      xytext=(0, 7), ha="center", fontsize=7)
    left.axhline(1.0, color="tab:gray", ls="--", lw=0.8)
    left.set_xscale("log")
    left.set_xticks(heights_ft)
    left.set_xticklabels([f"{h:g}" for h in heights_ft])
    left.set_xlabel(f"block height H [ft] (width H/{item.aspect_ratio:g})")
    left.set_ylabel("max |θ|/α [-]")
    left.set_ylim(0, 1.25)
    left.legend(fontsize=7.5, frameon=False, loc="lower left")
    _finish(left, f"Same shape (H/B = {item.aspect_ratio:g}), same record, COR {item.cor:g}")
    small, large = item.scaling_blocks
    right.plot(item.scaling_pt, item.scaling_theta_small / small.alpha, color="tab:blue",
               lw=1.6, label=f"{small.height / _FOOT:g} x {small.width / _FOOT:g} ft, record as is")
    right.plot(item.scaling_pt, item.scaling_theta_large / large.alpha, color="tab:orange",
               lw=0.8, ls="--",
               label=f"{large.height / _FOOT:g} x {large.width / _FOOT:g} ft, record "
                     f"√{item.scale:g} = {np.sqrt(item.scale):.3f}× slower")
    right.set_xlim(0, _active_until(item.scaling_pt, item.scaling_theta_small / small.alpha,
                                    margin=10.0))
    right.set_xlabel("dimensionless time p·t [-]")
    right.set_ylabel("θ/α [-]")
    right.legend(fontsize=7.5, frameon=False, loc="upper right",
                 title=f"max difference {item.scaling_difference:.1e} of the peak",
                 title_fontsize=7.5)
    _finish(right, "Scaling law: similar blocks, record slowed by √λ: same θ(p t)")
    fig.suptitle(f"Geometrically similar blocks: the larger survives\n({item.motion_name}; "
                 "Section 2.4 (1), Tables 4.2-4.3)", fontsize=10)
    fig.tight_layout()
    return fig


def plot_rocking_onset(item, fig=None):
    """Eq. (2-1) threshold against vertical acceleration, and a harmonic demonstration.

    Parameters
    ----------
    item : shaketable.studies.teaching.RockingOnset
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = pyplot()
    if fig is None:
        fig = plt.figure(figsize=(10, 4.2))
    left, right = fig.subplots(1, 2)
    ratio = item.block.width / item.block.height
    vertical = np.linspace(min(-0.8, item.vertical_g.min()), max(0.8, item.vertical_g.max()), 50)
    left.plot(vertical, ratio * (1 + vertical), "-", color="k", lw=1.2,
              label=f"Eq. 2-1: ü = (B/H)(g + v̈), B/H = {ratio:.2f}")
    left.plot(item.vertical_g, item.engine_onset_g, "o", color="tab:blue", ms=4,
              label=f"engine: ü at first uplift (ramp {item.ramp_rate_g:g} g/s)")
    left.axvline(0, color="tab:gray", lw=0.6)
    left.axvspan(vertical[0], 0, color="tab:blue", alpha=0.06)
    left.text(0.03, 0.92, "table accelerating\ndownward", transform=left.transAxes,
              fontsize=8, va="top")
    left.set_xlabel("vertical table acceleration v̈ [g] (up positive)")
    left.set_ylabel("horizontal acceleration that starts rocking [g]")
    left.set_ylim(0, None)
    left.legend(fontsize=7.5, frameon=False, loc="lower right")
    _finish(left, f"Threshold of rocking, {_label(item.block)} block")
    right.plot(item.harmonic_t, item.theta_without_vertical, color="tab:gray", lw=1.4,
               label=f"{item.harmonic_horizontal_g:g} g horizontal alone: no rocking")
    right.plot(item.harmonic_t, item.theta_with_vertical, color="tab:red", lw=0.9,
               label=f"+ {item.harmonic_vertical_g:g} g vertical in phase: rocks at "
                     f"{item.t_start_with_vertical:.2f} s")
    for sign in (1, -1):
        right.axhline(sign, color="tab:gray", ls="--", lw=0.8)
    right.set_ylim(-1.2, 1.6)  # room above the +α line for the legend
    right.set_xlabel("time [s]")
    right.set_ylabel("θ/α [-]")
    _finish(right, f"{item.harmonic_frequency:g} Hz, {item.harmonic_horizontal_g:g} g < "
                   f"B/H = {ratio:.2f} g:\nrocking needs the downward half-cycles")
    fig.suptitle("Rocking starts at a lower horizontal acceleration while the ground "
                 "accelerates downward (Eq. 2-1)", fontsize=10)
    fig.tight_layout()
    place_legend(right, fontsize=7.5, frameon=False)
    return fig


def save_item(item, path) -> None:
    """Draw one gallery item and save it to ``path`` (PNG, SVG... by suffix), then close it."""
    from shaketable.plots.base import save

    drawn = item.plot()
    save(getattr(drawn, "figure", drawn), path)
