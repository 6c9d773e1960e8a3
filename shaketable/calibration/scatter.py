"""The block's COR as it is on a real block: a mean with impact-to-impact scatter.

The least-squares fit of :mod:`~shaketable.calibration.fit` assumes one COR for
every impact (the report's model, Eq. 2-6). A real block's edges do not restore
the same share of the velocity at every impact: concrete or timber edges give
CORs that scatter from impact to impact by 0.01-0.03. The constant fit then
reports an interval of +-1e-4 around a value that the next impact misses by
100 times that, and its interval does not cover the block's mean COR.

:func:`cor_scatter` fits the random-effects model of the per-impact CORs of the
peak method (:func:`~shaketable.calibration.peaks.peak_estimate`: the n-th
impact's nu_n = sqrt(E_{n+1} / E_n), Eq. 2-6)::

    nu_hat = mu 1 + u + e,    u ~ N(0, sigma^2 I),    e ~ N(0, C)

mu is the block's mean COR, sigma the impact-to-impact scatter, and C the
measurement covariance of the per-impact CORs from the noise of the peaks
(tridiagonal: successive CORs share a peak, so their errors are anti-correlated;
built from ``PeakEstimate.log_energy_se``). sigma is estimated by restricted
maximum likelihood (REML), its 95 % interval by the profile REML likelihood
ratio (chi-square, 1 degree of freedom; the lower end is 0 when sigma = 0 is
not rejected); mu is the generalised least-squares mean at sigma_hat, with the
Hartung-Knapp variance (the weighted residual scale, never below 1) and the t
quantile with m - 1 degrees of freedom (Hartung and Knapp 2001; IntHout et al.
2014), which keeps the coverage of random-effects means at a handful of units
near nominal where the plain normal interval does not.

References
----------
.. [1] J. Hartung and G. Knapp, "A refined method for the meta-analysis of
   controlled clinical trials with binary outcome", Stat. Med. 20, 3875-3889, 2001.
.. [2] J. IntHout, J. P. A. Ioannidis and G. F. Borm, "The Hartung-Knapp-Sidik-Jonkman
   method for random effects meta-analysis is straightforward and considerably
   outperforms the standard DerSimonian-Laird method", BMC Med. Res. Methodol.
   14, 25, 2014.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.optimize
import scipy.stats

from shaketable.calibration.peaks import PeakEstimate
from shaketable.calibration.record import CalibrationError

#: Largest impact-to-impact scatter searched [-].
SIGMA_MAX = 0.5


@dataclass(frozen=True)
class CorScatter:
    """Mean COR of a block and its impact-to-impact scatter (random-effects model).

    Attributes
    ----------
    mean : float
        The block's mean COR mu [-].
    mean_se : float
        Its standard error (Hartung-Knapp) [-].
    mean_interval : tuple of float
        95 % interval of mu (t quantile, ``impacts - 1`` degrees of freedom) [-].
    sigma : float
        Impact-to-impact standard deviation of the COR [-] (REML).
    sigma_interval : tuple of float
        95 % profile-likelihood interval of sigma [-].
    impacts : int
        Number of per-impact CORs used.
    measurement_se : float
        Median measurement standard error of one per-impact COR [-] (from the
        noise of the peaks).
    """

    mean: float
    mean_se: float
    mean_interval: tuple[float, float]
    sigma: float
    sigma_interval: tuple[float, float]
    impacts: int
    measurement_se: float

    @property
    def dof(self) -> int:
        """Degrees of freedom of the mean's t quantile."""
        return max(self.impacts - 1, 1)

    def summary(self) -> dict[str, object]:
        """JSON-ready scalars (units in the keys)."""
        return {"cor_mean [-]": self.mean, "cor_mean_se [-]": self.mean_se,
                "cor_mean_interval [-]": [float(self.mean_interval[0]),
                                          float(self.mean_interval[1])],
                "cor_mean_dof": self.dof,
                "cor_scatter_sigma [-]": self.sigma,
                "cor_scatter_sigma_interval [-]": [float(self.sigma_interval[0]),
                                                   float(self.sigma_interval[1])],
                "cor_scatter_impacts": self.impacts,
                "cor_per_impact_measurement_se [-]": self.measurement_se}


def measurement_covariance(peaks: PeakEstimate) -> np.ndarray:
    """Covariance of the per-impact CORs from the noise of the peaks [-].

    log nu_n = (log E_{n+1} - log E_n) / 2, so with v_n = var(log E_n):
    var(log nu_n) = (v_n + v_{n+1}) / 4 and cov(log nu_n, log nu_{n+1}) = -v_{n+1} / 4;
    to first order cov(nu) = D cov(log nu) D with D = diag(nu).
    """
    cors = np.asarray(peaks.cor_per_impact, dtype=float)
    m = cors.size
    if peaks.log_energy_se is None:
        return np.diag(np.asarray(peaks.cor_per_impact_se, dtype=float) ** 2)
    v = np.asarray(peaks.log_energy_se, dtype=float)[:m + 1] ** 2
    log_cov = np.diag(0.25 * (v[:-1] + v[1:]))
    for n in range(m - 1):
        log_cov[n, n + 1] = log_cov[n + 1, n] = -0.25 * v[n + 1]
    return cors[:, None] * log_cov * cors[None, :]


def _reml(cors: np.ndarray, measurement: np.ndarray, sigma: float) -> tuple[float, float, float]:
    """(restricted log-likelihood, GLS mean, 1' V^-1 1) at ``sigma``."""
    m = cors.size
    covariance = measurement + sigma**2 * np.eye(m)
    cholesky = np.linalg.cholesky(covariance)
    ones = np.ones(m)
    a = scipy.linalg.cho_solve((cholesky, True), ones)
    information = float(ones @ a)
    mean = float(a @ cors) / information
    residual = cors - mean
    quadratic = float(residual @ scipy.linalg.cho_solve((cholesky, True), residual))
    log_det = 2.0 * float(np.sum(np.log(np.diag(cholesky))))
    return -0.5 * (log_det + math.log(information) + quadratic), mean, information


def cor_scatter(peaks: PeakEstimate, *, level: float = 0.95) -> CorScatter:
    """Mean COR and impact-to-impact scatter of a block from its per-impact CORs.

    Parameters
    ----------
    peaks : PeakEstimate
        The peak method's per-impact CORs (Eq. 2-6) and their noise.
    level : float
        Level of the intervals [-].

    Returns
    -------
    CorScatter

    Raises
    ------
    CalibrationError
        Fewer than 3 per-impact CORs.
    """
    cors = np.asarray(peaks.cor_per_impact, dtype=float)
    m = cors.size
    if m < 3:
        raise CalibrationError(f"only {m} per-impact COR(s): the scatter model needs 3")
    measurement = measurement_covariance(peaks)
    # keep C positive definite when two noise terms nearly cancel
    measurement = measurement + 1e-14 * np.eye(m)

    def negative(sigma: float) -> float:
        return -_reml(cors, measurement, sigma)[0]

    spread = float(np.std(cors, ddof=1))
    grid = np.concatenate([[0.0], np.geomspace(1e-6, SIGMA_MAX, 60)])
    values = np.array([negative(s) for s in grid])
    best = int(np.argmin(values))
    if best == 0:
        sigma, best_value = 0.0, float(values[0])
    else:
        found = scipy.optimize.minimize_scalar(
            lambda x: negative(math.exp(x)), method="bounded",
            bounds=(math.log(max(grid[best - 1], 1e-7)),
                    math.log(grid[min(best + 1, grid.size - 1)])))
        sigma, best_value = math.exp(found.x), float(found.fun)
        if values[best] < best_value:
            sigma, best_value = float(grid[best]), float(values[best])
    # profile interval of sigma: 2 (l_max - l(sigma)) <= chi2_1(level)
    cut = 0.5 * scipy.stats.chi2.ppf(level, 1)

    def excess(s: float) -> float:
        return negative(s) - best_value - cut

    lower = 0.0 if excess(0.0) <= 0 else scipy.optimize.brentq(excess, 0.0, sigma)
    upper, probe = SIGMA_MAX, max(sigma, spread, 1e-6)
    while probe < SIGMA_MAX:
        probe = min(2.0 * probe, SIGMA_MAX)
        if excess(probe) > 0:
            upper = scipy.optimize.brentq(excess, sigma, probe)
            break
    _, mean, information = _reml(cors, measurement, sigma)
    covariance = measurement + sigma**2 * np.eye(m)
    residual = cors - mean
    scale = float(residual @ np.linalg.solve(covariance, residual)) / max(m - 1, 1)
    se = math.sqrt(max(scale, 1.0) / information)
    quantile = float(scipy.stats.t.ppf(0.5 + level / 2, max(m - 1, 1)))
    return CorScatter(mean=mean, mean_se=se, mean_interval=(mean - quantile * se,
                                                             mean + quantile * se),
                      sigma=sigma, sigma_interval=(lower, upper), impacts=m,
                      measurement_se=float(np.median(np.sqrt(np.diag(measurement)))))

