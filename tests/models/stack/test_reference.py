"""The stack's runs against an independent formulation, and longer columns."""

import math
import warnings

import numpy as np
from scipy.integrate import solve_ivp

import shaketable as st
from shaketable.models.stack import Stack, StackTensionWarning, pattern_name, simulate_stack
from shaketable.models.stack.reference import newton_euler


def _newton_euler_between_samples(result):
    """Largest difference [rad, rad/s] between the run and the Newton-Euler equations
    (models/stack/reference.py, no shared code) integrated by DOP853 from each output sample
    to the next, over the intervals without an event; and the patterns visited."""
    stack, motion = result.stack, result.motion
    event_times = np.array([e["t"] for e in result.events])
    worst, visited = 0.0, set()
    for k in range(result.t.size - 1):
        t0, t1 = result.t[k], result.t[k + 1]
        pattern = tuple(int(s) for s in result.patterns[k])
        if np.any((event_times >= t0 - 1e-12) & (event_times <= t1 + 1e-12)) or not any(pattern):
            continue
        visited.add(pattern)
        u0, u1 = motion.horizontal[k], motion.horizontal[k + 1]
        v0, v1 = motion.vertical_or_zero[k], motion.vertical_or_zero[k + 1]

        def rhs(time, y, pattern=pattern, t0=t0, u0=u0, u1=u1, v0=v0, v1=v1):
            x = (time - t0) / (t1 - t0)
            n = y.size // 2
            theta_ddot, _ = newton_euler(stack.b, stack.h, stack.m, y[:n], y[n:], pattern,
                                         u0 + (u1 - u0) * x, v0 + (v1 - v0) * x)
            return np.concatenate([y[n:], theta_ddot])

        y0 = np.concatenate([result.theta[k], result.theta_dot[k]])
        end = solve_ivp(rhs, (t0, t1), y0, method="DOP853", rtol=1e-13, atol=1e-15).y[:, -1]
        worst = max(worst, np.abs(end - np.concatenate([result.theta[k + 1],
                                                        result.theta_dot[k + 1]])).max())
    return worst, visited


def test_two_block_runs_agree_with_newton_euler_in_every_pattern():
    # two runs that together visit every kind of moving pattern of two blocks (the stack as
    # one body, the top alone, both the same way, both opposite ways)
    t = np.arange(0.0, 1.0, 0.02)
    worst, visited = 0.0, set()
    runs = [(Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)]),
             st.Motion(t, 3.5 * np.sin(7 * t) * np.exp(-0.5 * t), 1.0 * np.sin(11 * t))),
            (Stack([st.Block(0.6, 0.6), st.Block(0.9, 0.2)]),
             st.Motion(t, 2.6 * np.sin(8 * t)))]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StackTensionWarning)
        for stack, motion in runs:
            error, patterns = _newton_euler_between_samples(simulate_stack(stack, motion))
            worst, visited = max(worst, error), visited | patterns
    assert worst < 1e-9
    kinds = {pattern_name(p).split(" (")[0] for p in visited}
    assert kinds == {"stack as one body", "top alone", "both, same way", "both, opposite ways"}


def test_the_constant_cor_law_of_one_block_is_the_engines():
    # impact="cor": the report's theta'+ = cor theta'- (Section 2.7 (5)), as the engine
    block = st.Block(1.0, 0.25)
    result = simulate_stack(Stack([block]), None, impact="cor", cor=0.8,
                            theta0=[0.7 * block.alpha], duration=1.5, output_dt=0.01)
    engine = st.simulate(block, None, cor=0.8, theta0=0.7 * block.alpha, duration=1.5,
                         output_dt=0.01, method="reference")
    assert np.abs(result.theta[:, 0] - engine.theta).max() < 1e-9


def test_columns_of_three_and_ten_blocks_run_to_the_end():
    # a constant pulse of 0.25 g for 0.3 s on columns of 3 and 10 equal blocks (b = 0.15 m,
    # h = 0.25 m): the column about its base corner uplifts at A1 = b / (n h) (0.2 and 0.06),
    # any upper part above its interface at b / (k h) >= A1, so the column rises as one body
    t = np.arange(0.0, 0.5, 0.01)
    pulse = st.Motion(t, np.where(t < 0.3, 0.25 * st.G, 0.0))
    for n in (3, 10):
        result = simulate_stack(Stack([st.Block(0.5, 0.3)] * n), pulse)
        assert result.status == "completed" and result.t[-1] == t[-1]
        assert result.events[0]["kind"] == "uplift" and result.events[0]["t"] == 0.0
        # the column uplifts as one body: A1 of n equal blocks is b / (n h) < 0.25
        assert result.events[0]["pattern_after"] == (1,) + (0,) * (n - 1)
        assert math.isfinite(result.peak_excursion)


def test_a_three_block_run_agrees_with_newton_euler():
    # three blocks under shaking that opens more than one interface (the top two rocking on
    # the bottom one): Newton-Euler integrated between the samples, as for two blocks
    t = np.arange(0.0, 1.0, 0.01)
    stack = Stack([st.Block(0.6, 0.6), st.Block(0.9, 0.3), st.Block(0.6, 0.15)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StackTensionWarning)
        result = simulate_stack(stack, st.Motion(t, 3.0 * np.sin(8 * t)))
    error, visited = _newton_euler_between_samples(result)
    assert error < 1e-9
    assert any(sum(s != 0 for s in p) >= 2 for p in visited)


def test_blocks_from_millimetres_to_a_hundred_metres_are_similar():
    # a 2 mm and a 100 m version of one stack (lengths x 5e4), the motion's time stretched by
    # sqrt(5e4) with the same accelerations: the same rotations at the corresponding times
    small = Stack([st.Block(0.004, 0.0016), st.Block(0.003, 0.0012)], masses=(1.0, 3.0))
    large = Stack([st.Block(200.0, 80.0), st.Block(150.0, 60.0)], masses=(1.0, 3.0))
    stretch = math.sqrt(5e4)
    t = np.linspace(0.0, 0.1, 101)
    acceleration = 4.5 * np.sin(2 * math.pi * t / 0.05)
    a = simulate_stack(small, st.Motion(t, acceleration))
    b = simulate_stack(large, st.Motion(stretch * t, acceleration))
    assert len(a.events) >= 2 and [e["kind"] for e in a.events] == [e["kind"] for e in b.events]
    assert np.abs(a.theta - b.theta).max() < 1e-8
