"""The engine is compiled once whatever the entry point.

``simulate`` and the batch call the same compiled integrator of each method
(:data:`shaketable.models.rocking.engine.INTEGRATORS`) and hand it arrays of one type (float64,
C-contiguous, read-only inputs; ``models.rocking.run.engine_arrays``), so numba compiles it
for one signature. Two signatures meant compiling the whole engine
twice (seconds on a fresh install).
"""

import numpy as np

from shaketable import Block, Motion, simulate
from shaketable.models.rocking import engine
from shaketable.models.rocking.batch import simulate_many
from shaketable.models.rocking.run import engine_arrays


def test_simulate_and_the_batch_use_one_compiled_signature():
    block = Block.from_feet(4, 1)
    t = np.linspace(0.0, 1.0, 101)
    record = Motion(t, 3.0 * np.sin(8.0 * t), 0.5 * np.cos(5.0 * t), name="two components")
    pitched = Motion(t, 3.0 * np.sin(8.0 * t), rotation=0.1 * np.sin(3.0 * t), name="pitched")
    writable_t = np.array(t)  # a motion built from writable arrays
    plain = Motion(writable_t, np.array(3.0 * np.sin(8.0 * t)), name="writable")
    for motion in (record, pitched, plain):
        simulate(block, motion, cor=0.9)
        simulate(block, motion, cor=0.9, method="predictor-corrector")
    simulate(block, None, cor=0.9, theta0=0.05, duration=0.5)
    simulate_many([block], [record, pitched, plain], [0.8, 0.9], scales=[1.0, 0.5][:1])
    simulate_many([block], [record, plain], [0.8], threads=1)
    for integrator in (engine.integrate_fast, engine.integrate_predictor_corrector):
        assert len(integrator.signatures) == 1, integrator.signatures


def test_engine_arrays_are_read_only_views_of_the_same_numbers():
    values = np.arange(5.0)
    (view,) = engine_arrays(values)
    assert not view.flags.writeable and view.flags.c_contiguous
    assert np.shares_memory(view, values) and values.flags.writeable
    (converted,) = engine_arrays(np.arange(5))  # integers: converted to float64
    assert converted.dtype == np.float64 and np.array_equal(converted, values)


def test_a_motion_without_a_vertical_component_gives_the_engines_the_same_array_types():
    # The stack, sliding and asymmetric engines take ``Motion.vertical_or_zero`` as it is:
    # zeros made writable (no vertical component) and a motion's own read-only array were two
    # numba signatures, the whole stack engine compiled twice (a harmonic, then a record)
    import numba

    from shaketable.core.constants import G
    from shaketable.ground.generators import harmonic
    from shaketable.models.sliding.engine import slide, stick_slip_kernel

    t = np.linspace(0.0, 1.0, 101)
    horizontal_only = harmonic(2.0, horizontal=0.5 * G, duration=0.5)
    both = Motion(t, 3.0 * np.sin(8.0 * t), 0.5 * np.cos(5.0 * t), name="two components")
    for zeros in (horizontal_only.vertical_or_zero, horizontal_only.rotation_or_zero):
        assert not zeros.flags.writeable and not zeros.any()
    kinds = {str(numba.typeof(np.ascontiguousarray(motion.vertical_or_zero, dtype=float)))
             for motion in (horizontal_only, both)}
    assert kinds == {"readonly array(float64, 1d, C)"}
    for motion in (horizontal_only, both):
        slide(motion, 0.3)
    assert len(stick_slip_kernel.signatures) == 1, stick_slip_kernel.signatures


def test_the_asymmetric_engine_is_compiled_for_one_signature():
    # simulate_asymmetric hands the engine a motion's read-only arrays, the batch its
    # concatenated records (read-only views too) and each case's block and motion index as
    # contiguous arrays (a column of the cases table is contiguous only with one case):
    # writable inputs or a strided index would compile the engine a second time
    from shaketable import AsymmetricBlock
    from shaketable.models.rocking import asymmetric

    block = AsymmetricBlock.from_angles(0.15, 0.35, 0.5)
    t = np.linspace(0.0, 1.0, 101)
    record = Motion(t, 3.0 * np.sin(8.0 * t), 0.5 * np.cos(5.0 * t), name="two components")
    plain = Motion(np.array(t), np.array(3.0 * np.sin(8.0 * t)), name="writable")
    for motion in (record, plain):
        simulate(block, motion, cor=0.9)
    simulate(block, None, cor=0.9, theta0=0.05, duration=0.5)
    for cases in ([[0, 0]], [[0, 0], [0, 1]]):
        asymmetric.simulate_many_asymmetric([block], [record, plain], np.array(cases),
                                            [0.8] * len(cases), threads=1)
    for compiled in (asymmetric.integrate_asymmetric, asymmetric._run_cases):
        assert len(compiled.signatures) == 1, compiled.signatures
