"""Covariance of the fitted parameters: iid, sandwich with the residuals' autocovariance,
and Newey-West (HAC) for the serially correlated residuals of a sampled record.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from shaketable.calibration.record import INTERVALS

if TYPE_CHECKING:
    from shaketable.calibration.result import Calibration


def bandwidth(n: int) -> int:
    """Lag window: 4 (n / 100)^(2/9), Newey and West's automatic choice."""
    return max(2, int(math.ceil(4.0 * (n / 100.0) ** (2.0 / 9.0))))


def _autocovariance(residuals, lags: int) -> np.ndarray:
    """Biased sample autocovariance gamma_k = sum e_t e_{t+k} / n, k = 0..lags [unit^2]."""
    n = residuals.size
    return np.array([float(residuals[:n - k] @ residuals[k:]) / n for k in range(lags + 1)])


def sandwich_covariance(jacobian: np.ndarray, residuals: np.ndarray, method: str,
                        lags: int) -> np.ndarray:
    """Covariance of the least-squares parameters, ``(J^T J)^-1 M (J^T J)^-1``.

    * ``"acf"``: M = J^T Sigma J with Sigma the Toeplitz matrix of the residuals'
      Bartlett-tapered sample autocovariance to ``lags`` (stationary noise:
      one autocovariance for the whole record, estimated from all n samples;
      positive semi-definite by the Bartlett taper);
    * ``"hac"``: Newey-West, M = sum_t sum_s w(|t-s|) e_t e_s J_t^T J_s;
    * ``"iid"``: M = s^2 J^T J.

    All are scaled by n / (n - k) for the k fitted parameters.
    """
    n, k = jacobian.shape
    bread = np.linalg.inv(jacobian.T @ jacobian)
    if method == "iid":
        return bread * float(residuals @ residuals) / (n - k)
    if method == "acf":
        gamma = _autocovariance(residuals, lags)
        meat = gamma[0] * (jacobian.T @ jacobian)
        for lag in range(1, lags + 1):
            weight = 1.0 - lag / (lags + 1.0)
            cross = jacobian[lag:].T @ jacobian[:-lag]
            meat += weight * gamma[lag] * (cross + cross.T)
        return bread @ meat @ bread * n / (n - k)
    scores = jacobian * residuals[:, None]
    meat = scores.T @ scores
    for lag in range(1, lags + 1):
        weight = 1.0 - lag / (lags + 1.0)
        gamma = scores[lag:].T @ scores[:-lag]
        meat += weight * (gamma + gamma.T)
    return bread @ meat @ bread * n / (n - k)


def covariance_of(calibration: Calibration, interval: str) -> np.ndarray:
    """The covariance of a calibration's parameters computed with another ``interval`` method.

    Parameters
    ----------
    calibration : Calibration
    interval : str
        One of :data:`INTERVALS`.

    Returns
    -------
    ndarray
        k x k covariance, in the order of ``calibration.parameters``.
    """
    if interval not in INTERVALS:
        raise ValueError(f"interval must be one of {sorted(INTERVALS)}, got {interval!r}")
    if calibration.jacobian is None:
        raise ValueError("calibration has no Jacobian (it was not made by calibrate())")
    return sandwich_covariance(calibration.jacobian, calibration.residuals, interval,
                               int(calibration.goodness["lags"]))
