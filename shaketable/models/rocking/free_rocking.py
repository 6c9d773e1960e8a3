"""What a free-rocking run (a released block, no table motion) answers, in words.

A block released from a tilt on a still table answers when it came to rest and after
how many visible cycles (what a reader checks against Section 3.7 (1), Fig. 3.4: "came
to rest in approximately 6 seconds, after about 10 vibrations"); its max θ/α is the
release angle, so it comes last, said as the release. The one verdict of such a run:
:meth:`~shaketable.models.rocking.result.RockingResult.verdict` says it, and every command
prints that.

The impacts are said as a reader of the figure can count them: those after a swing above
:data:`VISIBLE_FRACTION` of the release (two per cycle; the report's Fig. 3.4 block
rocks "about 10 vibrations"), then the ever smaller ones whose times accumulate at the
rest time, where the engine sums the endless rest of the cascade.
"""

from __future__ import annotations

import math

import numpy as np

#: Swings above this fraction of the release amplitude [-] count as visible on a figure
#: of theta; the smaller ones are the cascade accumulating at the rest time.
VISIBLE_FRACTION = 0.03


def is_free(result) -> bool:
    """True when the table did not move in ``result`` (a rocking run): free rocking."""
    motion = result.motion
    vertical = motion.vertical if motion.vertical is not None else np.zeros(1)
    return not (np.any(np.asarray(motion.horizontal) != 0.0)
                or np.any(np.asarray(vertical) != 0.0))


def rocking_rest_time(result) -> float:
    """When a rocking block (:class:`~shaketable.models.rocking.result.RockingResult`) came to rest
    for good [s]: NaN when it overturned, left the ground or still rocks at the end, 0
    when it never rocked."""
    if result.status != "completed":
        return math.nan
    if not math.isfinite(result.t_start):
        return 0.0
    moving = np.flatnonzero((result.theta != 0.0) | (result.theta_dot != 0.0))
    if not moving.size:
        return 0.0
    if moving[-1] == result.t.size - 1:
        return math.nan
    settled = float(result.t[moving[-1] + 1])
    # the summed cascade's end lies between the last moving sample and the next
    if math.isfinite(result.t_rest) and result.t[moving[-1]] <= result.t_rest <= settled:
        return float(result.t_rest)
    return settled


def last_swing_ratio(result) -> float:
    """The largest |θ|/α [-] since the last impact (the whole run without one): the
    amplitude a block still rocking at the end has left."""
    after = result.t >= result.impact_times[-1] if result.impact_times.size else slice(None)
    return float(np.max(np.abs(result.theta[after])) / result.block.alpha)


def visible_impacts(result, fraction: float = VISIBLE_FRACTION) -> int:
    """Impacts after a swing larger than ``fraction`` of the release amplitude [-] (the
    largest |θ| when the block was not released tilted): those whose angular velocity
    exceeds the one a swing of that amplitude reaches at θ = 0 (energy conserved between
    impacts, Eq. 2-3; :func:`shaketable.core.theory.impact_velocity`)."""
    from shaketable.core.theory import impact_velocity

    if result.impact_velocities.size == 0:
        return 0
    first = abs(result.theta[0]) if result.theta[0] != 0 else result.max_abs_theta
    limit = impact_velocity(result.block, fraction * first)
    return int(np.sum(np.abs(result.impact_velocities) > limit))


def _visible_words(result) -> tuple[str, int]:
    """(``"21 impacts of swings over 3 % of the release"``, the count of smaller ones)."""
    count = int(result.n_impacts)
    visible = visible_impacts(result)
    if visible == count:
        return f"{count} impact{'' if count == 1 else 's'}", 0
    of = "the release" if result.theta[0] != 0 else "the largest swing"   # as counted
    return (f"{visible} impact{'' if visible == 1 else 's'} of swings over "
            f"{100 * VISIBLE_FRACTION:g} % of {of}", count - visible)


def impacts_words(result) -> str:
    """The impacts of a free-rocking run for a reader of its figure: ``"21 impacts of
    swings over 3 % of the release (10.5 cycles), then 197 smaller ones accumulating at
    t = 5.76 s (218 impacts computed one by one, then 1 summed cascade)"``; ``"5 impacts"``
    when every swing was visible."""
    words, smaller = _visible_words(result)
    if smaller:
        words += (f" ({visible_impacts(result) / 2:g} cycles), then {smaller} smaller "
                  f"one{'' if smaller == 1 else 's'}")
        rest = rocking_rest_time(result)
        if result.cascades and math.isfinite(rest):
            words += (f" accumulating at t = {rest:.2f} s ({int(result.n_impacts)} impacts "
                      f"computed one by one, then {_cascades(result)})")
    elif result.cascades:
        words += f" and {_cascades(result)}"
    return words


def _cascades(result) -> str:
    return f"{result.cascades} summed cascade{'' if result.cascades == 1 else 's'}"


def free_rocking_verdict(result) -> str:
    """A free-rocking run in words, the answer first: ``"came to rest at t = 5.76 s
    after 10.5 cycles: 21 impacts of swings over 3 % of the release, then ever smaller
    ones accumulating there (released at θ/α = 0.50)"``, or ``"still rocking at the end
    (t = 2.00 s) after 2.5 cycles, last swing θ/α = 0.05: 5 impacts (released at θ/α =
    0.50)"`` (a block kicked from upright: ``"(started from θ = 0 at θ' = 0.2 rad/s)"``;
    an initial rate is said after the release); an overturned or airborne run, or one that
    never rocked, as
    :meth:`~shaketable.models.rocking.result.RockingResult.verdict` says it otherwise."""
    if result.status != "completed" or not math.isfinite(result.t_start):
        return result.verdict()
    ratio = abs(result.theta[0]) / result.block.alpha   # a release below 0.01: as given
    rate = float(result.theta_dot[0])
    if ratio == 0.0 and rate != 0.0:   # kicked from upright: its initial rate is its start
        release = f"started from θ = 0 at θ' = {rate:.3g} rad/s"
    else:
        release = (f"released at θ/α = {ratio:.2f}" if round(ratio, 2) >= 0.01 else
                   f"released at θ/α = {ratio:.2g}") + (f" at θ' = {rate:.3g} rad/s"
                                                        if rate != 0.0 else "")
    rest = rocking_rest_time(result)
    words, smaller = _visible_words(result)
    cycles = visible_impacts(result) / 2   # two impacts a cycle
    after = f"after {cycles:g} cycle{'' if cycles == 1 else 's'}"
    if math.isnan(rest):
        return (f"still rocking at the end (t = {result.t[-1]:.2f} s) {after}, last swing "
                f"θ/α {_ratio(last_swing_ratio(result))}: {words}"
                + (f" and {smaller} smaller" if smaller else "") + f" ({release})")
    if smaller:   # with a summed cascade the impacts' times accumulate at the rest time
        words += (", then ever smaller ones accumulating there" if result.cascades
                  else f", then {smaller} smaller")
    return f"came to rest at t = {rest:.2f} s {after}: {words} ({release})"


def first_period(result) -> float:
    """The period of a free-rocking run's first swing [s]: 4 x the time from the release
    to the first impact (a quarter period, Eq. 2-5's arccosh(1/(1 - θ0/α))/p for a slender
    block); NaN without an impact."""
    if not result.impact_times.size:
        return math.nan
    return 4.0 * float(result.impact_times[0] - result.t[0])


def _ratio(value: float) -> str:
    """``"= 0.05"``: θ/α to two decimals, as the release is said; ``"< 0.01"`` below."""
    return f"= {value:.2f}" if round(value, 2) >= 0.01 else "< 0.01"
