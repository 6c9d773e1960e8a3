"""Coefficient of restitution from a free-rocking record (Section 3.5 of the report, done rigorously).

The report released the 30 x 6 in block from theta0 < alpha on a table at rest,
digitized the angle at 50 samples/s and overlaid BLOKROC curves for several
COR values "by eye" (Section 3.5, Fig. 3.4: COR = 0.925). Here:

* :func:`calibrate` -- least squares on the whole record with the engine in
  the loop (``method="fast"``): the COR nu, the release angle theta0, the
  release time t_r and the sensor offset c are the parameters of::

      y_k = S(F[theta(t; nu, theta0, t_r)])(t_k) + c + e_k

  where theta(t) = theta0 for t < t_r (the block is held) and the engine's
  free rocking from (theta0, 0) after it (Eqs. 2-3, 2-6: rest between the
  impacts' cascades, then theta = 0), F is the record's quantity (the angle,
  or the exact top displacement of :func:`shaketable.lab.sensors.top_displacement`)
  and S the acquisition's anti-alias filter. S is not optional: left out,
  its smoothing of each impact's velocity jump biases nu by up to two
  standard errors (e.g. 5e-5 at nu = 0.80, 1e-5 at 0.925, nearly nothing at
  0.98, for 50 samples/s and a 20 Hz 4-pole filter; the bias changes with nu
  and theta0), and the interval then misses the truth in up to a quarter of
  the records (benchmarks/CALIBRATION.md). So by default
  (``anti_alias="fit"``) S is an analog Butterworth low-pass whose cutoff is
  a fifth parameter (order 1, 2, 4 or 8, the best fit kept), discretised
  exactly for the piecewise-linear fine-grid signal; a known filter is
  given as a :class:`~shaketable.lab.digitizer.Digitizer`.
  The 95 % interval of nu comes from the Jacobian J at the optimum with the
  sandwich covariance ``(J^T J)^-1 J^T Sigma J (J^T J)^-1``, Sigma the
  Toeplitz matrix of the residuals' autocovariance (``interval="acf"``: the
  noise of a filtered 50 samples/s record is correlated, lag-1 ~ 0.1, but
  stationary); ``"hac"`` (Newey-West, per-sample e_t e_s: robust to
  heteroscedastic noise but noisier, 6 % narrower on average on the benchmark's
  records),
  ``"iid"`` the textbook ``s^2 (J^T J)^-1``, and ``bootstrap=N`` a
  moving-block bootstrap.
* :func:`peak_estimate` -- an independent estimate from successive peak
  amplitudes with the exact energy relation (Eq. 2-6; theory.amplitude_after_impact)::

      cos(alpha - theta_{n+1}) - cos(alpha) = nu^2 [cos(alpha - theta_n) - cos(alpha)]

  fitted as log E_n = log E_0 + 2 n log nu, and the COR of each impact against
  its impact velocity (the report's Section 3.7 (1) claim that the COR does
  not depend on it becomes a slope with an interval).
* :func:`period_fit` -- periods measured the report's way (time from a peak
  to the next zero, times 4; Section 3.7 (1), Table 3.1) fitted with the exact
  period of Eq. (2-3) (:func:`shaketable.core.theory.exact_period`) for the
  block's effective size R and slenderness alpha.
* :func:`predict`, :func:`compare_free_rocking`, :func:`reproduce_fig_3_4` --
  the calibrated COR fed back into the theory run (Section 3.7 (1), Fig. 3.4).

Inputs are :class:`FreeRockingRecord` objects (time and angle, or time and top
displacement with the block height), built directly, from a
:class:`~shaketable.lab.sensors.Measurement` or read from a CSV or plain-text file
(:func:`read_record`).
A record without rocking, too short, clipped or too noisy raises
:class:`CalibrationError` with a message saying which.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, *Rocking and overturning
   response of rigid bodies to earthquake motions*, Lawrence Berkeley
   Laboratory, University of California, Berkeley (program BLOKROC).
"""

from __future__ import annotations

import math
import numbers
import time as _time
from typing import Any

import numpy as np
import scipy.optimize
import scipy.signal
import scipy.stats

from shaketable.calibration.covariance import bandwidth, sandwich_covariance
from shaketable.calibration.diagnostics import diagnose
from shaketable.calibration.filters import butterworth_delay
from shaketable.calibration.model import (
    PARAMETERS,
    TAU_FLOOR,
    FreeRockingModel,
    model_jacobian,
)
from shaketable.calibration.peaks import (
    noise_level,
    peak_estimate,
    period_fit,
    threshold_crossings,
    zero_time,
)
from shaketable.calibration.record import (
    FILTER_ORDERS,
    INTERVALS,
    CalibrationError,
    FreeRockingRecord,
)
from shaketable.calibration.result import Calibration
from shaketable.calibration.scatter import cor_scatter
from shaketable.core.geometry import Block
from shaketable.core.theory import exact_period
from shaketable.lab.digitizer import Digitizer


# ------------------------------------------------------------------ calibrate
def _check_record(record: FreeRockingRecord, block: Block,
                  stroke: float | None) -> tuple[np.ndarray, float, float, list[int]]:
    """Clear messages for records that cannot give a COR.

    Returns (theta [rad], noise sigma [rad], offset guess [record unit], zero crossings).
    """
    t, values = record.t, record.values
    if t.size < 20:
        raise CalibrationError(f"record {record.name!r} has {t.size} samples: too short "
                               "(at least 20 are needed)")
    flags = np.zeros(t.size, dtype=bool) if record.clipped is None else record.clipped.copy()
    if stroke is not None:
        flags |= np.abs(values) >= stroke * (1 - 1e-9)
    # a flat top: a run of equal samples at the record's extreme lasting >= 0.08 s (and >= 4
    # samples), away from the start (where the block may be held). A free-rocking peak curves
    # by p^2 sin(alpha - theta) tau^2 / 2 ~ 1e-3 rad over +-0.04 s, several ADC steps.
    shortest = max(4, int(math.ceil(0.08 / record.dt)))
    for extreme in (np.max(values), np.min(values)):
        at = np.flatnonzero(np.abs(values - extreme) <= 1e-12 * max(1.0, abs(extreme)))
        if at.size >= shortest and at[0] > 0.1 * t.size:
            runs = np.split(at, np.flatnonzero(np.diff(at) > 1) + 1)
            if max(len(run) for run in runs) >= shortest:
                flags[at] = True
    if np.any(flags):
        first = int(np.flatnonzero(flags)[0])
        raise CalibrationError(
            f"record {record.name!r} is clipped ({np.count_nonzero(flags)} samples, first at "
            f"t = {t[first]:.3f} s): the sensor's range was reached, the peaks are lost")
    # the offset is the reading at rest: the end of the record if the block rests there
    tail = values[-max(5, t.size // 10):]
    at_rest = np.std(tail) < 0.02 * np.ptp(values)
    offset_guess = float(np.median(tail)) if at_rest else 0.0
    theta = record.to_angle(values - offset_guess, block)
    sigma = noise_level(theta)
    amplitude = float(np.max(np.abs(theta)))
    if amplitude >= block.alpha:
        raise CalibrationError(f"record {record.name!r} exceeds alpha ({amplitude:.3f} rad > "
                               f"{block.alpha:.3f} rad): not free rocking (overturning?)")
    crossings = threshold_crossings(theta, max(4 * sigma, 1e-3 * block.alpha))
    if amplitude < 10 * sigma or amplitude < 0.01 * block.alpha or not crossings:
        raise CalibrationError(
            f"record {record.name!r} shows no rocking: largest excursion {amplitude:.3g} rad "
            f"({amplitude / block.alpha:.3f} alpha), noise {sigma:.3g} rad, "
            f"{len(crossings)} zero crossing(s)")
    if sigma > 0.05 * amplitude:
        raise CalibrationError(
            f"record {record.name!r} is too noisy to decide: noise {sigma:.3g} rad is "
            f"{100 * sigma / amplitude:.1f} % of the amplitude {amplitude:.3g} rad (limit 5 %)")
    if len(crossings) < 2:
        raise CalibrationError(
            f"record {record.name!r} is too short: {len(crossings)} impact(s) in "
            f"{record.duration:.2f} s; at least 2 are needed to separate the COR from the "
            "release angle")
    return theta, sigma, offset_guess, crossings


def _filter_mode(anti_alias: object) -> tuple[str, Digitizer | None]:
    """("none" | "known" | "fit", Digitizer or None) for the ``anti_alias`` argument."""
    if anti_alias is None or (isinstance(anti_alias, str) and anti_alias == "none"):
        return "none", None
    if isinstance(anti_alias, str) and anti_alias == "fit":
        return "fit", None
    if isinstance(anti_alias, Digitizer):
        return ("known", anti_alias) if anti_alias.anti_alias else ("none", None)
    raise ValueError(f"anti_alias must be 'fit', 'none', None or a shaketable.lab.digitizer.Digitizer, "
                     f"got {anti_alias!r}")


def _filter_orders(filter_order: object) -> tuple[int, ...]:
    """The Butterworth orders to fit for the ``filter_order`` argument ("auto" or 1 to 8)."""
    if isinstance(filter_order, str) and filter_order == "auto":
        return FILTER_ORDERS
    if isinstance(filter_order, (bool, str)) or not isinstance(filter_order, numbers.Real) \
            or not float(filter_order).is_integer() or not 1 <= float(filter_order) <= 8:
        raise ValueError(f"filter_order must be 'auto' or an integer from 1 to 8, got "
                         f"{filter_order!r}")
    return (int(float(filter_order)),)


def calibrate(record: FreeRockingRecord, block: Block, *,
              anti_alias: str | Digitizer | None = "fit", filter_order: int | str = "auto",
              interval: str = "acf", bootstrap: int = 0, seed: int | None = None,
              stroke: float | None = None, rtol: float = 1e-9,
              max_interval: float = 0.05) -> Calibration:
    """Identify the COR, release angle, release time and offset of a free-rocking record.

    Parameters
    ----------
    record : FreeRockingRecord
        The whole record (may begin before the release and end long after rest).
    block : Block
        The nominal block (Eq. 2-3 needs alpha and p).
    anti_alias : {"fit", "none", None} or Digitizer
        The acquisition's anti-alias filter in the model. ``"fit"`` (default,
        for an acquisition whose filter is not known): an analog Butterworth
        low-pass of ``filter_order`` poles whose cutoff is a fifth parameter
        (from no filter at all to 0.05 x the sample rate). This removes the
        bias an unmodelled filter leaves in the COR (its smoothing of each
        impact's velocity jump: e.g. 5e-5 at COR 0.80, 1e-5 at 0.925 for the
        report's 50 samples/s with a 20 Hz filter, up to two standard errors;
        benchmarks/CALIBRATION.md), and its uncertainty enters the interval.
        A :class:`~shaketable.lab.digitizer.Digitizer`: that known filter, exactly.
        ``"none"``/``None``: no filter (a record known to be unfiltered; the
        delay of an unknown filter is then absorbed by the release time, its
        smoothing is not).
    filter_order : int or "auto"
        Poles of the fitted Butterworth filter (``anti_alias="fit"``), 1 to 8.
        ``"auto"`` (default) fits each of :data:`FILTER_ORDERS` (1, 2, 4, 8
        poles) and keeps the smallest residual sum of squares: a wrong order
        leaves a model error that the interval does not cover (a 2-pole
        10 Hz filter fitted as 4-pole: 78-88 % coverage, chosen: 94-98 %,
        benchmarks/CALIBRATION.md), and it shows in the residuals.
    interval : str
        ``"acf"`` (default), ``"hac"`` or ``"iid"``, see :data:`INTERVALS`.
    bootstrap : int
        Number of moving-block bootstrap refits (0: none). The blocks are
        4 x the lag window long; the percentile interval is stored in
        ``bootstrap_interval`` and becomes ``cor_interval``.
    seed : int, optional
        Seed of the bootstrap.
    stroke : float, optional
        Range of the sensor [record unit]; values at it count as clipped.
    rtol : float
        Relative tolerance of the engine in the loop [-].
    max_interval : float
        Largest acceptable half-width of the 95 % interval [-]; wider means
        the record is too noisy to decide.

    Returns
    -------
    Calibration

    Raises
    ------
    CalibrationError
        No rocking, too short, clipped or too noisy (the message says which).
    ValueError
        Bad arguments, naming the argument.
    """
    started = _time.perf_counter()
    mode, digitizer, orders = _check_arguments(record, block, interval, anti_alias,
                                               filter_order, bootstrap)
    theta, sigma, offset_guess, crossings = _check_record(record, block, stroke)
    notes: list[str] = []
    x0, lower, upper, scales, steps = _initial_guess(record, block, theta, sigma,
                                                     offset_guess, crossings)
    model, solution, models, lower, upper, scales, steps = _fit(
        record, block, mode, digitizer, orders, rtol, x0, lower, upper, scales, steps)
    t = record.t
    x = solution.x
    fitted = model(x)
    res = record.values - fitted
    jacobian = model_jacobian(model, x, steps, lower, upper)
    lags = bandwidth(t.size)
    covariance = sandwich_covariance(jacobian, res, interval, lags)
    se = np.sqrt(np.clip(np.diag(covariance), 0.0, None))
    quantile = scipy.stats.t.ppf(0.975, t.size - x.size)
    cor_interval = (max(0.0, x[0] - quantile * se[0]), min(1.0, x[0] + quantile * se[0]))
    method = interval
    if x[0] >= 0.9999:
        notes.append("the COR reached its bound 1: the record shows no energy loss")
    t_release, t_release_se, apparent, cutoff, delay = _release_time(
        model, x, se, covariance, mode, digitizer, upper, notes)

    boot_interval: tuple[float, float] | None = None
    boot: np.ndarray | None = None
    if bootstrap:
        boot = _bootstrap(model, x, fitted, res, 4 * lags, int(bootstrap), seed, lower, upper,
                          scales)
        boot_interval = (float(np.percentile(boot, 2.5)), float(np.percentile(boot, 97.5)))
        cor_interval, method = boot_interval, "bootstrap"

    half_width = 0.5 * (cor_interval[1] - cor_interval[0])
    if not np.isfinite(half_width) or half_width > max_interval:
        raise CalibrationError(
            f"record {record.name!r} is too noisy to decide: the COR's 95 % interval is "
            f"{cor_interval[0]:.3f} to {cor_interval[1]:.3f} (half-width {half_width:.3f} > "
            f"{max_interval})")

    total = float(np.sum((record.values - np.mean(record.values))**2))
    lag1 = float(np.corrcoef(res[:-1], res[1:])[0, 1]) if res.size > 2 else math.nan
    release = apparent if apparent > t[0] else None
    peaks, periods, periods_held, scatter = _cross_checks(record, block, float(x[3]), release,
                                                          sigma, notes)
    warnings = diagnose(rate=record.rate, anti_alias=mode, filter_cutoff=float(cutoff),
                        residual_lag1=lag1, cor=float(x[0]), cor_se=float(se[0]), peaks=peaks,
                        scatter=scatter, periods=periods_held)
    goodness = {
        "rms": float(np.sqrt(np.mean(res**2))),
        "noise_estimate": float(sigma if record.quantity == "angle"
                                else sigma * (record.height or block.height)),
        "r_squared": 1.0 - float(res @ res) / total if total > 0 else math.nan,
        "residual_lag1_autocorrelation": lag1,
        "samples": int(t.size),
        "lags": int(lags),
        "engine_runs": int(sum(made.evaluations for made in models)),  # Jacobian included
        "optimizer_status": int(solution.status),
        "seconds": _time.perf_counter() - started,
    }
    return Calibration(record=record, block=block, cor=float(x[0]), cor_interval=cor_interval,
                       cor_se=float(se[0]), theta0=float(x[1]), theta0_se=float(se[1]),
                       t_release=float(t_release), t_release_se=float(t_release_se),
                       offset=float(x[3]), offset_se=float(se[3]), covariance=covariance,
                       interval_method=method, fitted=fitted, residuals=res, goodness=goodness,
                       peaks=peaks, periods=periods, periods_alpha_held=periods_held,
                       bootstrap_interval=boot_interval,
                       bootstrap_cors=boot,
                       notes=tuple(notes + [f"WARNING: {message}" for _, message in warnings]),
                       warnings=tuple(message for _, message in warnings),
                       warning_kinds=tuple(kind for kind, _ in warnings), scatter=scatter,
                       anti_alias=mode,
                       filter_order=int(model.order),
                       filter_cutoff=float(cutoff), filter_delay=float(delay),
                       t_release_apparent=float(apparent),
                       parameters=PARAMETERS + (("filter_u",) if mode == "fit" else ()),
                       jacobian=jacobian)


def _check_arguments(record: FreeRockingRecord, block: Block, interval: str,
                     anti_alias: object, filter_order: object,
                     bootstrap: int) -> tuple[str, Digitizer | None, tuple[int, ...]]:
    """:func:`calibrate`'s arguments checked: the filter mode, known filter and orders."""
    if not isinstance(record, FreeRockingRecord):
        raise ValueError(f"record must be a shaketable.calibration.record.FreeRockingRecord, got "
                         f"{type(record).__name__}")
    if not isinstance(block, Block):
        raise ValueError(f"block must be a shaketable.Block, got {type(block).__name__}")
    if interval not in INTERVALS:
        raise ValueError(f"interval must be one of {sorted(INTERVALS)}, got {interval!r}")
    mode, digitizer = _filter_mode(anti_alias)
    orders = _filter_orders(filter_order)
    if isinstance(bootstrap, bool) or int(bootstrap) != bootstrap or bootstrap < 0:
        raise ValueError(f"bootstrap must be a non-negative integer, got {bootstrap!r}")
    return mode, digitizer, orders


def _initial_guess(record: FreeRockingRecord, block: Block, theta: np.ndarray, sigma: float,
                   offset_guess: float, crossings: list[int]) -> tuple:
    """The starting point of the fit (COR, theta0 [rad], release time [s], offset [record
    unit]) read from the record, and the bounds, scales and Jacobian steps of each.

    The release angle from the first extreme, the release time from the first zero crossing
    minus the exact quarter period (Eq. 2-3), the COR from the peaks.
    """
    t = record.t
    first_zero = zero_time(t, theta, crossings[0])
    first_segment = theta[:crossings[0] + 1]
    sign = 1.0 if np.median(first_segment) > 0 else -1.0
    theta0_guess = float(np.median(first_segment[np.abs(first_segment) >= 0.98 * np.max(
        np.abs(first_segment))])) if first_segment.size else theta[0]
    theta0_guess = sign * min(max(abs(theta0_guess), 1e-4), 0.98 * block.alpha)
    t_release_guess = first_zero - exact_period(block, abs(theta0_guess)) / 4.0
    try:
        cor_guess = peak_estimate(record, block, offset=offset_guess,
                                  t_release=t_release_guess if t_release_guess > t[0] else None,
                                  sigma=sigma).cor
    except CalibrationError:
        cor_guess = 0.9
    cor_guess = float(np.clip(cor_guess, 0.3, 0.999))

    unit_scale = float(np.max(np.abs(record.values - offset_guess)))
    lower = [0.05, 0.0 if sign > 0 else -0.999 * block.alpha, t[0] - 5.0, -np.inf]
    upper = [1.0, 0.999 * block.alpha if sign > 0 else 0.0, first_zero, np.inf]
    scales = [0.01, 0.01 * block.alpha, 0.01, max(sigma, 1e-6 * unit_scale)]
    if record.quantity == "top displacement":
        height = record.height if record.height is not None else block.height
        scales[3] = max(sigma * height, 1e-9)
    steps = [2e-4, 2e-4 * block.alpha, 2e-3 * record.dt * 5, max(1e-6 * unit_scale, 1e-12)]
    x0 = np.array([cor_guess, theta0_guess, t_release_guess, offset_guess])
    return x0, lower, upper, scales, steps


def _solve(record: FreeRockingRecord, model: FreeRockingModel, x0: np.ndarray,
           low: list[float], high: list[float], scale: list[float],
           **options: Any) -> scipy.optimize.OptimizeResult:
    """Least squares of ``model`` on the record from ``x0``, inside the bounds."""
    x0 = np.clip(x0, np.array(low) + 1e-12, np.array(high) - 1e-12)
    return scipy.optimize.least_squares(lambda x: record.values - model(x), x0,
                                        bounds=(low, high), x_scale=np.array(scale),
                                        diff_step=1e-5, **options)


def _fit(record: FreeRockingRecord, block: Block, mode: str, digitizer: Digitizer | None,
         orders: tuple[int, ...], rtol: float, x0: np.ndarray, lower: list[float],
         upper: list[float], scales: list[float], steps: list[float]) -> tuple:
    """The least-squares fit, in two stages: the unfiltered model, then the filtered one.

    Returns the final model and its solution, every model made (their engine runs add up
    to the cost), and the bounds, scales and steps (with the filter's fifth parameter
    when ``mode`` is "fit").
    """
    tight = dict(xtol=1e-10, ftol=1e-12, gtol=1e-10, max_nfev=400)
    # stage 1: the unfiltered model, cheap (the engine at the samples only)
    plain = FreeRockingModel(record, block, "none", None, 4, rtol)
    solution = _solve(record, plain, x0, lower, upper, scales, **tight)
    x = solution.x
    models = [plain]
    model = plain
    if digitizer is not None:       # mode "known"
        # the known filter: its delay leaves the release time
        model = FreeRockingModel(record, block, "known", digitizer, digitizer.filter_order, rtol)
        models.append(model)
        x[2] -= butterworth_delay(digitizer.filter_order) / (2 * math.pi * digitizer.cutoff_frequency)
    elif mode == "fit":
        tau_max = 1.0 / (2.0 * math.pi * 0.05 * record.rate)
        tau_start = 1.0 / (2.0 * math.pi * 0.4 * record.rate)
        lower, upper = lower + [0.0], upper + [tau_max**2]
        scales = scales + [tau_start**2]
        steps = steps + [0.05 * tau_start**2]
        # stage 2: the filtered model from the unfiltered optimum, for each candidate order;
        # the smallest residual sum of squares wins
        # (chi-square differences between orders are > 1, so a loose tolerance ranks them)
        loose = dict(xtol=1e-6, ftol=1e-7, gtol=1e-8, max_nfev=200) if len(orders) > 1 else tight
        best: tuple[FreeRockingModel, scipy.optimize.OptimizeResult] | None = None
        for order in orders:
            candidate = FreeRockingModel(record, block, "fit", None, order, rtol)
            trial = _solve(record, candidate, np.append(x, tau_start**2), lower, upper, scales,
                           **loose)
            models.append(candidate)
            if best is None or trial.cost < best[1].cost:
                best = (candidate, trial)
        assert best is not None, "orders is never empty"
        model, solution = best
        if len(orders) > 1:
            solution = _solve(record, model, solution.x, lower, upper, scales, **tight)
    if mode == "known":
        # stage 2: the known filter, from the unfiltered optimum
        solution = _solve(record, model, x, lower, upper, scales, **tight)
    return model, solution, models, lower, upper, scales, steps


def _release_time(model: FreeRockingModel, x: np.ndarray, se: np.ndarray,
                  covariance: np.ndarray, mode: str, digitizer: Digitizer | None,
                  upper: list[float], notes: list[str]) -> tuple:
    """The release time [s] and its standard error, the apparent release time [s] (the
    fitted one, which holds the filter's delay), the filter's cutoff [Hz] and delay [s].

    Notes on a fitted filter at a bound are appended to ``notes``.
    """
    apparent = float(x[2])
    t_release, t_release_se = apparent, float(se[2])
    cutoff = model.cutoff(x)
    delay = 0.0
    if mode == "fit":
        tau = math.sqrt(max(float(x[4]), 0.0))
        delay = model.delay * tau
        t_release = apparent - delay
        if tau > TAU_FLOOR:
            gradient = np.zeros(x.size)
            gradient[2], gradient[4] = 1.0, -model.delay / (2.0 * tau)
            t_release_se = float(math.sqrt(max(gradient @ covariance @ gradient, 0.0)))
        if x[4] <= 1e-12 * upper[4]:
            notes.append("the fitted anti-alias filter reached no filter at all")
        elif x[4] >= 0.999 * upper[4]:
            notes.append(f"the fitted anti-alias filter reached its lowest cutoff "
                         f"{cutoff:.3g} Hz: the record looks smoothed beyond a plain filter")
    elif digitizer is not None:     # mode "known"
        delay = butterworth_delay(digitizer.filter_order) / (2 * math.pi * digitizer.cutoff_frequency)
        apparent = t_release + delay
    return t_release, t_release_se, apparent, cutoff, delay


def _bootstrap(model: FreeRockingModel, x: np.ndarray, fitted: np.ndarray, res: np.ndarray,
               length: int, count: int, seed: int | None, lower: list[float],
               upper: list[float], scales: list[float]) -> np.ndarray:
    """The COR of ``count`` moving-block bootstrap refits (blocks of ``length`` samples)."""
    size = res.size
    rng = np.random.default_rng(seed)
    replicates: list[float] = []
    for _ in range(count):
        starts = rng.integers(0, size - length + 1, size=int(math.ceil(size / length)))
        sample = np.concatenate([res[s:s + length] for s in starts])[:size]
        sample = sample - np.mean(sample) + np.mean(res)
        target = fitted + sample
        replicate = scipy.optimize.least_squares(
            lambda y: target - model(y), x, bounds=(lower, upper), x_scale=np.array(scales),
            diff_step=1e-5, max_nfev=100)
        replicates.append(replicate.x[0])
    return np.array(replicates)


def _cross_checks(record: FreeRockingRecord, block: Block, offset: float,
                  release: float | None, sigma: float, notes: list[str]) -> tuple:
    """The independent estimates beside the fit: the peak method, the period fit (with alpha
    fitted and held) and the COR's scatter model, each None where it fails (the reason
    appended to ``notes``)."""
    peaks = periods = None
    try:
        peaks = peak_estimate(record, block, offset=offset, t_release=release, sigma=sigma)
    except CalibrationError as error:
        notes.append(f"peak method: {error}")
    try:
        periods = period_fit(record, block, offset=offset, t_release=release, sigma=sigma)
    except CalibrationError as error:
        notes.append(f"period fit: {error}")
    periods_held = None
    if periods is not None:
        try:
            periods_held = period_fit(record, block, offset=offset, t_release=release,
                                      sigma=sigma, fit_alpha=False)
        except CalibrationError:
            periods_held = None
    scatter = None
    if peaks is not None:
        try:
            scatter = cor_scatter(peaks)
        except CalibrationError as error:
            notes.append(f"scatter model: {error}")
    return peaks, periods, periods_held, scatter
