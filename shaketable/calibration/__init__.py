"""COR identification from a measured free-rocking record (report Section 3.5).

:mod:`~shaketable.calibration.record` reads the record, :mod:`~shaketable.calibration.peaks`
gives the classical estimates (peak ratios, periods), :mod:`~shaketable.calibration.model`,
:mod:`~shaketable.calibration.filters` and :mod:`~shaketable.calibration.covariance` make the
best fit of :mod:`~shaketable.calibration.fit`, whose answer is a
:class:`~shaketable.calibration.result.Calibration`; :mod:`~shaketable.calibration.free_rocking`
compares a test with theory as Fig. 3.4 does.
"""

from shaketable.calibration.fit import calibrate
from shaketable.calibration.record import CalibrationError, FreeRockingRecord, read_record
from shaketable.calibration.result import Calibration, predict

__all__ = ["Calibration", "CalibrationError", "FreeRockingRecord", "calibrate", "predict",
           "read_record"]
