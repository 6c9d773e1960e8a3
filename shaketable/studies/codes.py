"""Design codes' checks of a free-standing or anchored rigid object, each with its source.

Only formulas that were checked against their source are here (``docs/assess.md`` lists
what was left out and why):

* ASCE/SEI 7-16 [1]_, Chapter 13 (nonstructural components):
  :func:`asce7_fp` -- Eq. 13.3-1 with its bounds Eqs. 13.3-2 and 13.3-3;
  :func:`asce7_overturning` -- the static overturning check of a component under Fp with
  the dead load reduced by the vertical effect ``0.2 S_DS D`` (Section 12.4.2.2,
  Eq. 12.4-4a) in load combination 7 of Section 2.3.6, ``(0.9 - 0.2 S_DS) D + E_h``.
* NTC 2018 [2]_ with its Circolare 2019 [3]_, C8.7.1 (local mechanisms, linear kinematic
  analysis): :func:`kinematic_multiplier` (alpha_0 = b/h, the static collapse multiplier
  of a rigid block about its corner) and :func:`kinematic_a0` (a0* = alpha_0 g / (e* FC),
  e* = 1 for a single rigid block).
* ASCE/SEI 43-05 [4]_, Appendix A, Section A.1 (sliding of an unanchored rigid body):
  :func:`asce43_sliding` -- Eq. A-1 ``mu_e = mu (1 - 0.4 A_v / g)`` and Eq. A-2
  ``c_s = 2 mu_e g``, and the lowest frequency at which the 10 %-damped horizontal
  spectrum reaches c_s.

References
----------
.. [1] ASCE/SEI 7-16, *Minimum Design Loads and Associated Criteria for Buildings and
   Other Structures*, American Society of Civil Engineers (2017).
.. [2] D.M. 17 gennaio 2018, *Aggiornamento delle Norme tecniche per le costruzioni*
   (NTC 2018).
.. [3] Circolare 21 gennaio 2019 n. 7 C.S.LL.PP., *Istruzioni per l'applicazione
   dell'Aggiornamento delle Norme tecniche per le costruzioni*.
.. [4] ASCE/SEI 43-05, *Seismic Design Criteria for Structures, Systems, and Components
   in Nuclear Facilities*, American Society of Civil Engineers (2005).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaketable.core.constants import G
from shaketable.core.validation import in_range, nonnegative, positive


@dataclass(frozen=True)
class ComponentForce:
    """ASCE 7-16 Eq. 13.3-1 to 13.3-3 evaluated.

    Attributes
    ----------
    fp : float
        Design force Fp, bounded [N].
    unbounded : float
        Eq. 13.3-1 before the bounds [N].
    lower, upper : float
        Eq. 13.3-3 (0.3 S_DS I_p W_p) and Eq. 13.3-2 (1.6 S_DS I_p W_p) [N].
    governs : str
        ``"Eq. 13.3-1"``, ``"Eq. 13.3-2"`` (the upper bound) or ``"Eq. 13.3-3"`` (the lower).
    """

    fp: float
    unbounded: float
    lower: float
    upper: float
    governs: str


def asce7_fp(weight: float, s_ds: float, *, z_over_h: float, a_p: float = 1.0,
             r_p: float = 2.5, i_p: float = 1.0) -> ComponentForce:
    """Horizontal seismic design force of a component, ASCE 7-16 Section 13.3.1.

    ``Fp = 0.4 a_p S_DS W_p (1 + 2 z/h) / (R_p / I_p)`` (Eq. 13.3-1), not more than
    ``1.6 S_DS I_p W_p`` (Eq. 13.3-2) and not less than ``0.3 S_DS I_p W_p`` (Eq. 13.3-3).

    Parameters
    ----------
    weight : float
        Operating weight W_p [N].
    s_ds : float
        Design spectral acceleration at short periods S_DS [g] (a number, e.g. 1.0).
    z_over_h : float
        Height of the point of attachment over the roof height [-]; 0 at or below the
        base; values above 1 are taken as 1 ("z/h need not exceed 1.0").
    a_p, r_p, i_p : float
        Component amplification factor, response modification factor and importance
        factor [-] (Tables 13.5-1 / 13.6-1; Section 13.1.3). Defaults: a_p = 1,
        R_p = 2.5, I_p = 1.

    Returns
    -------
    ComponentForce
    """
    weight = positive("weight", weight, " [N]")
    s_ds = positive("S_DS", s_ds, " [g]")
    ratio = min(nonnegative("z/h", z_over_h), 1.0)
    a_p = positive("a_p", a_p)
    r_p = positive("R_p", r_p)
    i_p = positive("I_p", i_p)
    unbounded = 0.4 * a_p * s_ds * weight * (1.0 + 2.0 * ratio) / (r_p / i_p)  # Eq. 13.3-1
    upper = 1.6 * s_ds * i_p * weight  # Eq. 13.3-2
    lower = 0.3 * s_ds * i_p * weight  # Eq. 13.3-3
    if unbounded > upper:
        return ComponentForce(upper, unbounded, lower, upper, "Eq. 13.3-2")
    if unbounded < lower:
        return ComponentForce(lower, unbounded, lower, upper, "Eq. 13.3-3")
    return ComponentForce(unbounded, unbounded, lower, upper, "Eq. 13.3-1")


@dataclass(frozen=True)
class OverturningCheck:
    """The static overturning check of a free-standing component under Fp.

    Attributes
    ----------
    moment : float
        Overturning moment Fp h_cg [N m].
    resisting : float
        ``(0.9 - 0.2 S_DS) W_p b / 2`` [N m] (zero or less when 0.2 S_DS >= 0.9).
    factor : float
        The dead-load factor 0.9 - 0.2 S_DS [-].
    uplift : float
        Tension the anchors on one side must take, ``max(0, (moment - resisting) / b)`` [N].
    stable : bool
        True when the factored dead load resists the overturning moment alone.
    """

    moment: float
    resisting: float
    factor: float
    uplift: float
    stable: bool


def asce7_overturning(fp: float, weight: float, s_ds: float, *, width: float,
                      height_cg: float) -> OverturningCheck:
    """Overturning of a rigid component about an edge of its base under Fp.

    Load combination 7 of ASCE 7-16 Section 2.3.6 with E = E_h - E_v, E_v = 0.2 S_DS D
    (Eq. 12.4-4a): the dead load that resists overturning is ``(0.9 - 0.2 S_DS) D``,
    acting at half the base width ``b / 2`` from the edge, against ``Fp h_cg``.

    Parameters
    ----------
    fp : float
        Horizontal design force [N] (:func:`asce7_fp`).
    weight : float
        W_p = D [N].
    s_ds : float
        S_DS [g].
    width : float
        Base width b in the direction of Fp [m].
    height_cg : float
        Height of the centre of mass above the base [m].

    Returns
    -------
    OverturningCheck
    """
    fp = nonnegative("fp", fp, " [N]")
    weight = positive("weight", weight, " [N]")
    s_ds = positive("S_DS", s_ds, " [g]")
    width = positive("width", width, " [m]")
    height_cg = positive("height_cg", height_cg, " [m]")
    factor = 0.9 - 0.2 * s_ds  # Section 2.3.6 combination 7 with Eq. 12.4-4a
    moment = fp * height_cg
    resisting = factor * weight * width / 2.0
    uplift = max(0.0, (moment - resisting) / width)
    return OverturningCheck(moment, resisting, factor, uplift, moment <= resisting)


def kinematic_multiplier(width: float, height: float) -> float:
    """alpha_0 = b / h: the horizontal load multiplier that starts a rigid block rocking.

    Moments about the corner of a uniform block of width b and height h under its weight
    W and a horizontal force alpha W at its centre: ``alpha W h/2 = W b/2``. The linear
    kinematic analysis of the Circolare 2019, C8.7.1, uses this multiplier (and the
    report's Eq. (2-1): tan(alpha) = b/h is the same threshold).

    Parameters
    ----------
    width, height : float
        b and h of the block [m].

    Returns
    -------
    float
        alpha_0 [-].
    """
    return positive("width", width, " [m]") / positive("height", height, " [m]")


def kinematic_a0(alpha0: float, *, e_star: float = 1.0, fc: float = 1.0) -> float:
    """Spectral acceleration that activates the mechanism, a0* = alpha_0 g / (e* FC).

    Circolare 2019, C8.7.1 (linear kinematic analysis of local mechanisms): e* is the
    fraction of the mass that participates (1 for a single rigid block, whose only
    mass is the moving one), FC the confidence factor of the knowledge level.

    Parameters
    ----------
    alpha0 : float
        Load multiplier [-] (:func:`kinematic_multiplier`).
    e_star : float
        Participating mass fraction e* [-], in (0, 1].
    fc : float
        Confidence factor FC [-], at least 1.

    Returns
    -------
    float
        a0* [m/s^2].
    """
    alpha0 = positive("alpha0", alpha0)
    e_star = in_range("e_star", e_star, 0.0, 1.0, low_open=True)
    fc = in_range("FC", fc, 1.0)
    return alpha0 * G / (e_star * fc)


@dataclass(frozen=True)
class SlidingCoefficient:
    """ASCE 43-05 Appendix A, Section A.1.

    Attributes
    ----------
    mu_e : float
        Effective coefficient of friction, Eq. A-1 [-].
    c_s : float
        Sliding coefficient, Eq. A-2 [m/s^2].
    f_s : float
        Lowest frequency at which the 10 %-damped horizontal spectrum reaches c_s [Hz]
        (NaN: it never does over the frequencies given, or no spectrum given).
    """

    mu_e: float
    c_s: float
    f_s: float = math.nan


def asce43_sliding(mu: float, vertical_peak: float, *, frequencies=None,
                   spectrum=None) -> SlidingCoefficient:
    """Effective friction and sliding coefficient, ASCE 43-05 Eqs. A-1 and A-2.

    ``mu_e = mu (1 - 0.4 A_v / g)`` (Eq. A-1) and ``c_s = 2 mu_e g`` (Eq. A-2); the
    sliding frequency f_s is "the lowest natural frequency at which the horizontal 10 %
    damped spectral acceleration equals c_s" (Section A.1). The sliding distance of
    Eq. A-3 is not transcribed (see ``docs/assess.md``).

    Parameters
    ----------
    mu : float
        Coefficient of sliding friction [-], in (0, 2].
    vertical_peak : float
        Peak vertical acceleration A_v [m/s^2], zero or positive.
    frequencies, spectrum : array_like, optional
        The 10 %-damped horizontal spectral acceleration [m/s^2] at frequencies [Hz]
        (increasing), for f_s; linear interpolation to the crossing.

    Returns
    -------
    SlidingCoefficient
    """
    mu = in_range("mu", mu, 0.0, 2.0, low_open=True)
    a_v = nonnegative("A_v", vertical_peak, " [m/s^2]")
    mu_e = mu * (1.0 - 0.4 * a_v / G)  # Eq. A-1
    c_s = 2.0 * mu_e * G  # Eq. A-2
    f_s = math.nan
    if frequencies is not None and spectrum is not None:
        f = np.asarray(frequencies, dtype=float)
        sa = np.asarray(spectrum, dtype=float)
        above = np.nonzero(sa >= c_s)[0]
        if above.size:
            k = int(above[0])
            if k == 0:
                f_s = float(f[0])
            else:
                f_s = float(np.interp(c_s, [sa[k - 1], sa[k]], [f[k - 1], f[k]]))
    return SlidingCoefficient(mu_e, c_s, f_s)
