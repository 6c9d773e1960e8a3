"""COR identification from a measured free-rocking record (report Section 3.5).

:mod:`~shaketable.calibration.record` reads the record, :mod:`~shaketable.calibration.peaks`
gives the classical estimates (peak ratios, periods), :mod:`~shaketable.calibration.model`,
:mod:`~shaketable.calibration.filters` and :mod:`~shaketable.calibration.covariance` make the
best fit of :mod:`~shaketable.calibration.fit`, whose answer is a
:class:`~shaketable.calibration.result.Calibration`; :mod:`~shaketable.calibration.free_rocking`
compares a test with theory as Fig. 3.4 does. :mod:`~shaketable.calibration.scatter` models
the block's mean COR with its impact-to-impact scatter, :mod:`~shaketable.calibration.diagnostics`
says when the constant-COR answer should not be trusted, and
:mod:`~shaketable.calibration.uncertainty` carries a calibration into an ensemble.
"""

from shaketable.calibration.fit import calibrate
from shaketable.calibration.record import CalibrationError, FreeRockingRecord, read_record
from shaketable.calibration.result import Calibration, predict
from shaketable.calibration.scatter import CorScatter, cor_scatter
from shaketable.calibration.uncertainty import (
    CalibratedCor,
    CalibratedEnsemble,
    calibrated_ensemble,
)

__all__ = ["CalibratedCor", "CalibratedEnsemble", "Calibration", "CalibrationError",
           "CorScatter", "FreeRockingRecord", "calibrate", "calibrated_ensemble",
           "cor_scatter", "predict", "read_record"]
