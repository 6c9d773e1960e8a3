"""Sliding response mode: a rigid block on the table with Coulomb stick-slip friction.

Model (Section 2.1 and Section 4.5 of [1]_; the sliding mode itself is the subject
of the report's reference (1)), per unit mass, ``x`` the block's displacement
relative to the table, ``N = g + vg`` the normal force per mass:

* stuck (x' = 0): the table holds the block while |ug| <= mu_s N; slip starts
  when |ug| > mu_s (g + vg) (Eq. (2-2)), toward -sign(ug);
* sliding with s = sign(x'):  x'' = -ug - s mu_d (g + vg);
* when x' returns to zero the block sticks if |ug| <= mu_s N at that instant,
  otherwise it slips on the other way (a reversal);
* N <= 0 (vertical table acceleration at or below -g): no normal force, no
  friction. The block would leave the table (jumping), which is outside this
  model: the run goes on with x'' = -ug, the phase is reported as
  ``"airborne"`` and counted in ``time_airborne``; nothing becomes NaN.

The table accelerations are linear between samples (Section 2.8 of [1]_), so
on each piece x'' = c0 + c1 tau is linear, x' a quadratic and x a cubic: each
piece is integrated exactly, the slip start and the normal-force sign changes
are zeros of linear functions and the stick/reversal instants zeros of the
velocity quadratic (stable quadratic formula). Nothing is located on samples.

The kernel is compiled with numba (as :mod:`shaketable.models.rocking.physics`); the
physics is in plain functions on floats and arrays.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.rocking.physics import ERROR_MODEL
from shaketable.models.sliding.result import Friction, SlidingResult

STUCK, SLIDING_POS, SLIDING_NEG, AIRBORNE = 0, 1, -1, 2
EV_START, EV_STICK, EV_REVERSE, EV_LIFTOFF, EV_LAND = 1, 2, 3, 4, 5

#: Sub-pieces allowed in one sample interval before the kernel gives up (a
#: safeguard against a stick-slip chatter loop; never reached in the tests).
MAX_PIECES_PER_INTERVAL = 10_000


@njit(cache=True, error_model=ERROR_MODEL)
def first_up_crossing(f0, slope, length):
    """First tau in [0, length] where the linear f0 + slope tau becomes positive.

    Returns 0 if it is positive at tau = 0 or zero and increasing; -1 if it
    stays <= 0 on [0, length].
    """
    if f0 > 0.0 or (f0 == 0.0 and slope > 0.0):
        return 0.0
    if slope <= 0.0:
        return -1.0
    tau = -f0 / slope
    if tau <= length:
        return tau
    return -1.0


@njit(cache=True, error_model=ERROR_MODEL)
def first_velocity_zero(w0, d0, d2, length):
    """First tau in (0, length] where w0 + d0 tau + d2 tau^2 reaches zero (w0 >= 0).

    ``w = s x'`` is the speed in the sliding direction. At the start of a
    slip (w0 = 0) the slope d0 = |ug| - mu_d N is non-negative (clipped to
    zero against rounding). Roots by the numerically stable quadratic formula.
    Returns -1 if the speed stays positive on the piece.
    """
    if w0 <= 0.0:
        if d0 <= 0.0:
            return 0.0 if d2 < 0.0 else -1.0
        if d2 < 0.0:
            tau = -d0 / d2
            return tau if tau <= length else -1.0
        return -1.0
    if d2 == 0.0:
        if d0 < 0.0:
            tau = -w0 / d0
            return tau if tau <= length else -1.0
        return -1.0
    disc = d0 * d0 - 4.0 * d2 * w0
    if disc < 0.0:
        return -1.0
    q = -0.5 * (d0 + math.copysign(math.sqrt(disc), d0))
    best = math.inf
    r1 = q / d2
    if r1 > 0.0:
        best = r1
    if q != 0.0:
        r2 = w0 / q
        if 0.0 < r2 < best:
            best = r2
    return best if best <= length else -1.0


@njit(cache=True, error_model=ERROR_MODEL)
def stick_slip_kernel(t, ug, vg, mu_s, mu_d, gravity, x0, v0, state0, x_out, v_out,
                      state_out, ev_t, ev_k, ev_x):
    """Exact piecewise integration of the stick-slip block (see the module docstring).

    Parameters
    ----------
    t, ug, vg : ndarray
        Sample times [s], horizontal and vertical (up) table acceleration [m/s^2].
    mu_s, mu_d : float
        Static and dynamic friction coefficients [-].
    gravity : float
        g [m/s^2].
    x0, v0 : float
        Initial relative displacement [m] and velocity [m/s].
    state0 : int
        Initial phase (0 stuck, +-1 sliding, 2 airborne).
    x_out, v_out, state_out : ndarray
        Filled at the samples.
    ev_t, ev_k, ev_x : ndarray
        Filled with the first ``len(ev_t)`` events (time, code, x).

    Returns
    -------
    tuple
        (n_events, peak, t_peak, episodes, reversals, time_sliding,
        time_airborne, t_first_slip, error)
    """
    n = t.size
    x = x0
    v = v0
    state = state0
    capacity = ev_t.size
    n_events = 0
    peak = abs(x)
    t_peak = t[0]
    episodes = 0
    reversals = 0
    time_sliding = 0.0
    time_airborne = 0.0
    t_first = math.nan
    error = 0
    x_out[0] = x
    v_out[0] = v
    state_out[0] = state
    for k in range(n - 1):
        h = t[k + 1] - t[k]
        a0 = ug[k]
        ka = (ug[k + 1] - ug[k]) / h
        b0 = gravity + vg[k]
        kb = (vg[k + 1] - vg[k]) / h
        tau = 0.0
        pieces = 0
        done = False
        while not done:
            pieces += 1
            if pieces > MAX_PIECES_PER_INTERVAL:
                error = 1
                break
            length = h - tau
            ua = a0 + ka * tau
            na = b0 + kb * tau
            event = 0
            if state == STUCK:
                t_air = first_up_crossing(-na, -kb, length)             # N < 0
                t_pos = first_up_crossing(ua - mu_s * na, ka - mu_s * kb, length)  # Eq. (2-2)
                t_neg = first_up_crossing(-ua - mu_s * na, -ka - mu_s * kb, length)
                te = -1.0
                for cand in (t_pos, t_neg):
                    if cand >= 0.0 and (te < 0.0 or cand < te):
                        te = cand
                if t_air >= 0.0 and (te < 0.0 or t_air <= te):
                    tau += t_air
                    state = AIRBORNE
                    event = EV_LIFTOFF
                elif te >= 0.0:
                    tau += te
                    ue = a0 + ka * tau
                    direction = ue if ue != 0.0 else ka
                    state = SLIDING_NEG if direction > 0.0 else SLIDING_POS
                    event = EV_START
                    episodes += 1
                    if math.isnan(t_first):
                        t_first = t[k] + tau
                else:
                    done = True
            elif state == AIRBORNE:
                t_land = first_up_crossing(na, kb, length)               # N > 0 again
                span = length if t_land < 0.0 else t_land
                c0 = -ua
                c1 = -ka
                x += v * span + 0.5 * c0 * span * span + c1 * span * span * span / 6.0
                v += c0 * span + 0.5 * c1 * span * span
                time_airborne += span
                if t_land < 0.0:
                    done = True
                else:
                    tau += span
                    event = EV_LAND
                    if v > 0.0:
                        state = SLIDING_POS
                    elif v < 0.0:
                        state = SLIDING_NEG
                    else:
                        state = STUCK
            else:
                s = 1.0 if state == SLIDING_POS else -1.0
                t_air = first_up_crossing(-na, -kb, length)
                end = length if t_air < 0.0 else t_air
                c0 = -ua - s * mu_d * na                                 # x'' while sliding
                c1 = -ka - s * mu_d * kb
                tr = first_velocity_zero(s * v, s * c0, 0.5 * s * c1, end)
                span = end if tr < 0.0 else tr
                x += v * span + 0.5 * c0 * span * span + c1 * span * span * span / 6.0
                v += c0 * span + 0.5 * c1 * span * span
                time_sliding += span
                if tr >= 0.0:
                    tau += span
                    v = 0.0
                    ue = a0 + ka * tau
                    ne = b0 + kb * tau
                    if abs(ue) <= mu_s * ne:
                        state = STUCK
                        event = EV_STICK
                    else:
                        state = SLIDING_NEG if ue > 0.0 else SLIDING_POS
                        event = EV_REVERSE
                        reversals += 1
                elif t_air >= 0.0:
                    tau += span
                    state = AIRBORNE
                    event = EV_LIFTOFF
                else:
                    done = True
            if abs(x) > peak:
                peak = abs(x)
                t_peak = t[k + 1] if done else t[k] + tau
            if event != 0:
                if n_events < capacity:
                    ev_t[n_events] = t[k] + tau
                    ev_k[n_events] = event
                    ev_x[n_events] = x
                n_events += 1
        x_out[k + 1] = x
        v_out[k + 1] = v
        state_out[k + 1] = state
        if error:
            break
    return (n_events, peak, t_peak, episodes, reversals, time_sliding, time_airborne,
            t_first, error)


def _check_motion(motion) -> Motion:
    if not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable Motion, got {type(motion).__name__}")
    return motion


def _check_friction(friction) -> Friction:
    if isinstance(friction, Friction):
        return friction
    if isinstance(friction, (tuple, list)) and len(friction) == 2:
        return Friction(*friction)
    try:
        return Friction.coulomb(friction)
    except ValueError as error:
        raise ValueError(f"friction: {error}") from None


def first_threshold_time(motion: Motion, coefficient: float) -> float:
    """First time |ug| > coefficient (g + vg) [s], located exactly; NaN if never.

    With ``coefficient = mu_s`` this is the start of sliding, Eq. (2-2); with
    ``coefficient = B/H`` the start of rocking, Eq. (2-1). Both sides are
    linear between samples, so the crossing is a zero of a linear function.

    Parameters
    ----------
    motion : Motion
        Table accelerations [m/s^2].
    coefficient : float
        mu_s or B/H [-].
    """
    t = motion.t
    normal = G + motion.vertical_or_zero
    best = math.nan
    for sign in (1.0, -1.0):
        f = sign * motion.horizontal - coefficient * normal
        if f[0] > 0.0:
            return float(t[0])
        above = np.flatnonzero(f[1:] > 0.0)
        if above.size == 0:
            continue
        k = int(above[0])
        crossing = t[k] + (t[k + 1] - t[k]) * (-f[k]) / (f[k + 1] - f[k])
        if not best <= crossing:
            best = float(crossing)
    return best


def mode_choice(block: Block, motion: Motion, static_friction: float) -> dict:
    """Section 2.1 of [1]_: which mode a block with static friction mu_s enters, and when.

    Rocking starts when |ug| > (B/H)(g + vg) (Eq. (2-1)), sliding when
    |ug| > mu_s (g + vg) (Eq. (2-2)). A block rocks only if mu_s > B/H and
    the rocking threshold is reached (then it is reached first); it slides
    if the sliding threshold is reached first; otherwise it moves with the
    table.

    Returns
    -------
    dict
        ``"mode"`` ("rocking", "sliding" or "moves with the table"),
        ``"mode t_start [s]"`` and both threshold times [s] (NaN if never),
        B/H, mu_s and a plain statement of what the model leaves out.
    """
    ratio = block.width / block.height
    mu_s = Friction(static_friction).static
    t_rock = first_threshold_time(motion, ratio)                     # Eq. (2-1)
    t_slide = first_threshold_time(motion, mu_s)                     # Eq. (2-2)
    if mu_s > ratio and not math.isnan(t_rock):
        mode, start = "rocking", t_rock
    elif not math.isnan(t_slide) and not (t_rock < t_slide):
        mode, start = "sliding", t_slide
    elif not math.isnan(t_rock):  # mu_s <= B/H but rocking's threshold first: cannot happen
        mode, start = "rocking", t_rock
    else:
        mode, start = "moves with the table", math.nan
    return {
        "mode (Section 2.1)": mode, "mode t_start [s]": start,
        "B/H [-]": ratio, "mode mu_s [-]": mu_s,
        "rocking threshold first reached [s]": t_rock,
        "sliding threshold first reached [s]": t_slide,
        "mode note": ("pure sliding or pure rocking only: combined sliding-rocking and "
                      "jumping are outside this model"),
    }


def slide(motion: Motion, friction, *, block: Block | None = None, x0: float = 0.0,
          v0: float = 0.0, max_recorded_events: int | None = None) -> SlidingResult:
    """Sliding response of a rigid block on the table (Coulomb stick-slip).

    Slip starts when |ug| > mu_s (g + vg) (Eq. (2-2) of [1]_); while sliding
    x'' = -ug - sign(x') mu_d (g + vg); the block sticks when x' returns to
    zero and |ug| <= mu_s (g + vg). Each piece between samples and events is
    integrated in closed form; events are located exactly.

    Parameters
    ----------
    motion : Motion
        Table accelerations [m/s^2], vertical positive up.
    friction : Friction or float or (float, float)
        Coefficients [-]: a :class:`Friction`, one mu (mu_s = mu_d), or
        ``(mu_s, mu_d)``.
    block : Block, optional
        If given, the Section 2.1 mode choice for this block and mu_s is added
        to the result (``mode_choice``, and so to ``summary()``). The sliding
        response itself does not depend on the block's size or mass.
    x0, v0 : float
        Initial relative displacement [m] and velocity [m/s]; a nonzero v0
        starts the block sliding.
    max_recorded_events : int, optional
        Events kept (all are counted); default four per sample.

    Returns
    -------
    SlidingResult

    Raises
    ------
    ValueError
        Bad friction (negative, NaN, mu_d > mu_s), bad motion or initial
        state; the message names the parameter.
    """
    motion = _check_motion(motion)
    friction = _check_friction(friction)
    for name, value in (("x0", x0), ("v0", v0)):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) \
                or not math.isfinite(value):
            raise ValueError(f"{name} must be a finite number, got {value!r}")
    t = np.ascontiguousarray(motion.t, dtype=float)
    ug = np.ascontiguousarray(motion.horizontal, dtype=float)
    vg = np.ascontiguousarray(motion.vertical_or_zero, dtype=float)
    n = t.size
    capacity = 4 * n + 16 if max_recorded_events is None else int(max_recorded_events)
    x_out, v_out = np.empty(n), np.empty(n)
    state_out = np.empty(n, dtype=np.int64)
    ev_t, ev_x = np.empty(capacity), np.empty(capacity)
    ev_k = np.empty(capacity, dtype=np.int64)
    state0 = STUCK if v0 == 0.0 else (SLIDING_POS if v0 > 0.0 else SLIDING_NEG)
    if G + vg[0] < 0.0:
        state0 = AIRBORNE
    (n_events, peak, t_peak, episodes, reversals, time_sliding, time_airborne, t_first,
     error) = stick_slip_kernel(t, ug, vg, friction.static, friction.dynamic, G, float(x0),
                                float(v0), state0, x_out, v_out, state_out, ev_t, ev_k, ev_x)
    if error:
        raise RuntimeError(f"stick-slip chatter: more than {MAX_PIECES_PER_INTERVAL} pieces in "
                           "one sample interval (please report the motion)")
    kept = min(n_events, capacity)
    if time_airborne > 0.0:
        status = "airborne"
    elif episodes > 0 or time_sliding > 0.0:
        status = "slid"
    else:
        status = "at rest"
    return SlidingResult(
        motion=motion, friction=friction, t=t.copy(), x=x_out, v=v_out, state=state_out,
        event_times=ev_t[:kept].copy(), event_kinds=ev_k[:kept].copy(),
        event_x=ev_x[:kept].copy(), peak_slip=float(peak), t_peak=float(t_peak),
        residual_slip=float(x_out[-1]), slip_episodes=int(episodes),
        reversals=int(reversals), time_sliding=float(time_sliding),
        time_airborne=float(time_airborne), t_first_slip=float(t_first), status=status,
        mode_choice={} if block is None else mode_choice(block, motion, friction.static))


def peak_slips(motions, dynamic_frictions, *, static_frictions=None):
    """Batch: peak slip for every (motion, mu_d) pair -- the sweep of Table 4.4.

    Parameters
    ----------
    motions : Motion or sequence of Motion
        Table motions [m/s^2].
    dynamic_frictions : float or sequence of float
        mu_d values [-].
    static_frictions : float or sequence of float, optional
        mu_s for each mu_d (same length); default mu_s = mu_d, the reading
        used for Table 4.4, which states only mu_d.

    Returns
    -------
    pandas.DataFrame
        One row per pair: motion, mu_s [-], mu_d [-], peak slip [m], peak slip
        [in], residual slip [m], slip episodes, time sliding [s], time airborne
        [s], run time [s].
    """
    import time

    import pandas as pd

    motions = [motions] if isinstance(motions, Motion) else list(motions)
    mu_d = np.atleast_1d(np.asarray(dynamic_frictions, dtype=float))
    mu_s = mu_d if static_frictions is None else np.atleast_1d(
        np.asarray(static_frictions, dtype=float))
    if mu_s.shape != mu_d.shape:
        raise ValueError(f"static_frictions must have one value per dynamic friction "
                         f"({mu_d.size}), got {mu_s.size}")
    rows = []
    for motion in motions:
        for static, dynamic in zip(mu_s, mu_d):
            start = time.perf_counter()
            result = slide(motion, Friction(float(static), float(dynamic)))
            rows.append({
                "motion": motion.name, "mu_s [-]": float(static), "mu_d [-]": float(dynamic),
                "peak slip [m]": result.peak_slip, "peak slip [in]": result.peak_slip_inches,
                "residual slip [m]": result.residual_slip,
                "slip episodes": result.slip_episodes,
                "time sliding [s]": result.time_sliding,
                "time airborne [s]": result.time_airborne,
                "run time [s]": time.perf_counter() - start,
            })
    return pd.DataFrame(rows)
