"""``shaketable.models.rocking.batch``: many runs in one compiled loop, each equal to ``simulate``.

The expected values here are never produced by the batch itself: every row is
compared with an independent call of :func:`shaketable.models.api` (one run, its
own Python driver) on the same inputs, and must agree *exactly* (the batch calls
the same compiled integrator on the same numbers; any difference is a bug).
"""

import math

import numpy as np
import pytest

import shaketable as st
from shaketable.core.constants import G
from shaketable.ground import generators as motions
from shaketable.ground import records
from shaketable.models.rocking import batch

# Scalar columns of the batch table -> the RockingResult attribute they must equal.
SCALARS = {
    "max_abs_theta [rad]": "max_abs_theta",
    # NaN for an overturned run in both (the report's F), never (pi/2)/alpha
    "max_theta_ratio [-]": "max_theta_ratio",
    "t_max [s]": "t_max",
    "t_start [s]": "t_start",
    "t_unstable [s]": "t_unstable",
    "unstable_direction": "unstable_direction",
    "t_overturn [s]": "t_overturn",
    "overturn_direction": "overturn_direction",
    "t_airborne [s]": "t_airborne",
    "t_rest [s]": "t_rest",
    "n_impacts": "n_impacts",
    "cascades": "cascades",
    "status": "status",
    "overturned": "overturned",
    "unstable": "unstable",
}


def _expected(result, attribute):
    """The RockingResult value a batch column must equal."""
    return getattr(result, attribute)


def _same(a, b) -> bool:
    """Bit-for-bit equality, NaN equal to NaN."""
    if isinstance(b, float) and math.isnan(b):
        return isinstance(a, (float, np.floating)) and math.isnan(a)
    return a == b


def _assert_rows_equal_simulate(frame, cases, **options):
    assert len(frame) == len(cases)
    for k, (block, motion, cor) in enumerate(cases):
        expected = st.simulate(block, motion, cor=cor, **options)
        row = frame.iloc[k]
        for column, attribute in SCALARS.items():
            assert _same(row[column], _expected(expected, attribute)), (
                f"row {k} ({block.describe()}, {motion.name}, cor {cor}): {column} = "
                f"{row[column]!r}, simulate gives {_expected(expected, attribute)!r}")
        for key, value in expected.statistics.items():
            assert row[f"solver {key}"] == value, (k, key)
        assert row["airborne"] == (expected.status == "airborne")


@pytest.fixture(scope="module")
def pacoima():
    # 30 s of the bundled Pacoima Dam S16E record with its recorded vertical.
    return records.load("pacoima-dam-s16e")


def test_cartesian_product_equals_simulate_row_by_row(pacoima):
    rods = st.PrestressRods.from_inches(0.4, 0.4, 12)  # Figs. 4.16-4.17: K 0.4 W/in, F0 0.4 W
    blocks = [st.Block.parse("16x4ft"), st.Block.parse("30x6in"),
              st.Block.parse("8x2ft", rods=rods)]
    artificial = motions.artificial("B-1", seed=4, duration=12.0)
    cors = [0.9, 1.0]
    frame = batch.simulate_many(blocks, [pacoima, artificial], cors, threads=2, duration=12.0)
    cases = [(b, m, c) for b in blocks for m in (pacoima, artificial) for c in cors]
    # the order is product(blocks, motions, scales, cors)
    assert list(frame["cor [-]"]) == [c for _, _, c in cases]
    assert list(frame["rods"]) == [b.rods is not None for b, _, _ in cases]
    _assert_rows_equal_simulate(frame, cases, duration=12.0)
    # the set covers what it must: vertical, rods, overturning and not
    assert frame["motion_vertical"].any() and frame["rods"].any()
    assert frame["overturned"].any() and not frame["overturned"].all()


def test_airborne_run_is_flagged_not_nan():
    # 1.2 g vertical at 2 Hz: g + v reaches zero at sin(4 pi t) = -1/1.2, i.e. at
    # t = (pi + asin(1/1.2)) / (4 pi) = 0.3266 s (first time after 0.25 s).
    shaking = motions.harmonic(2.0, horizontal=0.3 * G, vertical=1.2 * G, duration=2.0, dt=0.005)
    block = st.Block.parse("30x6in")
    frame = batch.simulate_many(block, shaking, 0.9)
    row = frame.iloc[0]
    assert row["status"] == "airborne" and row["airborne"]
    expected_time = (math.pi + math.asin(1 / 1.2)) / (4 * math.pi)
    assert row["t_airborne [s]"] == pytest.approx(expected_time, abs=0.005)  # one sample
    assert np.isfinite(row["max_theta_ratio [-]"])
    _assert_rows_equal_simulate(frame, [(block, shaking, 0.9)])


def test_explicit_cases_scales_and_other_methods(pacoima):
    block = st.Block.parse("6x3ft")
    harmonic = motions.harmonic(2.0, horizontal=0.5 * G, duration=4.0)          # Fig. 3.7 shaking
    cases = [batch.Case(block, pacoima, 1.0, scale=0.5),
             batch.Case(st.Block.parse("30x6in"), harmonic, 0.925),
             batch.Case(block, pacoima, 0.9, scale=1.3)]
    for method in ("fast", "predictor-corrector", "linear"):
        frame = batch.simulate_cases(cases, method=method, duration=10.0, threads=1)
        expected = [(c.block, c.motion.scaled(c.scale) if c.scale != 1.0 else c.motion, c.cor)
                    for c in cases]
        _assert_rows_equal_simulate(frame, expected, method=method, duration=10.0)
        assert list(frame["scale [-]"]) == [0.5, 1.0, 1.3]
        assert frame["pga [m/s^2]"].iloc[0] == pytest.approx(0.5 * pacoima.pga, rel=1e-15)


def test_initial_conditions_and_rtol_pass_through():
    # free rocking (Fig. 3.4: 30 x 6 in, COR 0.925, theta0 = 0.5 alpha) on a table at rest
    block = st.Block.parse("30x6in")
    rest = st.Motion.at_rest(8.0)
    frame = batch.simulate_many(block, rest, 0.925, theta0=0.5 * block.alpha, rtol=1e-9)
    expected = st.simulate(block, rest, cor=0.925, theta0=0.5 * block.alpha, rtol=1e-9)
    assert frame["t_rest [s]"].iloc[0] == expected.t_rest
    assert frame["n_impacts"].iloc[0] == expected.n_impacts > 10


def test_thread_count_does_not_change_results(pacoima):
    blocks = [st.Block.from_feet(h, w) for h, w in [(4, 1), (8, 2), (12, 3), (16, 4)]]
    one = batch.simulate_many(blocks, pacoima, [0.9, 0.95], threads=1, duration=10.0)
    two = batch.simulate_many(blocks, pacoima, [0.9, 0.95], threads=2, duration=10.0)
    assert one.equals(two)


def test_errors_name_the_argument():
    block = st.Block.parse("30x6in")
    rest = st.Motion.at_rest(1.0)
    with pytest.raises(ValueError, match="reference solver runs one at a time"):
        batch.simulate_many(block, rest, 0.9, method="reference")
    with pytest.raises(ValueError, match=r"cors\[1\]"):
        batch.simulate_many(block, rest, [0.9, 1.5])
    with pytest.raises(ValueError, match="unknown option 'theta_0'"):
        batch.simulate_many(block, rest, 0.9, theta_0=0.1)
    with pytest.raises(ValueError, match=r"motions\[0\] must be a shaketable.Motion"):
        batch.simulate_many(block, [np.zeros(3)], 0.9)
    with pytest.raises(ValueError, match="Case.scale"):
        batch.Case(block, rest, 0.9, scale=-1.0)
    with pytest.raises(ValueError, match="threads"):
        batch.simulate_many(block, rest, 0.9, threads=0)


def test_every_method_flags_an_airborne_run():
    # 1.2 g vertical at 2 Hz: g + 1.2 g sin(4 pi t) = 0 first at
    # t = (pi + asin(1/1.2)) / (4 pi) = 0.32840 s (to the 5 ms linear sampling of the
    # input); every method must stop there and flag the run (linear once looped forever)
    shaking = motions.harmonic(2.0, horizontal=0.3 * G, vertical=1.2 * G, duration=2.0, dt=0.005)
    block = st.Block.parse("30x6in")
    for method in ("fast", "predictor-corrector", "linear"):
        frame = batch.simulate_many(block, shaking, 0.9, method=method, threads=1)
        assert frame["status"].iloc[0] == "airborne"
        single = st.simulate(block, shaking, cor=0.9, method=method)
        assert single.status == "airborne"
        assert single.t_airborne == pytest.approx(frame["t_airborne [s]"].iloc[0], abs=0)
        assert single.t_airborne == pytest.approx(
            (math.pi + math.asin(1 / 1.2)) / (4 * math.pi), abs=1e-4)


