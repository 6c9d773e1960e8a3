"""Fragility curves fitted to a sweep's table (lognormal, maximum likelihood)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class FragilityFit:
    """A lognormal fragility curve P(overturn | PGA) = Phi(ln(PGA / median) / beta).

    Attributes
    ----------
    median : float
        PGA with a 50 % probability of overturning [same unit as the PGAs fitted].
    beta : float
        Logarithmic standard deviation [-].
    n_runs : int
        Runs fitted.
    n_overturned : int
        Of which overturned.
    """

    median: float
    beta: float
    n_runs: int
    n_overturned: int

    def probability(self, pga):
        """P(overturn) at ``pga`` [unit of the fit]."""
        from scipy.stats import norm

        pga = np.asarray(pga, dtype=float)
        return norm.cdf(np.log(pga / self.median) / self.beta)


def fragility_fit(pga, overturned) -> FragilityFit:
    """Maximum-likelihood lognormal fragility from (PGA, overturned) outcomes.

    Each run is a Bernoulli trial with probability
    ``Phi(ln(pga / median) / beta)``; the binomial log-likelihood is maximised
    over ``(ln median, ln beta)`` (Nelder-Mead from the probit moments). The
    usual estimator of seismic fragility (e.g. Baker, Earthquake Spectra 31(1),
    2015, Eq. 11).

    Parameters
    ----------
    pga : array_like
        Peak ground accelerations, positive [any unit; the median comes out in it].
    overturned : array_like of bool

    Raises
    ------
    ValueError
        No run overturned or every run did (the curve is not identified), or
        non-positive PGAs.
    """
    from scipy.optimize import minimize
    from scipy.stats import norm

    pga = np.asarray(pga, dtype=float)
    overturned = np.asarray(overturned, dtype=bool)
    if pga.shape != overturned.shape or pga.size == 0:
        raise ValueError("pga and overturned must be non-empty and of the same length")
    if not np.all(np.isfinite(pga)) or np.any(pga <= 0):
        raise ValueError("pga must be positive and finite")
    k = int(overturned.sum())
    if k == 0 or k == pga.size:
        raise ValueError(f"{'no' if k == 0 else 'every'} run overturned: a fragility curve "
                         "needs both outcomes (extend the PGA range)")
    log_pga = np.log(pga)

    def negative_log_likelihood(params):
        mu, log_beta = params
        z = (log_pga - mu) / math.exp(log_beta)
        return -(np.sum(norm.logcdf(z[overturned])) + np.sum(norm.logcdf(-z[~overturned])))

    # start: the median between the largest safe and smallest overturning PGA
    start = np.array([0.5 * (log_pga[overturned].mean() + log_pga[~overturned].mean()),
                      math.log(max(0.05, np.std(log_pga)))])
    best = minimize(negative_log_likelihood, start, method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    mu, log_beta = best.x
    return FragilityFit(median=float(math.exp(mu)), beta=float(math.exp(log_beta)),
                        n_runs=int(pga.size), n_overturned=k)
