"""Equation of motion of a rocking block, Eqs. (2-13) and (2-14) of [1]_.

Sign convention (stated once for the package; ``docs/conventions.md`` repeats it)
---------------------------------------------------------------------------------
* ``theta`` is a single signed rotation [rad]. ``theta > 0``: the block pivots on
  its corner at -x and its top moves toward -x; ``theta < 0``: it pivots on the
  corner at +x. This is the report's Fig. 2.7 convention, in which a positive
  horizontal ground acceleration drives ``theta`` positive (Eq. 2-13 as printed).
* The horizontal ground acceleration ``ug`` is positive along +x [m/s^2].
* The vertical ground acceleration ``vg`` is positive upward [m/s^2].

With ``s = sign(theta)`` (the active corner) Eq. (2-13) reads, per unit mass,

    (4/3) R^2 theta'' = ug (h cos(theta) + s b sin(theta))
                        - (g + vg) (s b cos(theta) - h sin(theta)) - s M_rods / M

which for ``theta > 0`` is Eq. (2-13) letter for letter and for ``theta < 0`` its
mirror image. The printed Eq. (2-14) writes B and H where Eq. (2-13) has b and h;
that is a misprint: with K = F0 = 0 it must reduce to Eq. (2-13), so b and h are
used here. The rod moments are the report's RM1 and RM2 with the rods'
extensions taken as the uplift of their anchor points, delta_i = d_i sin|theta|.

Impact (Section 2.7 (5)): the report writes theta'_{i+1} = -nu theta'_i with
theta measured about the active corner; with one signed theta that is
``theta_dot_after = cor * theta_dot_before`` (same sign).

Every function here is compiled with numba (``nopython``) and works on floats and
one parameter array built by :func:`block_parameters`, so the solvers can call
them without Python overhead.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
"""

from __future__ import annotations

import math
from typing import Final

import numpy as np
from numba import njit

from shaketable.core.constants import G
from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.core.numba_cache import register
from shaketable.core.validation import in_range
from shaketable.numerics import cascade

# numba's cache of the package's compiled functions in one folder whatever the install
# (before the first cached function of the package is defined; core/numba_cache.py)
register()

# Indices into the parameter array.
HALF_WIDTH, HALF_HEIGHT, INERTIA, ROD_STIFFNESS, ROD_FORCE, ROD_ARM_1, ROD_ARM_2, ALPHA, \
    HOLD_DOWN, TOP_FORCE = range(10)

#: Indices read by the planar model only (:mod:`shaketable.models.planar.physics`): the
#: pivot of theta < 0 (b, I0 and alpha of that side; HALF_WIDTH, INERTIA and ALPHA are
#: those of theta > 0), the centroidal inertia per unit mass Ic [m^2], whether the block
#: is asymmetric (1.0) and, for an asymmetric block, the impact couple ratio rho and the
#: cascade's theta' ratio of an impact onto each pivot (+, -). A symmetric block has the
#: same values on both sides and Ic = I0 / 4.
HALF_WIDTH_MINUS, INERTIA_MINUS, ALPHA_MINUS, CENTROIDAL, ASYMMETRIC, RHO_PLUS, RHO_MINUS, \
    COR_PLUS, COR_MINUS = range(10, 19)

N_PARAMETERS = 19

#: numba's error model of every compiled function of the engines (rocking, planar, sliding):
#: with "numpy" a division by zero gives inf or NaN (IEEE 754) instead of raising
#: ZeroDivisionError, so that no compiled division carries a zero test and a branch to raise.
#: The engines' divisions are guarded (the divisor tested, or positive by construction) and
#: the results are the same bit for bit as with numba's default "python" (every rocking
#: result array of ``benchmarks``' cases, 143 planar and 13 sliding runs compared); the
#: planar engine runs a third faster and the rocking engine's first compile is a few
#: hundredths of a second shorter. Given explicitly to each function
#: (``tests/models/rocking/test_error_model.py`` checks every one), not left to numba's
#: inheritance from the caller: numba's cache keys and its compiled overloads ignore the
#: options, so a helper first compiled for a Python caller would otherwise be linked into
#: an engine compiled after it. numba's cache does not see a change of this value in a
#: module that only imports it either; the package's own cache folder is keyed by the
#: sources of ``core``, ``models`` and ``numerics`` (``shaketable/__init__.py``), so such a change
#: compiles afresh there, but a cache folder set by hand (``NUMBA_CACHE_DIR``) must be
#: cleared.
ERROR_MODEL: Final = "numpy"


def block_parameters(block: Block, top_force: float = 0.0) -> np.ndarray:
    """Pack a block into the float array the compiled physics uses.

    Parameters
    ----------
    block : Block
    top_force : float
        A constant horizontal force at the middle of the block's top, per unit
        mass [m/s^2], positive along +x (one potentiometer wire, Section 3.3).

    Returns
    -------
    ndarray, shape (N_PARAMETERS,)
        b [m], h [m], I0/M = 4R^2/3 [m^2], per-rod stiffness per mass
        g K/2 [1/s^2], per-rod prestress per mass g F0/2 [m/s^2], rod arms
        S and B - S from the pivot [m], alpha [rad], the hold-down
        acceleration g F0 [m/s^2] (the rods' pull at rest, per unit mass) and
        the top force per mass [m/s^2]; then the planar model's slots (b, I0, alpha of
        the other pivot, Ic = I0/4 [m^2]; 0 for "symmetric").
    """
    parameters = np.zeros(N_PARAMETERS)
    parameters[TOP_FORCE] = top_force
    parameters[HALF_WIDTH] = block.b
    parameters[HALF_HEIGHT] = block.h
    parameters[INERTIA] = block.I0_per_mass
    parameters[ALPHA] = block.alpha
    parameters[HALF_WIDTH_MINUS] = block.b
    parameters[INERTIA_MINUS] = block.I0_per_mass
    parameters[ALPHA_MINUS] = block.alpha
    parameters[CENTROIDAL] = 0.25 * block.I0_per_mass
    rods = block.rods
    if rods is not None:
        parameters[ROD_STIFFNESS] = G * rods.stiffness / 2
        parameters[ROD_FORCE] = G * rods.force / 2
        parameters[ROD_ARM_1] = rods.edge_distance
        parameters[ROD_ARM_2] = block.width - rods.edge_distance
        parameters[HOLD_DOWN] = G * rods.force
    return parameters


def side_parameters(block: Block | AsymmetricBlock) -> np.ndarray:
    """The parameter arrays of the two pivots: row 0 for theta > 0, row 1 for theta < 0.

    An asymmetric block on side s is Eq. (2-13) with that side's b_s and I0_s (h is
    common), so each row is the symmetric block's array with those values and the
    side's alpha_s: :func:`flight_acceleration` (the one equation of motion) is called
    with the row of the active pivot. A :class:`Block` gives :func:`block_parameters`
    twice. Rods and a top force are not offered for an asymmetric block.

    Returns
    -------
    ndarray, shape (2, N_PARAMETERS)
    """
    if isinstance(block, Block):
        row = block_parameters(block)
        return np.vstack([row, row])
    if not isinstance(block, AsymmetricBlock):
        raise ValueError(f"block must be a shaketable.Block or AsymmetricBlock, got "
                         f"{type(block).__name__}")
    rows = np.zeros((2, N_PARAMETERS))
    for index, side in ((0, 1.0), (1, -1.0)):
        rows[index, HALF_WIDTH] = block.b_of(side)
        rows[index, HALF_HEIGHT] = block.h
        rows[index, INERTIA] = block.I0_of(side)
        rows[index, ALPHA] = block.alpha_of(side)
    return rows


def asymmetric_parameters(block: AsymmetricBlock, cor: float | str) -> np.ndarray:
    """The planar model's parameter array of an asymmetric block (one array, both pivots).

    HALF_WIDTH, INERTIA, ALPHA are b, I0 and alpha of the pivot of theta > 0 (the corner
    at -x), HALF_WIDTH_MINUS, INERTIA_MINUS, ALPHA_MINUS those of theta < 0; CENTROIDAL
    is k^2; ASYMMETRIC is 1. The impact onto pivot k has the couple ratio
    rho_k = cor / c_H,k (c_H,k: :meth:`AsymmetricBlock.housner_cor`, so that a sticking
    rock-to-rock impact gives theta'+ = cor theta'-, Section 2.7 (5)) or 1 for
    ``"housner"``, and its cascade ratio is cor or c_H,k.

    Returns
    -------
    ndarray, shape (N_PARAMETERS,)
    """
    if not isinstance(block, AsymmetricBlock):
        raise ValueError(f"block must be an AsymmetricBlock, got {type(block).__name__}")
    parameters = np.zeros(N_PARAMETERS)
    parameters[HALF_HEIGHT] = block.h
    parameters[HALF_WIDTH], parameters[HALF_WIDTH_MINUS] = block.b_plus, block.b_minus
    parameters[INERTIA], parameters[INERTIA_MINUS] = block.I0_of(1.0), block.I0_of(-1.0)
    parameters[ALPHA], parameters[ALPHA_MINUS] = block.alpha_plus, block.alpha_minus
    parameters[CENTROIDAL] = block.k_squared
    parameters[ASYMMETRIC] = 1.0
    cors = impact_cors(block, cor)
    for index, onto in ((0, 1.0), (1, -1.0)):
        c_housner = block.housner_cor(onto)
        if isinstance(cor, str):
            parameters[(RHO_PLUS, RHO_MINUS)[index]] = 1.0
        elif c_housner == 0.0:
            raise ValueError(f"cor: a numeric cor ({cor!r}) needs Housner's ratio c_H != 0 "
                             "for the impacts onto both pivots; use cor='housner'")
        else:
            parameters[(RHO_PLUS, RHO_MINUS)[index]] = cors[index] / c_housner
        parameters[(COR_PLUS, COR_MINUS)[index]] = cors[index]
    return parameters


def impact_cors(block: Block | AsymmetricBlock, cor: float | str) -> np.ndarray:
    """Coefficients of restitution of the impacts onto each pivot: [onto theta > 0, onto < 0].

    ``cor`` a number: the report's constant COR (Section 2.7 (5)) for both;
    ``"housner"``: :meth:`AsymmetricBlock.housner_cor` of each pivot (for a
    :class:`Block`, 1 - 1.5 sin^2(alpha) twice).
    """
    if isinstance(cor, str):
        if cor != "housner":
            raise ValueError(f"cor must be a number in [0, 1] or 'housner', got {cor!r}")
        if isinstance(block, Block):
            value = 1.0 - 1.5 * math.sin(block.alpha) ** 2
            return np.array([value, value])
        return np.array([block.housner_cor(1.0), block.housner_cor(-1.0)])
    value = in_range("cor", cor, 0.0, 1.0)
    return np.array([value, value])


@njit(cache=True, error_model=ERROR_MODEL)
def flight_acceleration(theta, side, ug, vg, rg, parameters):
    """theta'' [rad/s^2] of a block pivoting on the corner ``side`` (+1 or -1): Eq. (2-13)/(2-14).

    The one statement of the equation of motion in the package; every solver uses it.

    Eq. (2-13)/(2-14) with s = ``side`` whatever the sign of ``theta``: equal to
    :func:`angular_acceleration` while ``side * theta >= 0``
    and its analytic continuation beyond theta = 0 (the rods' uplift
    sin|theta| continued as side * sin(theta)), so that a step of one flight
    never sees the switch of corner.
    """
    s = side
    b = parameters[HALF_WIDTH]
    h = parameters[HALF_HEIGHT]
    cosine = math.cos(theta)
    sine = math.sin(theta)
    moment = ug * (h * cosine + s * b * sine) - (G + vg) * (s * b * cosine - h * sine)
    stiffness = parameters[ROD_STIFFNESS]
    force = parameters[ROD_FORCE]
    if stiffness != 0.0 or force != 0.0:
        uplift = s * sine
        arm_1 = parameters[ROD_ARM_1]
        arm_2 = parameters[ROD_ARM_2]
        moment -= s * ((force + stiffness * arm_1 * uplift) * arm_1
                       + (force + stiffness * arm_2 * uplift) * arm_2) * cosine
    top_force = parameters[TOP_FORCE]
    if top_force != 0.0:
        moment -= top_force * (2.0 * h * cosine + s * b * sine)
    return moment / parameters[INERTIA] - rg


@njit(cache=True, error_model=ERROR_MODEL)
def angular_acceleration(theta, side, ug, vg, rg, parameters):
    """Angular acceleration theta'' [rad/s^2] from Eq. (2-13)/(2-14).

    Parameters
    ----------
    theta : float
        Rotation relative to the table [rad].
    side : float
        Active corner, +1 or -1; used when ``theta == 0`` (otherwise the sign
        of ``theta`` decides).
    ug, vg : float
        Horizontal (+x) and vertical (upward) ground acceleration at the
        block [m/s^2].
    rg : float
        Angular acceleration of the table (pitch) [rad/s^2], same sense as
        theta: the block's absolute rotation is theta + table rotation, so
        it enters as -rg.
    parameters : ndarray
        From :func:`block_parameters`.
    """
    s = side
    if theta > 0.0:
        s = 1.0
    elif theta < 0.0:
        s = -1.0
    # Eq. (2-13)/(2-14) on the corner the block stands on: with s = sign(theta) the
    # continued form is the equation itself (s sin(theta) = sin|theta|, exactly)
    return flight_acceleration(theta, s, ug, vg, rg, parameters)


#: :func:`shaketable.numerics.cascade.cascade_rest_time`, compiled.
cascade_rest_time = njit(cache=True, error_model=ERROR_MODEL)(cascade.cascade_rest_time)
