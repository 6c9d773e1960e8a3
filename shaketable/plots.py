"""Figures. The only module of the package that imports matplotlib."""

from __future__ import annotations

import numpy as np

from .constants import G


def _pyplot():
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "module://matplotlib_inline.backend_inline"):
        try:
            import matplotlib.pyplot as plt  # noqa: F401
        except ImportError:  # pragma: no cover
            matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def calcomp(result, fig=None, title: str | None = None):
    """The report's Calcomp layout (Figs. 2.8 and 4.1-4.17) for one result.

    From top to bottom: horizontal and vertical ground acceleration [g], the
    angular acceleration [rad/s^2] and velocity [rad/s] superimposed, and the
    angular displacement [rad] with the +-alpha lines that bound the stable
    region.

    Parameters
    ----------
    result : RockingResult
    fig : matplotlib.figure.Figure, optional
        Figure to draw into (a new one otherwise).
    title : str, optional
        Defaults to the block, COR and motion, in the report's style.

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _pyplot()
    if fig is None:
        fig = plt.figure(figsize=(8.5, 9.0))
    axes = fig.subplots(4, 1, sharex=True, gridspec_kw={"height_ratios": [1, 1, 1.3, 1.5]})
    block = result.block
    motion = result.motion
    end = result.t[-1]
    shown = motion.t <= end + 1e-12
    axes[0].plot(motion.t[shown], motion.horizontal[shown] / G, color="k", lw=0.7)
    axes[0].set_ylabel("horizontal\nground acc. [g]")
    axes[1].plot(motion.t[shown], motion.vertical_or_zero[shown] / G, color="k", lw=0.7)
    axes[1].set_ylabel("vertical\nground acc. [g]")
    axes[2].plot(result.t, result.theta_ddot, color="tab:red", lw=0.6,
                 label="angular acceleration [rad/s²]")
    axes[2].plot(result.t, result.theta_dot, color="tab:blue", lw=0.9,
                 label="angular velocity [rad/s]")
    axes[2].set_ylabel("θ'' [rad/s²]\nθ' [rad/s]")
    axes[2].legend(loc="upper right", fontsize=7, frameon=False)
    axes[3].plot(result.t, result.theta, color="k", lw=0.9)
    for sign in (1, -1):
        axes[3].axhline(sign * block.alpha, color="tab:gray", lw=0.8, ls="--")
    axes[3].set_ylabel("θ [rad]")
    axes[3].set_xlabel("time [s]")
    limit = max(1.3 * block.alpha, 1.1 * float(np.max(np.abs(result.theta), initial=0.0)))
    axes[3].set_ylim(-limit, limit)
    note = f"max θ/α = {result.max_theta_ratio:.2f}"
    if result.overturned:
        note += f", overturns ({'+' if result.overturn_direction > 0 else '−'}) at " \
                f"{result.t_overturn:.2f} s"
    elif result.status == "airborne":
        note += f", leaves the ground at {result.t_airborne:.2f} s (vertical ≤ −g)"
    axes[3].text(0.01, 0.04, note, transform=axes[3].transAxes, fontsize=8)
    for axis in axes:
        axis.grid(True, lw=0.3, alpha=0.5)
        axis.set_xlim(motion.t[0], max(end, motion.t[0] + 1e-9))
    if title is None:
        inch = 0.0254
        title = (f"B = {block.width / inch:g} in, H = {block.height / inch:g} in, "
                 f"COR = {result.cor:g}")
        if block.rods is not None:
            title += (f", K = {block.rods.stiffness * inch:g} W/in, "
                      f"prestress = {block.rods.force:g} W")
        if motion.name:
            title = f"{motion.name}\n{title}"
    fig.suptitle(title, fontsize=10)
    fig.align_ylabels(axes)
    return fig


def save(fig, path) -> None:
    """Save and close a figure."""
    plt = _pyplot()
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)


def section_2_figure(frame, figure: str):
    """Figs. 2.3-2.6: the report's closed forms against the engine.

    Parameters
    ----------
    frame : pandas.DataFrame
        From :func:`shaketable.section2.figure_2_3` (``figure="2.3"``),
        ``figure_2_4`` (``"2.4"``), ``figure_2_5`` (``"2.5"``) or ``figure_2_6``
        (``"2.6"``).
    figure : str

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _pyplot()
    fig, axis = plt.subplots(figsize=(6.5, 4.5))
    if figure == "2.3":
        for (name, group), color in zip(frame.groupby("block", sort=False),
                                        plt.rcParams["axes.prop_cycle"].by_key()["color"]):
            axis.plot(group["theta0/alpha [-]"], group["Eq. 2-5 [s]"], "--", color=color,
                      lw=1, label=f"{name}: Eq. 2-5")
            axis.plot(group["theta0/alpha [-]"], group["exact [s]"], "-", color=color, lw=1.2,
                      label=f"{name}: exact")
            axis.plot(group["theta0/alpha [-]"], group["engine [s]"], "o", color=color, ms=3)
        axis.set_xlabel("amplitude θ0/α [-]")
        axis.set_ylabel("period T [s]")
        axis.set_title("Fig. 2.3: period of free rocking (dots: engine, COR 1)", fontsize=10)
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
    axis.legend(fontsize=7, frameon=False)
    fig.tight_layout()
    return fig


def figure_3_6(frame, block=None):
    """Fig. 3.6: period of free rocking against amplitude, 36 x 9 in block.

    Parameters
    ----------
    frame : pandas.DataFrame
        From :func:`shaketable.report_tables.table_3_1`: the report's test and
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
    from . import theory
    from .geometry import Block

    plt = _pyplot()
    block = block or Block.from_inches(36, 9)
    degrees = 180.0 / np.pi
    amplitudes = np.linspace(0.02, 0.95, 80) * block.alpha
    fig, axis = plt.subplots(figsize=(6.5, 4.5))
    axis.plot(amplitudes * degrees, [theory.housner_period(block, a) for a in amplitudes], "--",
              color="0.4", lw=1, label="Eq. 2-5 (slender block)")
    axis.plot(amplitudes * degrees, [theory.exact_period(block, a) for a in amplitudes], "-",
              color="C3", lw=1.2, label="exact (energy integral)")
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
    axis.legend(fontsize=7, frameon=False)
    fig.tight_layout()
    return fig
