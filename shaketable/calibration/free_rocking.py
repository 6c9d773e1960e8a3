"""Free rocking, test against theory (Fig. 3.4, Table 3.1): a virtual free-rocking record,
its calibration, and the comparison of the measured decay with the model's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from shaketable.calibration.fit import calibrate
from shaketable.calibration.peaks import find_peaks, noise_level
from shaketable.calibration.record import FreeRockingRecord
from shaketable.calibration.result import Calibration, predict
from shaketable.core.files import json_ready
from shaketable.core.geometry import Block
from shaketable.models.api import simulate

if TYPE_CHECKING:
    from shaketable.lab.sensors import Measurement, Sensors


def _visible_rest(t, theta, threshold):
    """Time after which |theta| stays below ``threshold`` [s] (NaN if it never does)."""
    above = np.flatnonzero(np.abs(theta) >= threshold)
    if above.size == 0:
        return float(t[0])
    if above[-1] == t.size - 1:
        return math.nan
    return float(t[above[-1] + 1])


@dataclass(frozen=True)
class FreeRockingComparison:
    """Test (the record) against theory (the engine with the calibrated COR), Fig. 3.4.

    Attributes
    ----------
    calibration : Calibration
    theory : RockingResult
        Free rocking from the fitted release angle with the calibrated COR.
    t, test_theta, theory_theta : ndarray
        FreeRockingRecord times [s] and the two angles [rad] (offset removed; theory
        shifted to the fitted release time).
    peak_ratios : ndarray
        Test / theory amplitude of the successive peaks [-].
    rest_threshold : float
        |theta| below which the block counts as at rest [rad].
    test_rest, theory_rest : float
        Time from the release after which |theta| stays below the threshold [s].
    theory_t_rest : float
        The engine's exact rest time (end of the impact cascade) [s].
    cycles : int
        Full cycles (two impacts each) of the theory run above the threshold.
    rms_difference : float
        RMS of test minus theory after the release [rad].
    """

    calibration: Calibration
    theory: object
    t: np.ndarray
    test_theta: np.ndarray
    theory_theta: np.ndarray
    peak_ratios: np.ndarray
    rest_threshold: float
    test_rest: float
    theory_rest: float
    theory_t_rest: float
    cycles: int
    rms_difference: float

    def summary(self) -> dict:
        """Scalar results (JSON-ready)."""
        return {key: json_ready(value) for key, value in {
            "cor [-]": self.calibration.cor,
            "peak_ratio_mean [-]": float(np.mean(self.peak_ratios)),
            "peak_ratio_max_deviation [-]": float(np.max(np.abs(self.peak_ratios - 1.0))),
            "test_rest [s]": self.test_rest, "theory_rest [s]": self.theory_rest,
            "theory_t_rest [s]": self.theory_t_rest, "cycles": self.cycles,
            "rms_difference [rad]": self.rms_difference,
            "rest_threshold [rad]": self.rest_threshold}.items()}


def compare_free_rocking(calibration: Calibration, *, rest_threshold: float | None = None,
                         peaks: int = 8) -> FreeRockingComparison:
    """Feed the calibrated COR back into the theory run and compare with the record (Fig. 3.4).

    Parameters
    ----------
    calibration : Calibration
    rest_threshold : float, optional
        |theta| counted as rest [rad] (default 0.01 alpha, or 5 x the noise
        if larger); the same rule is applied to test and theory.
    peaks : int
        Number of successive peaks compared.
    """
    block, record = calibration.block, calibration.record
    theory = predict(calibration)
    t = record.t
    # the theory starts where the release shows in the record (the filter's delay included)
    start = (calibration.t_release_apparent if calibration.t_release_apparent is not None
             else calibration.t_release)
    tau = t - start
    theory_theta = np.where(tau <= 0, calibration.theta0,
                            np.interp(tau, theory.t, theory.theta))
    test_theta = record.to_angle(record.values - calibration.offset, block)
    sigma = noise_level(test_theta)
    threshold = rest_threshold if rest_threshold is not None else max(0.01 * block.alpha,
                                                                      5 * sigma)
    release = start if start > t[0] else None
    test_peaks = find_peaks(t, test_theta, block, sigma, plateau_end=release)
    theory_peaks = find_peaks(theory.t + start, theory.theta, block, 0.0,
                               plateau_end=None)
    theory_amplitudes = np.concatenate([[abs(calibration.theta0)], theory_peaks.amplitudes])
    count = min(peaks, test_peaks.amplitudes.size, theory_amplitudes.size)
    ratios = test_peaks.amplitudes[:count] / theory_amplitudes[:count]
    after = tau > 0
    test_rest = _visible_rest(tau[after], test_theta[after], threshold)
    theory_rest = _visible_rest(tau[after], theory_theta[after], threshold)
    above = theory_peaks.amplitudes >= threshold
    return FreeRockingComparison(
        calibration=calibration, theory=theory, t=t, test_theta=test_theta,
        theory_theta=theory_theta, peak_ratios=ratios, rest_threshold=threshold,
        test_rest=test_rest, theory_rest=theory_rest, theory_t_rest=float(theory.t_rest),
        cycles=int((np.count_nonzero(above) + 1) // 2),
        rms_difference=float(np.sqrt(np.mean((test_theta[after] - theory_theta[after])**2))))


def virtual_free_rocking_record(block: Block, cor: float, theta0: float, *, seed: int | None = 0,
                                before: float = 1.0, duration: float = 10.0,
                                sensors: Sensors | None = None, method: str = "fast",
                                rtol: float | None = None) -> tuple[FreeRockingRecord, Measurement]:
    """A virtual free-rocking test seen through the sensors (Section 3.5 set-up).

    Both potentiometers (their forces cancel), 50 samples/s with the 20 Hz
    anti-alias filter and 12-bit ADC of :class:`~shaketable.lab.digitizer.Digitizer`,
    the record starting ``before`` seconds before the release (block held at
    ``theta0``) and lasting ``duration`` seconds in all.

    Parameters
    ----------
    block : Block
    cor : float
        The true COR [-].
    theta0 : float
        Release angle [rad].
    seed : int or None
        Seed of the sensors' noise (ignored when ``sensors`` is given).
    before, duration : float
        FreeRockingRecord time before the release and in all [s].
    sensors : Sensors, optional
        Default ``Sensors(seed=seed)``.
    method, rtol
        Solver of the "test" run and its tolerance (:func:`shaketable.models.api`;
        default the fast engine at its default 1e-11, tighter than the
        calibration's 1e-9; ``method="reference"`` for SciPy's DOP853).

    Returns
    -------
    (FreeRockingRecord, Measurement)
    """
    from shaketable.lab.sensors import Sensors, measure

    sensors = Sensors(seed=seed) if sensors is None else sensors
    # 1 ms output: the sensors interpolate the run (cubic Hermite) between outputs, which
    # near an impact errs by ~ jump in theta' x output step / 8
    run = simulate(block, cor=cor, theta0=theta0, duration=duration - before,
                   top_force=sensors.top_force(block), output_dt=0.001, method=method,
                   rtol=rtol)
    digitizer = sensors.digitizer
    if digitizer.start is None:
        from dataclasses import replace

        sensors = replace(sensors, digitizer=replace(digitizer, start=-before,
                                                     end=duration - before))
    measurement = measure(run, block, sensors=sensors)
    return FreeRockingRecord.from_measurement(measurement), measurement


def reproduce_fig_3_4(*, cor: float = 0.925, theta0_ratio: float = 0.5, seed: int = 0,
                      duration: float = 9.0) -> FreeRockingComparison:
    """Fig. 3.4: virtual free-rocking test of the 30 x 6 in block, calibrated and re-run.

    The "test" is the engine with the true ``cor`` released from
    ``theta0_ratio x alpha`` (the fig-3-4 scene: 0.5 alpha) seen through the
    sensors (50 samples/s, noise, both potentiometers); the COR is calibrated
    from that record and the theory run with it is compared (the report: "the
    two curves are identical, for all practical purposes ... the block came
    to rest in approximately 6 seconds, after about 10 vibrations").
    """
    block = Block.parse("30x6in")
    record, _ = virtual_free_rocking_record(block, cor, theta0_ratio * block.alpha, seed=seed,
                                            duration=duration)
    return compare_free_rocking(calibrate(record, block))
