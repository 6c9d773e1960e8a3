"""The acquisition's anti-alias filter as the fit models it: a causal Butterworth low-pass
discretised with a first-order hold, and its group delay [s].
"""

from __future__ import annotations

import functools
import math

import numpy as np
import scipy.optimize
import scipy.signal
import scipy.stats


# ------------------------------------------------------------------ the model
def butterworth_delay(order: int) -> float:
    """Low-frequency group delay of a Butterworth low-pass in units of 1 / omega_c [-].

    The normalised poles p_k = exp(i pi (2k + N - 1) / (2N)), k = 1..N, lie on the
    unit circle, so the delay at omega -> 0, sum_k -Re(1 / p_k) / omega_c, is
    sum_k sin((2k - 1) pi / (2N)) / omega_c: 2.6131 / omega_c for N = 4
    (0.0208 s at 20 Hz), 1.4142 / omega_c for N = 2, 1 / omega_c for N = 1.
    """
    k = np.arange(1, int(order) + 1)
    return float(np.sum(np.sin((2 * k - 1) * math.pi / (2 * int(order)))))


@functools.lru_cache(maxsize=8)
def _butterworth_prototype(order: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Modal form of the analog Butterworth low-pass with omega_c = 1 rad/s.

    Returns (poles, V, V^-1 B_1, C_1 V) of a state-space realisation
    (A_1, B_1, C_1) with A_1 = V diag(poles) V^-1 (the poles are distinct).
    """
    zeros, poles, gain = scipy.signal.butter(order, 1.0, analog=True, output="zpk")
    a_matrix, b_matrix, c_matrix, _ = scipy.signal.zpk2ss(zeros, poles, gain)
    eigenvalues, vectors = np.linalg.eig(a_matrix)
    return (eigenvalues, vectors, np.linalg.solve(vectors, b_matrix.astype(complex)),
            c_matrix @ vectors)


def analog_butterworth_foh(order: int, tau: float,
                           dt: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Modal first-order-hold discretisation of an analog Butterworth low-pass (omega_c = 1/tau).

    H(s) = H_1(s tau) with H_1 the unit-cutoff prototype, so A = A_1 / tau,
    B = B_1 / tau, C = C_1. The first-order hold (as
    ``scipy.signal.cont2discrete(method="foh")``) is exact when the input is
    linear between the fine-grid points, for any cutoff, even one above the
    fine grid's Nyquist frequency, and tends to the identity as tau -> 0. In
    modal form, with x_i = p_i dt / tau, the state of mode i obeys
    z_i[k+1] = e^{x_i} z_i[k] + beta_i u[k] with
    beta_i = [(e^x - 1)/x - (e^x - 1 - x)/x^2 + e^x (e^x - 1 - x)/x^2] b_i dt / tau,
    and y[k] = sum_i c_i z_i[k] + D u[k], D = sum_i c_i (e^x - 1 - x)/x^2 b_i dt / tau.
    Parallel first-order sections stay well conditioned where a polynomial
    transfer function of order 8 with poles clustered near z = 1 does not.

    Returns
    -------
    (alpha, gain, direct)
        Complex mode poles e^{x_i}, complex gains c_i beta_i, and the real
        feed-through D.
    """
    poles, vectors, b_modal, c_modal = _butterworth_prototype(int(order))
    x = poles * (dt / tau)
    exponential = np.exp(x)
    small = np.abs(x) < 1e-4
    safe = np.where(small, 1.0, x)
    first = np.where(small, 1.0 + x / 2.0, np.expm1(x) / safe)
    second = np.where(small, 0.5 + x / 6.0, (np.expm1(x) - x) / safe**2)
    b = b_modal[:, 0] * (dt / tau)
    c = c_modal[0, :]
    beta = (first - second + exponential * second) * b
    direct = float(np.real(np.sum(c * second * b)))
    return exponential, c * beta, direct


def foh_filter(coefficients: tuple[np.ndarray, np.ndarray, float], values: np.ndarray,
               initial: float) -> np.ndarray:
    """Apply :func:`analog_butterworth_foh` coefficients, at rest on ``initial`` before."""
    alpha, gain, direct = coefficients
    out = direct * values
    for pole, weight in zip(alpha, gain):
        state = weight * initial / (1.0 - pole)            # steady state of the mode
        section, _ = scipy.signal.lfilter([0.0, weight], [1.0, -pole],
                                          values.astype(complex), zi=[state])
        out = out + np.real(section)
    return out
