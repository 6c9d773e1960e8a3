"""``simulate_planar``: one run of the planar block (rest, slide, rock, slide-rock, flight).

:func:`shaketable.models.api.simulate` delegates here when it is given ``friction=``.
The model is stated in :mod:`shaketable.models.planar.physics`; the engine is
:mod:`shaketable.models.planar.engine`.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.core.motion import Motion, whole_number
from shaketable.core.validation import in_range
from shaketable.models.planar import engine as planar
from shaketable.models.planar.result import MODES, PlanarResult
from shaketable.models.rocking.physics import COR_PLUS, RHO_PLUS, asymmetric_parameters, block_parameters
from shaketable.models.rocking.run import call_interruptibly, engine_arrays, run_motion, run_options
from shaketable.models.sliding.result import Friction

#: Default relative tolerance of the planar engine's DOP853 steps [-].
DEFAULT_PLANAR_RTOL = 1e-12


def impact_ratios(block: Block, cor: float | str) -> tuple[float, float]:
    """(rho, cor of a rock-to-rock impact) for a numeric COR or ``"housner"``.

    rho = cor / c_H scales the angular momentum about the striking corner; Housner's law
    (rho = 1) gives theta' -> c_H theta', c_H = 1 - 1.5 sin^2(alpha). For B/H > sqrt(2)
    c_H < 0 and rho < 0 (a rock-to-rock impact still gives theta' -> cor theta'; the energy
    cap of :func:`~shaketable.models.planar.physics.impact` guards the other states).
    """
    c_h = 1.0 - 1.5 * math.sin(block.alpha) ** 2
    if isinstance(cor, str):
        if cor != "housner":
            raise ValueError(f"cor must be a number in [0, 1] or 'housner', got {cor!r}")
        return 1.0, c_h
    value = in_range("cor", cor, 0.0, 1.0)
    if c_h == 0.0:
        raise ValueError("cor: a numeric COR is cor / c_H times the angular momentum about "
                         "the corner, and c_H = 1 - 1.5 sin^2(alpha) is 0 for this block "
                         "(B/H = sqrt(2)); give cor='housner' or change B/H")
    return value / c_h, value


def check_planar_inputs(block, friction) -> Friction:
    """The block and friction of the coupled model, checked (errors name the parameter)."""
    if not isinstance(block, (Block, AsymmetricBlock)):
        raise ValueError(f"block must be a shaketable.Block or AsymmetricBlock, got "
                         f"{type(block).__name__}")
    if isinstance(block, Block) and block.rods is not None:
        raise ValueError("rods: the coupled model (friction=...) refuses prestress rods: a rod "
                         "hinged to the ground ties the block to the table, so it cannot "
                         "slide; run the rocking model (no friction) for a block with rods")
    if not isinstance(friction, Friction):
        raise ValueError(f"friction must be a shaketable Friction(static, dynamic), got "
                         f"{friction!r}")
    return friction


def planar_parameters(block: Block | AsymmetricBlock, cor: float | str
                      ) -> tuple[np.ndarray, float, float]:
    """The engine's parameter array, rho and the cascade's ratio of a block and COR.

    A :class:`Block`: :func:`~shaketable.models.rocking.physics.block_parameters` and
    :func:`impact_ratios`. An :class:`AsymmetricBlock`:
    :func:`~shaketable.models.rocking.physics.asymmetric_parameters` (both pivots, each impact's
    rho and ratio in the array; the scalars are then not read).
    """
    if isinstance(block, AsymmetricBlock):
        parameters = asymmetric_parameters(block, cor)
        return parameters, float(parameters[RHO_PLUS]), float(parameters[COR_PLUS])
    rho, cor_cascade = impact_ratios(block, cor)
    return block_parameters(block), rho, cor_cascade


def simulate_planar(block: Block | AsymmetricBlock, motion: Motion | None = None, *, cor: float | str,
                    friction: Friction, theta0: float = 0.0, theta_dot0: float = 0.0,
                    duration: float | None = None, rtol: float | None = None,
                    output_dt: float = 0.005, rest_tolerance: float | None = None,
                    max_recorded_events: int = 100_000) -> PlanarResult:
    """Response of a free-standing rigid block with Coulomb friction: all five modes.

    Parameters
    ----------
    block : Block
        The block (no prestress rods).
    motion : Motion, optional
        Table accelerations [m/s^2] (horizontal +x, vertical up; no table rotation).
        ``None``: free rocking on a table at rest (give ``duration``).
    cor : float or "housner"
        Coefficient of restitution [-] in [0, 1] (Section 2.7 (5)): a rock-to-rock
        impact with ample friction gives theta' -> cor theta'; ``"housner"`` conserves
        the angular momentum about the striking corner (theta' -> c_H theta').
    friction : Friction
        Static and dynamic coefficients mu_s >= mu_d >= 0 [-].
    theta0, theta_dot0 : float
        Initial rotation [rad] and rate [rad/s]; nonzero: the block starts rocking about
        its lower corner, which stands where it stands at rest.
    duration : float, optional
        Length of the run [s] (the motion is cut or padded with the table at rest).
    rtol : float, optional
        Relative tolerance of the DOP853 steps [-], default 1e-12.
    output_dt : float
        Output interval of free rocking [s].
    rest_tolerance : float, optional
        Cascade duration below which an impact cascade is summed [s] (default 1e-6/p,
        the rocking engine's).
    max_recorded_events : int
        Events kept in the result (all are counted).

    Returns
    -------
    PlanarResult

    Raises
    ------
    ValueError
        Bad input, named: ``rods``, ``friction``, ``cor``, ``motion`` (a table that
        rotates), and the options checked as in :func:`~shaketable.models.api.simulate`.
    """
    friction = check_planar_inputs(block, friction)
    parameters, rho, cor_cascade = planar_parameters(block, cor)
    options = run_options("fast", theta0=theta0, theta_dot0=theta_dot0, duration=duration,
                          rtol=DEFAULT_PLANAR_RTOL if rtol is None else rtol,
                          rest_tolerance=rest_tolerance)
    motion = run_motion(motion, options.duration, output_dt)
    if motion.rotation is not None and np.any(motion.rotation != 0.0):
        raise ValueError("motion: the coupled model (friction=...) has no table rotation "
                         "(pitch); give a motion without rotation")
    capacity = max(1, whole_number("max_recorded_events", max_recorded_events, minimum=0))
    # read-only float64 views whatever the motion (a motion without a vertical gives a
    # fresh writable array of zeros): one compiled signature for every run and the batch
    t_grid, ug, vg = engine_arrays(motion.t, motion.horizontal, motion.vertical_or_zero)
    n = t_grid.size
    out = np.zeros((n, planar.N_OUT))
    events = np.zeros((capacity, planar.EVENT_COLUMNS))
    final = np.zeros(planar.N_OUT)
    info = np.zeros(planar.N_INFO)
    call_interruptibly(planar.integrate, (
        t_grid, ug, vg, parameters, rho, cor_cascade, friction.static, friction.dynamic,
        options.rtol, options.rest_tolerance, options.theta0, options.theta_dot0, out, events,
        final, info, *planar.work_arrays()), 20 * n)
    return planar_result(block, motion, cor, friction, t_grid, out, events, final, info)


def planar_result(block, motion, cor, friction, t_grid, out, events, final, info
                  ) -> PlanarResult:
    """The engine's arrays as a :class:`PlanarResult`."""
    filled = int(info[planar.I_N_OUTPUT])
    status = planar.STATUSES[int(info[planar.I_STATUS])]
    t = t_grid[:filled]
    rows = out[:filled]
    t_end = info[planar.I_T_END]
    if status != "completed" and t_end > t[-1]:
        t = np.append(t, t_end)
        rows = np.vstack([rows, final[None, :]])
    n_events = int(info[planar.I_N_EVENTS])
    kept = events[:min(n_events, events.shape[0])].copy()
    visited = int(info[planar.I_VISITED])

    def direction(index):
        value = info[index]
        return 0 if not np.isfinite(value) else int(value)

    times = (planar.I_TIME_REST, planar.I_TIME_SLIDE, planar.I_TIME_ROCK,
             planar.I_TIME_SLIDE_ROCK, planar.I_TIME_FLIGHT)
    return PlanarResult(
        block=block, motion=motion, cor=cor, friction=friction, t=t,
        x=rows[:, planar.OUT_X].copy(), y=rows[:, planar.OUT_Y].copy(),
        theta=rows[:, planar.OUT_THETA].copy(), x_dot=rows[:, planar.OUT_X_DOT].copy(),
        y_dot=rows[:, planar.OUT_Y_DOT].copy(), theta_dot=rows[:, planar.OUT_OMEGA].copy(),
        slip=rows[:, planar.OUT_SLIP].copy(), mode=rows[:, planar.OUT_MODE].astype(np.int64),
        events=kept, n_events=n_events,
        time_in_mode={name: float(info[index]) for name, index in zip(MODES, times)},
        modes_visited=tuple(name for code, name in enumerate(MODES) if visited >> code & 1),
        peak_slip=float(info[planar.I_PEAK_SLIP]), t_peak_slip=float(info[planar.I_T_PEAK_SLIP]),
        residual_slip=float(rows[-1, planar.OUT_SLIP]),
        peak_excursion=float(info[planar.I_PEAK_EXCURSION]),
        max_abs_theta=float(info[planar.I_MAX_ABS_THETA]), t_max=float(info[planar.I_T_MAX]),
        t_start=float(info[planar.I_T_START]), t_unstable=float(info[planar.I_T_UNSTABLE]),
        unstable_direction=direction(planar.I_UNSTABLE_DIRECTION),
        t_overturn=float(info[planar.I_T_OVERTURN]),
        overturn_direction=direction(planar.I_OVERTURN_DIRECTION),
        t_rest=float(info[planar.I_T_REST]), n_impacts=int(info[planar.I_N_IMPACTS]),
        capped_impacts=int(info[planar.I_CAPPED]), cascades=int(info[planar.I_CASCADES]),
        work_table=float(info[planar.I_W_TABLE]), work_friction=float(info[planar.I_W_FRICTION]),
        impact_loss=float(info[planar.I_IMPACT_LOSS]), energy_start=float(info[planar.I_E0]),
        energy_end=float(info[planar.I_E_END]), status=status,
        peak_base_slip=float(info[planar.I_PEAK_BASE_SLIP]),
        t_peak_base_slip=float(info[planar.I_T_PEAK_BASE_SLIP]),
        statistics={"steps": int(info[planar.I_STEPS]),
                    "rejected": int(info[planar.I_REJECTED]),
                    "evaluations": int(info[planar.I_EVALUATIONS])})
