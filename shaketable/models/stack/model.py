"""The stack model behind the package's one interface, and its one run."""

from __future__ import annotations

import math
import os
import sys
import types
import warnings
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from shaketable.core.motion import Motion
from shaketable.core.validation import in_range, positive
from shaketable.models.base import ModelResult
from shaketable.models.stack.geometry import Stack
from shaketable.models.stack.result import PLAUSIBLE_FRICTION, StackResult

#: The impact laws offered.
IMPACT_LAWS = ("plastic", "cor")
#: The engines offered: the compiled one (numba; default) and the Python one (SciPy's
#: DOP853 with events), which runs the same algorithm.
STACK_METHODS = ("compiled", "reference")


class StackTensionWarning(UserWarning):
    """A contact of the stack carried a tensile force: the no-flight assumption failed."""


class StackFrictionWarning(UserWarning):
    """A contact of the stack needed more friction than
    :data:`~shaketable.models.stack.result.PLAUSIBLE_FRICTION`: the no-slip assumption
    failed."""


class StackRetryWarning(UserWarning):
    """A run stopped with events without end
    (:class:`~shaketable.models.stack.engine.StackChatter`) and was run again at a tighter
    tolerance (:func:`integrate_retrying`)."""


class StackStalledWarning(UserWarning):
    """A run of a stack batch could not be continued at any tolerance tried
    (:class:`~shaketable.models.stack.engine.StackStalled`): its row says "stalled" and
    holds no results; the other runs go on."""


#: The divisors of ``rtol`` of the runs made again after a chatter stall, in turn.
RETRY_DIVISORS = (10.0, 100.0)
#: The tightest tolerance a run is made again at [-].
TIGHTEST_RTOL = 1e-14


def integrate_retrying(integrate, stack: Stack, motion: Motion, *, rtol: float,
                       **options: Any) -> tuple[dict, float, str]:
    """``integrate(stack, motion, rtol=rtol, **options)``; where it stalls in the chatter of
    a contact at its uplift threshold, again at ``rtol`` divided by each of
    :data:`RETRY_DIVISORS` (never below :data:`TIGHTEST_RTOL`).

    The chatter (a landing at the noise level, the uplift chosen again, the next landing
    ...; :class:`~shaketable.models.stack.engine.StackChatter`) comes from the rounding of
    the tolerance's own steps, not from the motion: a tighter tolerance, which is also more
    accurate, takes other steps. A run that completes at the tolerance asked is the same
    bits as without this function.

    Returns
    -------
    (dict, float, str)
        The engine's output, the tolerance it was computed at [-], and a note saying where
        the runs before it stalled ("" when the first completed).

    Raises
    ------
    StackChatter
        Every tolerance stalled (the message lists them).
    StackStalled
        A run that cannot go on otherwise. Both carry the last tolerance tried as their
        ``rtol`` attribute [-].
    """
    from shaketable.models.stack.engine import StackChatter, StackStalled

    stalls: list[str] = []
    tolerances = [rtol] + [max(rtol / divisor, TIGHTEST_RTOL) for divisor in RETRY_DIVISORS]
    for tolerance in dict.fromkeys(tolerances):   # in turn, each once
        try:
            out = integrate(stack, motion, rtol=tolerance, **options)
        except StackChatter as error:
            stalls.append(f"at rtol {tolerance:g}: {error}")
            continue
        except StackStalled as error:
            if not stalls:
                error.rtol = tolerance  # type: ignore[attr-defined]
                raise
            # a retry that fails otherwise: the stalls before it are said first
            failed = StackStalled(f"{'; '.join(stalls)}; run again at rtol {tolerance:g}: "
                                  f"{error}")
            failed.rtol = tolerance  # type: ignore[attr-defined]
            raise failed from None
        note = ("" if not stalls else
                f"the run stalled ({'; '.join(stalls)}) and was run again at rtol "
                f"{tolerance:g}")
        return out, tolerance, note
    chatter = StackChatter("; ".join(stalls) + " (events without end at every tolerance "
                           "tried)")
    chatter.rtol = tolerance  # type: ignore[attr-defined]  # the last tried
    raise chatter


def _user_stacklevel() -> int:
    """The ``stacklevel`` of :func:`warnings.warn`, called from the caller of this function,
    that points at the first frame outside the package: the user's call, however many of
    the package's functions (``shaketable.simulate``, the model registry) lie between."""
    package = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    frame: types.FrameType | None = sys._getframe(1)
    level = 1
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(
            package + os.sep):
        frame = frame.f_back
        level += 1
    return level


def user_location() -> tuple[str, int, dict | None]:
    """The file, line and module globals of the first frame outside the package (the
    user's call), where :func:`simulate_stack`'s warnings point (``_user_stacklevel``);
    found in the calling thread, so that a warning raised in another thread (a batch's
    worker, :func:`warnings.warn_explicit`) points there too; ``("sys", 1, None)`` past
    the stack's top, as :func:`warnings.warn`."""
    try:
        frame = sys._getframe(_user_stacklevel() - 1)
    except ValueError:
        return "sys", 1, None
    return frame.f_code.co_filename, frame.f_lineno, frame.f_globals


def simulate_stack(stack: Stack, motion: Motion | None = None, *, impact: str = "plastic",
                   cor: float | None = None, theta0=None, theta_dot0=None,
                   duration: float | None = None, rtol: float = 1e-12,
                   rest_tolerance: float | None = None, output_dt: float = 0.005,
                   max_recorded_events: int = 100_000, method: str = "compiled") -> StackResult:
    """Rocking response of a column of rigid blocks (``docs/stack.md``).

    Parameters
    ----------
    stack : Stack
    motion : Motion, optional
        The table's accelerations [m/s^2]; ``None``: free rocking for ``duration``.
    impact : {"plastic", "cor"}
        The impact law: the plastic, no-slip multi-contact law (default; Housner's
        1 - 1.5 sin^2(alpha) for one block) or the constant COR ``cor`` (every block's rate
        times ``cor``, the report's Section 2.7 (5) for one block).
    cor : float, optional
        The constant COR [-] in [0, 1]; only with ``impact="cor"`` (a float given alone
        selects that law).
    theta0, theta_dot0 : sequence of float, optional
        Each block's initial absolute rotation [rad] and rate [rad/s] (default zeros).
    duration : float, optional
        Length of free rocking [s] (``motion=None`` only).
    rtol : float
        The integrators' relative tolerance [-] (DOP853's, and in the compiled engine's one-DOF
        patterns the single block's RKN6(4)'s). A run that stalls in the chatter of a contact
        at its uplift threshold is made again at rtol/10, then rtol/100
        (:func:`integrate_retrying`, a :class:`StackRetryWarning`); ``statistics["rtol"]``
        is the tolerance the result was computed at.
    rest_tolerance : float, optional
        Remaining time of an impact cascade summed in closed form [s] (default
        1e-6 / p of the bottom block, as the single-block engine).
    output_dt : float
        Output interval of free rocking [s].
    max_recorded_events : int
        Events kept in the result (all are counted).
    method : {"compiled", "reference"}
        The engine: ``"compiled"`` (numba, default; its first run in a fresh cache
        compiles it: the one-DOF patterns with the single block's RKN6(4) stepper, the others
        with DOP853) or ``"reference"`` (the same algorithm in Python on SciPy's
        ``solve_ivp``, DOP853 throughout, about a hundred times slower). They agree to the
        tolerance's level (``docs/stack.md``, validation).
    """
    if method not in STACK_METHODS:
        raise ValueError(f"method must be one of {STACK_METHODS}, got {method!r}")
    if method == "compiled":
        from shaketable.models.stack.compiled import integrate  # numba on use
    else:
        from shaketable.models.stack.engine import integrate  # SciPy on use

    if not isinstance(stack, Stack):
        raise TypeError(f"stack must be a Stack, got {type(stack).__name__}")
    if impact not in IMPACT_LAWS:
        raise ValueError(f"impact must be one of {IMPACT_LAWS}, got {impact!r}")
    if impact == "cor":
        if cor is None:
            raise ValueError("impact='cor' needs cor, the coefficient of restitution [-]")
        cor = in_range("cor", cor, 0.0, 1.0)
    elif cor is not None:
        raise ValueError("cor is given with impact='plastic': give impact='cor' for the "
                         "constant-COR law")
    n = stack.n
    theta0 = _per_block("theta0", theta0, n)
    theta_dot0 = _per_block("theta_dot0", theta_dot0, n)
    if np.any(np.abs(np.diff(theta0, prepend=0.0)) >= 0.5 * math.pi):
        raise ValueError("theta0: every interface's relative rotation must be below pi/2")
    if motion is None:
        if duration is None:
            raise ValueError("free rocking (motion None) needs duration [s]")
        motion = Motion.at_rest(positive("duration", duration, " [s]"), output_dt)
    elif duration is not None:
        raise ValueError("duration is for free rocking only (the motion sets the run's length)")
    elif not isinstance(motion, Motion):
        raise TypeError(f"motion must be a shaketable.Motion, got {type(motion).__name__}")
    rtol = in_range("rtol", rtol, 1e-14, 1e-3)
    rest = (1e-6 / stack.blocks[0].p if rest_tolerance is None
            else positive("rest_tolerance", rest_tolerance, " [s]"))
    out, rtol, retried = integrate_retrying(
        integrate, stack, motion, law=impact, cor=1.0 if cor is None else cor, theta0=theta0,
        theta_dot0=theta_dot0, rtol=rtol, rest_tolerance=rest,
        max_recorded_events=int(max_recorded_events))
    run = out["run"]
    # the motion uses the masses' ratios only; forces, work and energies are in kg units
    # (the engines' arrays are the run's own: scaled in place)
    scale = stack.mass_scale
    forces, work = out["forces"], out["work"]
    forces *= scale
    work *= scale
    scaled = getattr(run, "scaled_events", None)   # the compiled engine's: column by column
    events = tuple(scaled(scale) if scaled is not None else
                   (_scaled_energies(event, scale) for event in run.events))
    result = StackResult(
        stack=stack, motion=motion, impact=impact, cor=math.nan if cor is None else cor,
        t=motion.t[:out["filled"]].copy(), theta=out["theta"], theta_dot=out["rate"],
        theta_ddot=out["acceleration"], patterns=out["patterns"],
        forces=forces, work=work, events=events,
        status=run.status, t_overturn=run.t_overturn,
        overturned_block=run.overturned_block, t_airborne=run.t_airborne,
        n_events=run.n_events, statistics={"steps": run.steps, "evaluations": run.evaluations,
                                           "rtol": rtol})
    if retried:
        warnings.warn(retried, StackRetryWarning, stacklevel=_user_stacklevel())
    tension = result.t_tension
    if not math.isnan(tension):
        warnings.warn(f"a contact of the stack carried a tensile force from t = "
                      f"{tension:.6g} s: the model (no flight) is outside its "
                      "assumptions there" + _while_falling(tension, result.t_past_alpha),
                      StackTensionWarning, stacklevel=_user_stacklevel())
    slip = result.t_friction_exceeded(PLAUSIBLE_FRICTION)
    if not math.isnan(slip):
        warnings.warn(f"a contact of the stack needed a friction coefficient F/N above "
                      f"{PLAUSIBLE_FRICTION:g} from t = {slip:.6g} s: real blocks would slide "
                      "there, the model (no slip) is outside its assumptions"
                      + _while_falling(slip, result.t_past_alpha),
                      StackFrictionWarning, stacklevel=_user_stacklevel())
    return result


def _while_falling(t_outside: float, t_past_alpha: float) -> str:
    """What a warning adds when the model leaves its assumptions only after a block passed
    its alpha: the column was already falling, the fall is the model's answer, the motion
    of the fall is not."""
    if math.isnan(t_past_alpha) or t_outside < t_past_alpha:
        return ""
    return (f" (after a block passed its alpha at t = {t_past_alpha:.6g} s: the column was "
            "already falling; the motion of the fall is outside the model, not the fall)")


def _scaled_energies(event: dict, scale: float) -> dict:
    """An event with its energies [J] in the stack's masses (:attr:`Stack.mass_scale`)."""
    if scale == 1.0:
        return event
    return {key: value * scale if key in ("energy_before", "energy_after") else value
            for key, value in event.items()}


def _per_block(name: str, values, n: int) -> np.ndarray:
    if values is None:
        return np.zeros(n)
    array = np.atleast_1d(np.asarray(values, dtype=float))
    if array.shape != (n,) or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must give {n} finite values (one per block), got {values!r}")
    return array


class StackModel:
    """The stack model behind :class:`~shaketable.models.base.Model`."""

    name: str = "stack"

    def accepts(self, subject: Any) -> bool:
        return isinstance(subject, Stack)

    def validate(self, subject: Any, options: Mapping[str, Any]) -> dict[str, Any]:
        """The options of :func:`simulate_stack` from those of ``shaketable.simulate``."""
        options = dict(options)
        friction = options.pop("friction", None)
        if friction is not None:
            raise ValueError("friction is not offered for a Stack: the stack model does not "
                             "slide (it reports the friction each contact needs: "
                             "StackResult.friction_demand)")
        method = options.pop("method", "fast")
        if method not in ("fast",) + STACK_METHODS:
            raise ValueError(f"method for a Stack is one of {STACK_METHODS} (default "
                             f"'compiled'), got {method!r}")
        options["method"] = "compiled" if method == "fast" else method
        for key, default in (("top_force", 0.0), ("subdivisions", 4)):
            if key in options and options.pop(key) != default:
                raise ValueError(f"{key} is not offered for a Stack")
        options.pop("max_recorded_impacts", None)
        for key in ("theta0", "theta_dot0"):   # the block's scalar default: the stack's zeros
            value = options.get(key, 0.0)
            if np.ndim(value) == 0 and value == 0.0:
                options.pop(key, None)
        if options.get("rtol", 0.0) is None:
            options.pop("rtol")
        cor = options.pop("cor", None)
        if isinstance(cor, str):
            if cor != "plastic":
                raise ValueError(f"cor for a Stack is a number (the constant-COR law) or "
                                 f"'plastic', got {cor!r}")
            cor = None
        if cor is not None:
            options.setdefault("impact", "cor")
        if "impact" not in options:
            options["impact"] = "plastic"
        options["cor"] = cor
        return options

    def run(self, subject: Any, motion: Any, **options: Any) -> StackResult:
        return simulate_stack(subject, motion, **self.validate(subject, options))

    def run_many(self, subject: Any, motions: Iterable[Any], *, threads: int | None = None,
                 **options: Any) -> list[ModelResult]:
        """One run of the stack per motion (the compiled engine releases the GIL: the runs
        share ``threads`` threads, default numba's thread count), in the motions' order."""
        from concurrent.futures import ThreadPoolExecutor

        import numba

        motions = list(motions)
        options = self.validate(subject, options)
        count = numba.get_num_threads() if threads is None else int(threads)
        if count < 1:
            raise ValueError(f"threads must be a positive integer, got {threads!r}")
        if count == 1 or len(motions) < 2:
            return [simulate_stack(subject, motion, **options) for motion in motions]
        with ThreadPoolExecutor(max_workers=min(count, len(motions))) as pool:
            return list(pool.map(lambda motion: simulate_stack(subject, motion, **options),
                                 motions))


STACK_MODEL = StackModel()
