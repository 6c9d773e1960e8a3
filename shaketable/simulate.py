"""``simulate``: one block, one ground motion, one solver."""

from __future__ import annotations

import math

import numpy as np

from .dynamics import airborne_acceleration, block_parameters
from .geometry import Block
from .motion import MIN_SAMPLE_INTERVAL, Motion, whole_number
from .results import STATUSES, RockingResult
from .solvers import engine
from .solvers.reference import integrate_reference

#: Solvers by name. ``fast`` is the default.
METHODS = {
    "fast": "compiled Runge-Kutta-Nystrom 6(4), adaptive, with event location (numba)",
    "reference": "SciPy DOP853 with tight tolerances and Brent event location (slow)",
    "predictor-corrector": "the report's BLOKROC scheme: Heun steps, `subdivisions` per sample",
    "linear": "Housner's slender-block linearisation (Eq. 2-4), closed form between events",
}

_DEFAULT_RTOL = {"fast": 1e-11, "reference": 1e-12}
_COMPILED = {"fast": engine.METHOD_FAST,
             "predictor-corrector": engine.METHOD_PREDICTOR_CORRECTOR,
             "linear": engine.METHOD_LINEAR}


def _check_method(method: str) -> str:
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; expected one of {sorted(METHODS)}")
    return method


def _check_number(name, value, low=-math.inf, high=math.inf, low_open=False):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if number < low or number > high or (low_open and number == low):
        bracket = "(" if low_open else "["
        raise ValueError(f"{name} must be in {bracket}{low}, {high}], got {value!r}")
    return number


def _extended(motion: Motion, duration: float | None) -> Motion:
    """The motion cut or padded with zeros (table at rest) to end at exactly ``duration``.

    Cut: the samples before ``t[0] + duration`` and one at that time,
    interpolated linearly (exact: a motion is linear between samples); a
    sample already within rounding of it is kept as it is. Padded: zeros
    every ``motion.dt`` after the last sample, the last interval shortened
    to end at ``t[0] + duration``.
    """
    if duration is None:
        return motion
    t = motion.t
    end = t[0] + duration
    tolerance = max(1e-9 * motion.dt, MIN_SAMPLE_INTERVAL)
    if end <= t[-1] + tolerance:
        k = int(np.searchsorted(t, end - tolerance, side="left"))
        if t[k] <= end + tolerance:       # a sample at the end already
            times, index = t[:k + 1], slice(0, k + 1)
            interpolate = False
        else:
            times, index = np.append(t[:k], end), slice(0, k)
            interpolate = True
        if times.size < 2:
            raise ValueError(f"duration {duration!r} s is shorter than the shortest accepted "
                             f"sample interval {MIN_SAMPLE_INTERVAL:g} s")

        def cut(values):
            if values is None:
                return None
            if not interpolate:
                return values[index]
            return np.append(values[index], np.interp(end, t, values))

        return Motion(times, cut(motion.horizontal), cut(motion.vertical), name=motion.name,
                      rotation=cut(motion.rotation))
    dt = motion.dt
    extra = int(math.ceil((end - t[-1]) / dt - 1e-9))
    added = t[-1] + dt * np.arange(1, extra + 1)
    added[-1] = end
    if added.size > 1 and end - added[-2] < tolerance:
        added = np.delete(added, -2)
    times = np.concatenate([t, added])

    def padded(values):
        return None if values is None else np.concatenate([values, np.zeros(added.size)])

    return Motion(times, padded(motion.horizontal), padded(motion.vertical), name=motion.name,
                  rotation=padded(motion.rotation))


def simulate(block: Block, motion: Motion | None = None, *, cor: float, theta0: float = 0.0,
             theta_dot0: float = 0.0, duration: float | None = None, method: str = "fast",
             rtol: float | None = None, subdivisions: int = 4, output_dt: float = 0.005,
             rest_tolerance: float | None = None, max_recorded_impacts: int = 100_000,
             top_force: float = 0.0) -> RockingResult:
    """Rocking response of a rigid block, Eqs. (2-13)/(2-14) with impacts.

    Parameters
    ----------
    block : Block
        The block (with optional prestress rods).
    motion : Motion, optional
        Ground accelerations [m/s^2]. ``None`` is free rocking on a table at
        rest (Figs. 2.9, 2.10, 3.4): give ``duration``.
    cor : float
        Coefficient of restitution [-] in [0, 1] (Section 2.7 (5)).
    theta0 : float
        Initial rotation [rad], |theta0| < pi/2.
    theta_dot0 : float
        Initial angular velocity [rad/s].
    duration : float, optional
        Length of the run [s]; the run ends at exactly ``t[0] + duration``.
        With a motion, the motion is cut there (the last sample interpolated
        linearly when it falls between samples) or continued with the table
        at rest.
    method : str
        One of :data:`METHODS`: ``"fast"`` (default), ``"reference"``,
        ``"predictor-corrector"``, ``"linear"``.
    rtol : float, optional
        Relative tolerance of the adaptive methods [-] (fast 1e-11,
        reference 1e-12 by default).
    subdivisions : int
        Equal parts each input interval is divided into by the
        predictor-corrector (Section 2.8): an integer >= 1 (``2.7`` is
        refused, not truncated).
    output_dt : float
        Output interval for free rocking [s]: output at 0, output_dt,
        2 output_dt, ... and at ``duration`` (:meth:`Motion.at_rest`), never
        beyond it.
    rest_tolerance : float, optional
        Remaining duration of an impact cascade [s] below which it is summed in
        closed form (default 1e-6 / p).
    max_recorded_impacts : int
        Impacts kept in ``impact_times`` (all are counted), an integer >= 0.
    top_force : float
        Constant horizontal force at the middle of the top of the block per
        unit mass [m/s^2], positive along +x: one potentiometer wire
        (Section 3.3); two opposite wires cancel.

    Returns
    -------
    RockingResult

    Raises
    ------
    ValueError
        For invalid parameters; the message names the parameter.
    shaketable.solvers.reference.ReferenceSolverError
        ``method="reference"`` only: SciPy's integrator gave up or made no
        progress.
    """
    if not isinstance(block, Block):
        raise ValueError(f"block must be a shaketable.Block, got {type(block).__name__}")
    method = _check_method(method)
    cor = _check_number("cor", cor, 0.0, 1.0)
    theta0 = _check_number("theta0", theta0)
    theta_dot0 = _check_number("theta_dot0", theta_dot0)
    if abs(theta0) >= math.pi / 2:
        raise ValueError(f"theta0 must satisfy |theta0| < pi/2 rad, got {theta0!r}")
    if duration is not None:
        duration = _check_number("duration", duration, 0.0, low_open=True)
    if motion is None:
        if duration is None:
            raise ValueError("free rocking (motion=None) needs a duration [s]")
        motion = Motion.at_rest(duration, _check_number("output_dt", output_dt, 0.0,
                                                        low_open=True))
    elif not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable.Motion or None, got {type(motion).__name__}")
    else:
        motion = _extended(motion, duration)
    if rtol is None:
        rtol = _DEFAULT_RTOL.get(method, 1e-10)
    rtol = _check_number("rtol", rtol, 0.0, 1.0, low_open=True)
    subdivisions = whole_number("subdivisions", subdivisions)
    rest = -1.0 if rest_tolerance is None else _check_number("rest_tolerance", rest_tolerance,
                                                             0.0)

    parameters = block_parameters(block, _check_number("top_force", top_force))
    t_grid = np.ascontiguousarray(motion.t)
    ug = np.ascontiguousarray(motion.horizontal)
    vg = np.ascontiguousarray(motion.vertical_or_zero)
    rg = np.ascontiguousarray(motion.rotation_or_zero)
    n = t_grid.size
    theta, omega, acceleration = np.zeros(n), np.zeros(n), np.zeros(n)
    impact_times = np.zeros(max(1, whole_number("max_recorded_impacts", max_recorded_impacts,
                                                minimum=0)))
    impact_velocities = np.zeros_like(impact_times)
    info = np.zeros(engine.N_INFO)
    if method == "reference":
        integrate_reference(t_grid, ug, vg, rg, parameters, block.alpha, block.p, cor, theta0,
                            theta_dot0, rtol, rest, theta, omega, acceleration, impact_times,
                            impact_velocities, info)
    else:
        engine.integrate(_COMPILED[method], t_grid, ug, vg, rg, parameters, cor, theta0, theta_dot0,
                         rtol, subdivisions, rest, theta, omega, acceleration, impact_times,
                         impact_velocities, info)
    return _result(block, motion, cor, method, t_grid, theta, omega, acceleration,
                   impact_times, impact_velocities, info)


def _result(block, motion, cor, method, t_grid, theta, omega, acceleration, impact_times,
            impact_velocities, info) -> RockingResult:
    filled = int(info[engine.INFO_N_OUTPUT])
    status = STATUSES[int(info[engine.INFO_STATUS])]
    t = t_grid[:filled]
    theta, omega, acceleration = theta[:filled], omega[:filled], acceleration[:filled]
    t_end = info[engine.INFO_T_END]
    if status != "completed" and t_end > t[-1]:
        t = np.append(t, t_end)
        theta = np.append(theta, info[engine.INFO_THETA_END])
        omega = np.append(omega, info[engine.INFO_THETA_DOT_END])
        acceleration = np.append(acceleration, np.nan if status == "airborne" else 0.0)
        if status == "overturned":
            acceleration[-1] = acceleration[-2]
    if status == "airborne":
        acceleration[-1] = acceleration[-2] if acceleration.size > 1 else 0.0
    n_impacts = int(info[engine.INFO_N_IMPACTS])
    kept = min(n_impacts, impact_times.size)

    def direction(index):
        value = info[index]
        return 0 if not np.isfinite(value) else int(value)

    return RockingResult(
        block=block, motion=motion, cor=cor, method=method, t=t, theta=theta, theta_dot=omega,
        theta_ddot=acceleration, impact_times=impact_times[:kept].copy(),
        impact_velocities=impact_velocities[:kept].copy(),
        t_start=info[engine.INFO_T_START], t_unstable=info[engine.INFO_T_UNSTABLE],
        unstable_direction=direction(engine.INFO_UNSTABLE_DIRECTION),
        t_overturn=info[engine.INFO_T_OVERTURN],
        overturn_direction=direction(engine.INFO_OVERTURN_DIRECTION),
        t_airborne=info[engine.INFO_T_AIRBORNE], t_rest=info[engine.INFO_T_REST],
        max_abs_theta=info[engine.INFO_MAX_ABS_THETA], t_max=info[engine.INFO_T_MAX],
        n_impacts=n_impacts, cascades=int(info[engine.INFO_CASCADES]), status=status,
        statistics={"steps": int(info[engine.INFO_STEPS]),
                    "rejected": int(info[engine.INFO_REJECTED]),
                    "evaluations": int(info[engine.INFO_EVALUATIONS])},
    )


def airborne_limit(block: Block) -> float:
    """Vertical acceleration at which the block leaves the ground [m/s^2] (re-export)."""
    return airborne_acceleration(block)
