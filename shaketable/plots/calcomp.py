"""The report's Calcomp layout (Figs. 2.8 and 4.1-4.17): ground, angular motion, rotation."""

from __future__ import annotations

import numpy as np

from shaketable.core.constants import G, length_factor
from shaketable.plots.base import pyplot
from shaketable.studies.free_rocking import free_rocking_verdict

#: Colours of the angular acceleration and velocity traces.
_ACCELERATION_COLOUR = "tab:red"
_VELOCITY_COLOUR = "tab:blue"
#: The overlaid runs' colours (neither the acceleration's red nor the velocity's blue).
_OTHER_COLOURS = ("tab:green", "tab:purple", "tab:orange", "tab:brown", "tab:olive",
                  "tab:cyan", "tab:pink")


def describe_block(block) -> str:
    """The block as the report's captions give it: ``"B × H = 4 × 16 ft"`` (or inches).

    Feet when both dimensions are whole feet of at least 2 ft (Chapter 4's
    blocks), inches otherwise (Chapter 3's specimens); prestress rods with
    their total stiffness K [W/in] and force F0 [W] (Section 2.8). A block parsed
    from the user's text (``--block 30x6in``, ``size = "4x0.8ft"``) is echoed in the
    user's order and units: ``"H × B = 30 × 6 in"``, ``"H × B = 4 × 0.8 ft"``.
    """
    foot, inch = length_factor("ft"), length_factor("in")
    width_ft, height_ft = block.width / foot, block.height / foot
    if getattr(block, "label", ""):
        text = f"H × B = {block.label.replace(' x ', ' × ')}"
    elif min(width_ft, height_ft) >= 2 and np.allclose([width_ft, height_ft],
                                                     np.round([width_ft, height_ft]), atol=1e-9):
        text = f"B × H = {width_ft:g} × {height_ft:g} ft"
    else:
        text = f"B × H = {block.width / inch:g} × {block.height / inch:g} in"
    if block.rods is not None:
        text += (f", prestress rods K = {block.rods.stiffness * inch:g} W/in, "
                 f"F0 = {block.rods.force:g} W")
    return text


def describe_motion(motion, free: bool) -> str:
    """The ground motion in words (its name, or "free rocking")."""
    if free:
        return "free rocking (no ground motion)"
    return motion.name or "ground motion"


def has_signal(values) -> bool:
    """True when a ground-motion channel is not identically zero."""
    return bool(np.any(np.asarray(values) != 0.0))


def ground_panels(motion, end: float, ratios, fig=None, height=(3.6, 1.9)):
    """The Calcomp layout's figure: a panel for each ground component that is not zero
    (acceleration [g] up to ``end`` [s]) above the panels of height ``ratios``.

    Returns ``(fig, axes)``, every panel sharing the time axis; the figure is
    ``height[0] + height[1] * panels`` inches high, laid out by matplotlib's constrained
    layout.
    """
    plt = pyplot()
    shown = motion.t <= end + 1e-12
    ground = [(label, values) for label, values in (
        ("horizontal\nground acc. [g]", motion.horizontal[shown] / G),
        ("vertical\nground acc. [g]", motion.vertical_or_zero[shown] / G)) if has_signal(values)]
    heights = [1.0] * len(ground) + list(ratios)
    if fig is None:
        fig = plt.figure(figsize=(8.5, height[0] + height[1] * len(heights)),
                         layout="constrained")
    else:
        fig.set_layout_engine("constrained")
    axes = fig.subplots(len(heights), 1, sharex=True, gridspec_kw={"height_ratios": heights})
    for axis, (label, values) in zip(axes, ground):
        axis.plot(motion.t[shown], values, color="k", lw=0.7)
        axis.set_ylabel(label)
    return fig, axes


def broken_at_sign_changes(t, theta, values):
    """``(t, values)`` with NaN inserted where theta changes sign (an impact).

    The angular acceleration of Eq. (2-13) flips sign at each impact (the
    pivot changes corner), and jumps from and to zero where the block lifts
    off or comes to rest: a line drawn through the samples would draw a
    vertical jump at every impact, and a cascade of impacts would become a
    solid band. Broken at the impacts, the trace shows its envelope.
    """
    t = np.asarray(t, dtype=float)
    values = np.asarray(values, dtype=float)
    sign = np.sign(theta)
    breaks = np.flatnonzero(sign[1:] != sign[:-1]) + 1
    return np.insert(t, breaks, np.nan), np.insert(values, breaks, np.nan)


def calcomp(result, fig=None, title: str | None = None, time_range=None, others=(),
            details=()):
    """The report's Calcomp layout (Figs. 2.8 and 4.1-4.17) for one result, with its caption.

    From top to bottom: horizontal and vertical ground acceleration [g], the
    angular acceleration [rad/s^2] and velocity [rad/s] superimposed, and the
    angular displacement [rad] with the +-alpha lines that bound the stable
    region. A ground channel that is identically zero is left out and said so
    in the caption (free rocking has no ground panel). The angular
    acceleration is broken at every impact (:func:`broken_at_sign_changes`).

    The caption (the figure's title) carries what the report's captions give:
    block B x H with units, COR, prestress rods K and F0, the ground motion,
    and the verdict ("overturned (+) at 6.42 s" or "max θ/α = 0.78").

    Parameters
    ----------
    result : RockingResult
    fig : matplotlib.figure.Figure, optional
        Figure to draw into (a new one otherwise).
    title : str, optional
        First line of the caption, e.g. ``"Fig. 4.1"``; the block, COR, motion
        and verdict follow on their own lines.
    time_range : (float, float), optional
        Time axis limits [s] (default: the motion's start to the end of the
        longest run). Figures meant to be compared share one.
    others : sequence of RockingResult, optional
        Runs of the same block and motion at other CORs, overlaid on the
        rotation panel (their verdicts join the caption).
    details : sequence of str, optional
        Further caption lines (e.g. the record's scale or a substitute note).

    Returns
    -------
    matplotlib.figure.Figure
    """
    block = result.block
    motion = result.motion
    # to the end of the longest run: a run that overturns early must not cut short the
    # others overlaid on it (the large block's peak after the small one fell)
    end = max(float(run.t[-1]) for run in (result, *others))
    fig, axes = ground_panels(motion, end, (1.3, 1.5), fig, height=(3.6, 1.9))
    rates, rotation = axes[-2], axes[-1]
    t_broken, acceleration = broken_at_sign_changes(result.t, result.theta, result.theta_ddot)
    labels = run_labels((result, *others))
    which = f", {labels[0]} only" if others else ""
    rates.plot(t_broken, acceleration, color=_ACCELERATION_COLOUR, lw=0.6,
               label=f"θ'' angular acceleration [rad/s²]\n(broken at impacts{which})")
    rates.plot(result.t, result.theta_dot, color=_VELOCITY_COLOUR, lw=0.9,
               label=f"θ' angular velocity [rad/s], {labels[0]}" if others
               else "θ' angular velocity [rad/s]")
    # every run's velocity, in its colour on the rotation panel: a run that ends early
    # (its block overturned) must not leave the panel blank for the rest of the others
    colours = [_OTHER_COLOURS[index % len(_OTHER_COLOURS)] for index in range(len(others))]
    for other, label, colour in zip(others, labels[1:], colours):
        rates.plot(other.t, other.theta_dot, color=colour, lw=0.9,
                   label=f"θ' angular velocity [rad/s], {label}")
    rates.set_ylabel("θ'' [rad/s²]\nθ' [rad/s]")
    rates.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=True,
                 borderaxespad=0.0)
    rotation.plot(result.t, result.theta, color="k", lw=0.9,
                  label=labels[0] if others else "θ")
    extremes = [float(np.max(np.abs(result.theta), initial=0.0))]
    for other, label, colour in zip(others, labels[1:], colours):
        rotation.plot(other.t, other.theta, color=colour, lw=0.9, label=label)
        extremes.append(float(np.max(np.abs(other.theta), initial=0.0)))
    for sign in (1, -1):
        rotation.axhline(sign * block.alpha, color="tab:gray", lw=0.8, ls="--",
                         label="±α (stability limit)" if sign > 0 else None)
    rotation.set_ylabel("θ [rad]")
    rotation.set_xlabel("time [s]")
    limit = max(1.3 * block.alpha, 1.1 * max(extremes))
    rotation.set_ylim(-limit, limit)
    rotation.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=True,
                    borderaxespad=0.0)
    start, stop = (motion.t[0], max(end, motion.t[0] + 1e-9)) if time_range is None \
        else time_range
    for axis in axes:
        axis.grid(True, lw=0.3, alpha=0.5)
        axis.set_xlim(start, stop)
    for run, label in zip((result, *others), labels):
        mark_overturn(axes, run, stop, label if others else None)
    fig.suptitle("\n".join(calcomp_caption(result, title=title, others=others,
                                           details=details)), fontsize=9.5)
    fig.align_ylabels(axes)
    return fig


def mark_overturn(axes, run, stop, name: str | None = None) -> None:
    """Where the run ends because the block overturned, when the time axis goes on past it.

    A run stops where its block overturns; on a time axis shared with another
    figure (``time_range``) the panels are blank after that time. A vertical
    line on every panel and the words "overturned (±) at t s: the run ends
    here" on the rotation panel say why, where the blank begins; with several runs
    overlaid, ``name`` says which run ends ("4 x 0.8 ft overturned (−) at 4.28 s: its
    run ends here"). Nothing is drawn when the axis ends with the run (the caption gives
    the time).
    """
    start = axes[0].get_xlim()[0]
    if not run.overturned or not np.isfinite(run.t_overturn) \
            or stop - run.t_overturn <= 0.1 * (stop - start):
        return
    for axis in axes:
        axis.axvline(run.t_overturn, color="0.35", lw=0.8, ls="-.")
    side = "+" if run.overturn_direction > 0 else "−"
    # on the side away from the fall: the trace ends at the top (+) or at the bottom (−)
    words = f"overturned ({side}) at {run.t_overturn:.2f} s:\nthe run ends here" if name is None \
        else f"{name} overturned ({side})\nat {run.t_overturn:.2f} s: its run ends here"
    axes[-1].annotate(words,
                      (run.t_overturn, 0.96 if run.overturn_direction < 0 else 0.04),
                      xycoords=axes[-1].get_xaxis_transform(), xytext=(4, 0),
                      textcoords="offset points", fontsize=7, ha="left",
                      va="top" if run.overturn_direction < 0 else "bottom")


def run_labels(runs) -> list[str]:
    """Legend labels telling runs apart by what differs: ``COR 0.9`` when only the COR
    does, ``30 x 6 in, θ0/α 0.2, COR 0.9`` when block sizes or release angles do too."""
    blocks = [run.block.describe() for run in runs]
    starts = [f"θ0/α {run.theta[0] / run.block.alpha:.3g}" for run in runs]
    parts = [blocks] if len(set(blocks)) > 1 else []
    parts += [starts] if len(set(starts)) > 1 else []
    if len({run.cor for run in runs}) > 1 or not parts:
        parts.append([f"COR {run.cor:g}" for run in runs])
    return [", ".join(part[index] for part in parts) for index in range(len(runs))]


def calcomp_caption(result, title: str | None = None, others=(), details=()) -> list[str]:
    """The caption lines of :func:`calcomp`: heading, block and COR, motion, verdict."""
    block, motion = result.block, result.motion
    free = not has_signal(motion.horizontal) and not has_signal(motion.vertical_or_zero)
    cors = ", ".join(f"{run.cor:g}" for run in (result, *others))
    lines = [] if not title else [title]
    if len({(run.block.height, run.block.width) for run in (result, *others)}) > 1:
        cors = ", ".join(sorted({f"{run.cor:g}" for run in (result, *others)}))
        names = list(dict.fromkeys(describe_block(run.block) for run in (result, *others)))
        if all(name.startswith("H × B = ") for name in names):
            names = ["H × B = " + ", ".join(name[8:] for name in names)]
        lines.append(f"blocks {', '.join(names)}, COR {cors}")
    else:
        lines.append(f"{describe_block(block)}, α = {block.alpha:.4g} rad, COR {cors}")
    ground = describe_motion(motion, free)
    if not free and not has_signal(motion.vertical_or_zero):
        ground += " (no vertical motion: panel left out)"
    elif not free and not has_signal(motion.horizontal):
        ground += " (no horizontal motion: panel left out)"
    lines.append(ground)
    lines.extend(details)
    if others:
        runs = (result, *others)
        verdicts = [f"{label}: {run.verdict()}" for label, run in zip(run_labels(runs), runs)]
        lines.append(("; " if len("; ".join(verdicts)) <= 100 else "\n").join(verdicts))
    else:
        lines.append(free_rocking_verdict(result) if free else result.verdict())
    return lines
