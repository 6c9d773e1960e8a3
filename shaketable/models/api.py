"""``simulate``: one block, one ground motion, one solver."""

from __future__ import annotations

from typing import cast

import numpy as np

from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.core.impulses import ImpulsiveMotion
from shaketable.core.motion import Motion, whole_number
from shaketable.core.validation import in_range
from shaketable.models.rocking import engine
from shaketable.models.rocking.physics import block_parameters
from shaketable.models.rocking.run import (
    COMPILED_METHODS,
    call_interruptibly,
    check_fixed_steps,
    engine_arrays,
    impact_buffers,
    result_from_info,
    run_motion,
    run_options,
)
from shaketable.models.sliding.result import Friction


def simulate(block: Block | AsymmetricBlock, motion: Motion | ImpulsiveMotion | None = None, *,
             cor: float | None = None, theta0: float = 0.0,
             theta_dot0: float = 0.0, duration: float | None = None, method: str = "fast",
             rtol: float | None = None, subdivisions: int = 4, output_dt: float = 0.005,
             rest_tolerance: float | None = None, max_recorded_impacts: int = 100_000,
             top_force: float = 0.0, friction: Friction | None = None, model: str | None = None):
    """Rocking response of a rigid block, Eqs. (2-13)/(2-14) with impacts.

    Parameters
    ----------
    block : Block or AsymmetricBlock
        The block (with optional prestress rods); an
        :class:`~shaketable.core.geometry.AsymmetricBlock` runs
        :func:`shaketable.models.rocking.asymmetric.simulate_asymmetric` (``method`` "fast" or
        "reference", ``cor`` a number or ``"housner"``, no friction, rods, impulses or top
        force) and returns an :class:`~shaketable.models.rocking.asymmetric_result.AsymmetricResult`.
        A :class:`~shaketable.models.stack.Stack` runs the stack model
        (:func:`~shaketable.models.stack.simulate_stack`; ``cor`` then selects the
        constant-COR law, the plastic law by default) and returns a ``StackResult``.
    motion : Motion or ImpulsiveMotion, optional
        Ground accelerations [m/s^2]; an :class:`~shaketable.core.impulses.ImpulsiveMotion`
        adds steps of the table's velocity, applied exactly as jumps of theta'
        (:mod:`shaketable.models.rocking.impulses`). ``None`` is free rocking on a table at
        rest (Figs. 2.9, 2.10, 3.4): give ``duration``.
    cor : float
        Coefficient of restitution [-] in [0, 1] (Section 2.7 (5)); required for a block.
    theta0 : float
        Initial rotation [rad], |theta0| < pi/2.
    theta_dot0 : float
        Initial angular velocity [rad/s].
    duration : float, optional
        Length of the run [s]; the run ends at exactly ``t[0] + duration``.
        With a motion, the motion is cut there (the last sample interpolated
        linearly when it falls between samples) or continued with the table
        at rest.
    method : str
        One of :data:`~shaketable.models.rocking.layout.METHODS`: ``"fast"`` (default), ``"reference"``,
        ``"predictor-corrector"``, ``"linear"``.
    rtol : float, optional
        Relative tolerance of the adaptive methods [-] (fast 1e-11,
        reference 1e-12 by default).
    subdivisions : int
        Equal parts each input interval is divided into by the
        predictor-corrector (Section 2.8): an integer >= 1 (``2.7`` is
        refused, not truncated).
    output_dt : float
        Output interval for free rocking [s]: output at 0, output_dt,
        2 output_dt, ... and at ``duration`` (:meth:`Motion.at_rest`), never
        beyond it.
    rest_tolerance : float, optional
        Remaining duration of an impact cascade [s] below which it is summed in
        closed form (default 1e-6 / p).
    max_recorded_impacts : int
        Impacts kept in ``impact_times`` (all are counted), an integer >= 0.
    top_force : float
        Constant horizontal force at the middle of the top of the block per
        unit mass [m/s^2], positive along +x: one potentiometer wire
        (Section 3.3); two opposite wires cancel.
    friction : Friction, optional
        Coulomb friction between block and table: runs the coupled planar model
        (rest, slide, rock, slide-rock, free flight;
        :func:`shaketable.models.planar.run.simulate_planar`) and returns a
        :class:`~shaketable.models.planar.result.PlanarResult`. ``cor`` may then also be
        ``"housner"``; ``method`` must be ``"fast"`` (its own compiled engine),
        ``top_force`` 0, ``subdivisions`` unused, no rods. Without it nothing changes.
    model : str, optional
        The model by name, one of :data:`shaketable.models.registry.MODELS`
        (``"rocking"``, ``"planar"``, ``"sliding"``, ``"stack"``). ``None`` (default): the
        model of the input (:func:`~shaketable.models.registry.model_for`): a ``Block``
        rocks, with ``friction`` it is the planar block, a
        :class:`~shaketable.models.stack.Stack` is the stack model's. ``"sliding"``: the
        block only slides (:func:`~shaketable.models.sliding.engine.slide`, with
        ``friction``; the rocking options stay at their defaults).

    Returns
    -------
    RockingResult
        (:class:`~shaketable.models.planar.result.PlanarResult` when ``friction`` is given,
        the chosen model's result with ``model``)

    Raises
    ------
    ValueError
        For invalid parameters; the message names the parameter.
    shaketable.models.rocking.reference.ReferenceSolverError
        ``method="reference"`` only: SciPy's integrator gave up or made no
        progress.
    """
    other = _other_model(block, motion, cor=cor, theta0=theta0, theta_dot0=theta_dot0,
                         duration=duration, method=method, rtol=rtol, subdivisions=subdivisions,
                         output_dt=output_dt, rest_tolerance=rest_tolerance,
                         max_recorded_impacts=max_recorded_impacts, top_force=top_force,
                         friction=friction, model=model)
    if other is not None:
        return other
    block, motion = cast(Block, block), cast("Motion | None", motion)   # the rest went above
    cor = in_range("cor", cast(float, cor), 0.0, 1.0)
    options = run_options(method, theta0=theta0, theta_dot0=theta_dot0, duration=duration,
                          rtol=rtol, subdivisions=subdivisions, rest_tolerance=rest_tolerance,
                          top_force=top_force)
    motion = run_motion(motion, options.duration, output_dt)
    method, rtol, subdivisions = options.method, options.rtol, options.subdivisions
    theta0, theta_dot0, rest = options.theta0, options.theta_dot0, options.rest_tolerance

    parameters = block_parameters(block, options.top_force)
    t_grid, ug, vg, rg = engine_arrays(motion.t, motion.horizontal, motion.vertical_or_zero,
                                       motion.rotation_or_zero)
    n = t_grid.size
    check_fixed_steps(method, n, subdivisions)
    # filled up to info[INFO_N_OUTPUT] / the impact count and read only that far
    theta, omega, acceleration = np.empty(n), np.empty(n), np.empty(n)
    work = n * (subdivisions if method == "predictor-corrector" else 1)
    impact_times, impact_velocities = impact_buffers(
        max(1, whole_number("max_recorded_impacts", max_recorded_impacts, minimum=0)), work)
    info = np.zeros(engine.N_INFO)
    if method == "reference":
        from shaketable.models.rocking.reference import (
            integrate_reference,  # SciPy: loaded on use
        )

        integrate_reference(t_grid, ug, vg, rg, parameters, block.alpha, block.p, cor, theta0,
                            theta_dot0, rtol, rest, theta, omega, acceleration, impact_times,
                            impact_velocities, info)
    else:
        call_interruptibly(engine.INTEGRATORS[COMPILED_METHODS[method]], (
            t_grid, ug, vg, rg, 1.0, parameters, cor, theta0, theta_dot0, rtol, subdivisions,
            rest, theta, omega, acceleration, impact_times, impact_velocities, info), work)
    return result_from_info(block, motion, cor, method, t_grid, theta, omega, acceleration,
                   impact_times, impact_velocities, info)


def _other_model(block, motion, *, cor, theta0, theta_dot0, duration, method, rtol,
                 subdivisions, output_dt, rest_tolerance, max_recorded_impacts, top_force,
                 friction, model):
    """:func:`simulate` for what the rocking engine does not run: another model's input (a
    stack, an asymmetric block), friction (the planar model) or velocity steps (split at
    the steps, :mod:`shaketable.models.rocking.impulses`); None for a Block the engine runs."""
    if model is not None or not isinstance(block, Block):   # another model, else refused below
        from shaketable.models.registry import model_for, model_named

        chosen = (model_for(block, {"friction": friction}) if model is None
                  else model_named(model, block))
        if chosen is not None and chosen.name in ("rocking", "planar"):  # run below
            if model is not None:   # named: its options checked (an input is, below)
                chosen.validate(block, {"friction": friction})
        elif chosen is not None:
            return chosen.run(block, motion, cor=cor, theta0=theta0, theta_dot0=theta_dot0,
                              duration=duration, method=method, rtol=rtol,
                              subdivisions=subdivisions, output_dt=output_dt,
                              rest_tolerance=rest_tolerance, top_force=top_force,
                              friction=friction)
    if isinstance(block, AsymmetricBlock) and friction is None:
        if isinstance(motion, ImpulsiveMotion) or top_force != 0.0:
            raise ValueError("block: impulses and top_force are not offered for an "
                             "AsymmetricBlock")
        from shaketable.models.rocking.asymmetric import simulate_asymmetric

        return simulate_asymmetric(block, motion, cor=cast(float, cor), theta0=theta0,
                                   theta_dot0=theta_dot0, duration=duration, method=method,
                                   rtol=1e-12 if rtol is None else rtol, output_dt=output_dt)
    cor = cast(float, cor)   # a Block's cor is checked where it is used (None: ValueError)
    if friction is not None:
        from shaketable.models.planar.run import simulate_planar  # compiled on first use

        if method != "fast":
            raise ValueError(f"method {method!r} is not offered with friction: the coupled "
                             "model has its own engine (give method='fast')")
        if top_force != 0.0:
            raise ValueError("top_force is not offered with friction (the coupled model has "
                             "no top force)")
        if isinstance(motion, ImpulsiveMotion):
            raise ValueError("impulses (velocity steps) are not offered with friction: the "
                             "coupled model takes a sampled motion")
        return simulate_planar(block, motion, cor=cor, friction=friction, theta0=theta0,
                               theta_dot0=theta_dot0, duration=duration, rtol=rtol,
                               output_dt=output_dt, rest_tolerance=rest_tolerance,
                               max_recorded_events=max_recorded_impacts)
    if not isinstance(block, Block):
        raise ValueError(f"block must be a shaketable.Block, got {type(block).__name__}")
    if isinstance(motion, ImpulsiveMotion):   # velocity steps: split there (models.rocking.impulses)
        from shaketable.models.rocking.impulses import simulate_impulsive

        return simulate_impulsive(block, motion, simulate=simulate, cor=cor, theta0=theta0,
                                  theta_dot0=theta_dot0,
                                  duration=duration, method=method, rtol=rtol,
                                  subdivisions=subdivisions, output_dt=output_dt,
                                  rest_tolerance=rest_tolerance,
                                  max_recorded_impacts=max_recorded_impacts, top_force=top_force)
    return None
