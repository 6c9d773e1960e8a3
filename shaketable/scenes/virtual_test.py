"""Test against theory, as in Section 3.7 of the report.

"Test" is the virtual experiment: the block with its true COR on the table
(command, servo and pitch as the scene's ``[table]`` names them), read
through the potentiometers and accelerometers at 50 samples/s
(:mod:`shaketable.lab.sensors`). "Theory" is what the report did next: the
engine driven by the *digitized* table accelerations, with a COR identified
from a free-rocking test of the block (:mod:`shaketable.calibration.fit`) or given.
The comparison overlays the measured angle (top displacement / height, the
report's conversion) on the theory's and gives numbers: peak ratio, RMS
difference of theta/alpha, the times and directions of instability and of
overturning.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.units import parse
from shaketable.core.validation import check_keys, flag
from shaketable.lab.digitizer import Digitizer
from shaketable.lab.sensors import (
    WIRES,
    Accelerometers,
    Measurement,
    Potentiometers,
    Sensors,
    measure,
)
from shaketable.models.api import simulate
from shaketable.models.rocking.result import RockingResult

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

    from shaketable.calibration.result import Calibration


@dataclass(frozen=True)
class TheorySetup:
    """How the theory run of a virtual test is made.

    Parameters
    ----------
    cor : float or None
        COR of the theory run [-]; ``None``: identified by
        :func:`shaketable.calibration.fit.calibrate` from a virtual free-rocking
        test of the same block through the same sensors (the report's
        procedure, Section 3.5).
    release : float
        Release angle of that free-rocking test, as a fraction of alpha [-].
    free_rocking_duration : float
        Length of that free-rocking record [s].
    method : str
        Solver of the theory run.
    """

    cor: float | None = None
    release: float = 0.5
    free_rocking_duration: float = 8.0
    method: str = "fast"

    def __post_init__(self) -> None:
        if self.cor is not None and not (isinstance(self.cor, (int, float))
                                         and 0.0 <= self.cor <= 1.0):
            raise ValueError(f"theory.cor must be a number in [0, 1] or 'calibrated', got "
                             f"{self.cor!r}")
        if not 0.0 < self.release < 1.0:
            raise ValueError(f"theory.release must be between 0 and 1 (a fraction of alpha), "
                             f"got {self.release!r}")


@dataclass(frozen=True)
class VirtualTestResult:
    """One virtual test and its theory run.

    Attributes
    ----------
    test : RockingResult
        The physics behind the test (true COR, the motion the block felt).
    measurement : Measurement
        The test as the sensors recorded it.
    theory : RockingResult
        The engine run on the digitized table accelerations (or on the
        commanded motion when no accelerometers are fitted).
    theory_cor : float
        The COR used by the theory run [-].
    calibration : object or None
        The calibration result when the COR was identified.
    """

    test: RockingResult
    measurement: Measurement
    theory: RockingResult
    theory_cor: float
    calibration: object = None

    @property
    def block(self) -> Block:
        return self.test.block

    def measured_theta(self) -> np.ndarray:
        """The test's angle [rad], the report's way (top displacement / height)."""
        if self.measurement.theta is None:
            raise ValueError("the test has no potentiometers: no measured angle")
        return self.measurement.theta

    def theory_theta(self) -> np.ndarray:
        """The theory's angle at the measurement's sample times [rad]."""
        theory = self.theory
        theta = np.interp(self.measurement.t, theory.t, theory.theta)
        if theory.overturned:  # lying on the catcher arms after overturning
            theta[self.measurement.t > theory.t_overturn] = theory.overturn_direction * math.pi / 2
        return theta

    def metrics(self) -> dict:
        """Test against theory: the numbers of the comparison (JSON-ready).

        * instability: first sample of the 50 samples/s record where
          |theta| > alpha, test (measured) and theory; overturning verdict and
          direction (the theory's direction, and the test's as the sign of
          theta when it became unstable);
        * ``peak ratio``: max |theta| of the test over max |theta| of the
          theory, each up to and including its own first sample above alpha
          (the whole record if it never gets there): after that both just
          fall. Taking both peaks in a common window would end it on one
          curve's steep rise through alpha, where a shift of one or two
          samples (0.02-0.04 s) changes the other curve's value by 10-20 %
          (Fig. 3.8's 2 Hz runs); the time of instability is compared
          separately;
        * ``RMS difference theta/alpha``: over the common samples before either
          becomes unstable.
        """
        alpha = self.block.alpha
        t = self.measurement.t
        measured = self.measured_theta()
        theory = self.theory_theta()
        t_test = _first_above(t, measured, alpha)
        t_theory = _first_above(t, theory, alpha)
        end = min(_finite(t_test, math.inf), _finite(t_theory, math.inf))
        window = t <= end
        peak_test = float(np.max(np.abs(measured[t <= t_test])))
        peak_theory = float(np.max(np.abs(theory[t <= t_theory])))
        rms = (float(np.sqrt(np.mean(((measured - theory)[window] / alpha) ** 2)))
               if window.any() else math.nan)
        direction_test = 0
        if math.isfinite(t_test):
            direction_test = int(np.sign(measured[np.searchsorted(t, t_test)]))
        return {
            "test cor": self.test.cor, "theory cor": round(self.theory_cor, 4),
            "peak ratio test/theory": (round(peak_test / peak_theory, 3) if peak_theory > 0
                                       else None),
            "max theta/alpha test (measured)": round(peak_test / alpha, 3),
            "max theta/alpha theory": round(peak_theory / alpha, 3),
            "RMS difference theta/alpha": None if math.isnan(rms) else round(rms, 4),
            "t unstable test [s]": _rounded(t_test),
            "t unstable theory [s]": _rounded(t_theory),
            "direction test": direction_test,
            "direction theory": int(self.theory.overturn_direction or
                                    (np.sign(theory[np.searchsorted(t, t_theory)])
                                     if math.isfinite(t_theory) else 0)),
            "overturned test": bool(self.test.overturned),
            "overturned theory": bool(self.theory.overturned),
            "t overturn test [s]": _rounded(self.test.t_overturn),
            "t overturn theory [s]": _rounded(self.theory.t_overturn),
        }

    def to_frame(self) -> pd.DataFrame:
        """The record and the theory at its samples (pandas)."""
        frame = self.measurement.to_frame()
        frame["theory theta [rad]"] = self.theory_theta()
        return frame

    def plot(self, fig: Figure | None = None, title: str | None = None) -> Figure:
        """Test and theory overlaid, like Figs. 3.4 and 3.7-3.9.

        Top: the digitized table accelerations (when measured); bottom: theta/alpha
        of the test (measured) and the theory, with the +-1 stability lines.
        """
        from shaketable.plots.virtual_test import plot_test_vs_theory

        return plot_test_vs_theory(self, fig=fig, title=title)


def run_virtual_test(block: Block, felt: Motion | None, *, cor: float, sensors: Sensors,
                     theory: TheorySetup | None = None, commanded: Motion | None = None,
                     theta0: float = 0.0, theta_dot0: float = 0.0,
                     duration: float | None = None, method: str = "fast",
                     **options: Any) -> VirtualTestResult:
    """The virtual test of ``block`` on the table motion ``felt`` and its theory run.

    Parameters
    ----------
    block : Block
    felt : Motion or None
        What the block feels on the table [m/s^2] (``run_table(...).felt``);
        ``None``: free rocking on a table at rest.
    cor : float
        The block's true COR [-].
    sensors : Sensors
        The instruments; a single potentiometer wire adds its force at the top.
    theory : TheorySetup, optional
        Default ``TheorySetup()``: the COR identified from a free-rocking test.
    commanded : Motion, optional
        Drives the theory when no accelerometers are fitted.
    theta0, theta_dot0, duration, method, options
        As for :func:`shaketable.models.api.simulate` (the test run; the theory run
        starts from the same state).
    """
    theory = TheorySetup() if theory is None else theory
    top_force = sensors.top_force(block)
    test = simulate(block, felt, cor=cor, theta0=theta0, theta_dot0=theta_dot0,
                    duration=duration, method=method,
                    top_force=top_force, **options)
    measurement = measure(test, block, felt if felt is not None else test.motion, sensors)
    calibration = None
    theory_cor = theory.cor
    if theory_cor is None:
        calibration = calibrate_from_free_rocking(block, cor, sensors, theory)
        theory_cor = float(calibration.cor)
    if felt is None:
        drive = None
    elif sensors.accelerometers is not None:
        drive = measurement.motion()
    else:
        drive = commanded if commanded is not None else felt
    theory_run = simulate(block, drive, cor=theory_cor, theta0=theta0, theta_dot0=theta_dot0,
                          duration=duration if drive is None else None, method=theory.method)
    return VirtualTestResult(test, measurement, theory_run, theory_cor, calibration)


def calibrate_from_free_rocking(block: Block, cor: float, sensors: Sensors,
                                theory: TheorySetup) -> Calibration:
    """COR of ``block`` identified from its virtual free-rocking record (Section 3.5).

    The block (true ``cor``) is released from ``theory.release`` alpha on a
    table at rest and recorded by the same sensors for
    ``theory.free_rocking_duration`` seconds; :func:`shaketable.calibration.fit.calibrate`
    fits the record.
    """
    from shaketable.calibration.fit import calibrate
    from shaketable.calibration.free_rocking import virtual_free_rocking_record

    if sensors.potentiometers is None:
        raise ValueError("calibrating the COR needs potentiometers in [sensors]")
    record, _ = virtual_free_rocking_record(block, cor, theory.release * block.alpha,
                                            sensors=sensors,
                                            duration=theory.free_rocking_duration)
    return calibrate(record, block, anti_alias=sensors.digitizer)


# --------------------------------------------------------------------------- scene sections
_SENSOR_KEYS = {"potentiometers", "accelerometers", "rate", "anti_alias", "cutoff", "bits",
                "potentiometer_noise", "accelerometer_noise", "seed", "stroke", "wire_force"}

_THEORY_KEYS = {"cor", "release", "free_rocking_duration", "method"}


def sensors_from_dict(spec: dict, where: str = "<scene>") -> Sensors:
    """Validate a scene's ``[sensors]`` section into :class:`~shaketable.lab.sensors.Sensors`.

    Keys: ``potentiometers = "both" | "minus-x" | "plus-x" | false``,
    ``accelerometers = true | false``, ``rate = "50 Hz"``, ``anti_alias``,
    ``cutoff = "20 Hz"``, ``bits = 12``, ``potentiometer_noise = "0.005 in"``,
    ``accelerometer_noise = "0.002 g"``, ``stroke = "15 in"``,
    ``wire_force = "20 oz"``, ``seed = 1``.
    """
    if not isinstance(spec, dict):
        raise ValueError(f"{where}: [sensors] must be a table")
    check_keys(spec, _SENSOR_KEYS, where, "[sensors]")

    def quantity(key, kind):
        return parse(spec[key], kind, where=f"{where}: sensors.{key}")

    try:
        potentiometers = None
        wires = spec.get("potentiometers", "both")
        if wires is not False:
            if wires not in WIRES:
                raise ValueError(f"{where}: sensors.potentiometers must be one of "
                                 f"{', '.join(WIRES)} or false, got {wires!r}")
            options = {"wires": wires}
            if "potentiometer_noise" in spec:
                options["noise"] = quantity("potentiometer_noise", "length")
            if "stroke" in spec:
                options["stroke"] = quantity("stroke", "length")
            if "wire_force" in spec:
                options["wire_force"] = quantity("wire_force", "force")
            potentiometers = Potentiometers(**options)
        accelerometers = None
        fitted = spec.get("accelerometers", True)
        flag(f"{where}: sensors.accelerometers", fitted)
        if fitted:
            options = {}
            if "accelerometer_noise" in spec:
                options["noise"] = quantity("accelerometer_noise", "acceleration")
            accelerometers = Accelerometers(**options)
        options = {}
        if "rate" in spec:
            options["rate"] = quantity("rate", "frequency")
        if "cutoff" in spec:
            options["cutoff"] = quantity("cutoff", "frequency")
        for key in ("anti_alias", "bits"):
            if key in spec:
                options[key] = spec[key]
        seed = spec.get("seed")
        return Sensors(potentiometers, accelerometers, Digitizer(**options), seed=seed)
    except ValueError as error:
        message = str(error)
        raise ValueError(message if message.startswith(where) else
                         f"{where}: [sensors]: {message}") from None


def theory_from_dict(spec: dict, where: str = "<scene>") -> TheorySetup:
    """Validate a scene's ``[theory]`` section: ``cor = 0.925`` or ``"calibrated"``,
    ``release = "0.5 alpha"``, ``free_rocking_duration = "8 s"``, ``method``."""
    if not isinstance(spec, dict):
        raise ValueError(f"{where}: [theory] must be a table")
    check_keys(spec, _THEORY_KEYS, where, "[theory]")
    options: dict[str, Any] = {}
    cor = spec.get("cor", "calibrated")
    if cor != "calibrated":
        if isinstance(cor, bool) or not isinstance(cor, (int, float)):
            raise ValueError(f"{where}: theory.cor must be a number in [0, 1] or "
                             f"'calibrated', got {cor!r}")
        options["cor"] = float(cor)
    if "release" in spec:
        text = str(spec["release"]).strip()
        if not text.endswith("alpha"):
            raise ValueError(f"{where}: theory.release must be a fraction of alpha such as "
                             f"'0.5 alpha', got {spec['release']!r}")
        try:
            options["release"] = float(text[:-5].strip() or "1")
        except ValueError:
            raise ValueError(f"{where}: theory.release: {spec['release']!r} is not a multiple "
                             "of alpha such as '0.5 alpha'") from None
    if "free_rocking_duration" in spec:
        options["free_rocking_duration"] = parse(spec["free_rocking_duration"], "time",
                                                 where=f"{where}: theory.free_rocking_duration")
    if "method" in spec:
        options["method"] = str(spec["method"])
    try:
        return TheorySetup(**options)
    except ValueError as error:
        raise ValueError(f"{where}: {error}") from None


def _first_above(t, theta, alpha) -> float:
    above = np.nonzero(np.abs(theta) > alpha)[0]
    return float(t[above[0]]) if above.size else math.inf


def _finite(value, default):
    return value if value is not None and math.isfinite(value) else default


def _rounded(value, digits=3):
    if value is None or not math.isfinite(value):
        return None
    return round(float(value), digits)


__all__ = ["TheorySetup", "VirtualTestResult", "run_virtual_test", "calibrate_from_free_rocking",
           "sensors_from_dict", "theory_from_dict"]
