"""The stack batch's rows against the result objects of the same runs.

The reference of every value is :class:`StackResult` (``simulate_stack``'s result): its
properties compute them from the histories by their own path (the excursion sample by sample
through ``physics.kinematics``, the friction demand and the times from whole arrays, the
counts from the event dicts); the batch computes them from the engine's arrays in one
compiled pass. Equal bit for bit (NaN equal to NaN), on runs that rock, come to rest,
overturn, stay at rest and leave the table (airborne), of two and three blocks, with both
impact laws.
"""

import math
import warnings

import numpy as np
import pandas as pd
import pytest

import shaketable as st
from shaketable.models.rocking.run import extended
from shaketable.models.stack import Stack, pattern_name, simulate_stack
from shaketable.models.stack.batch import Case, simulate_cases, simulate_many

TWO = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.2)], masses=(2.0, 1.0))
THREE = Stack([st.Block(1.0, 0.3), st.Block(0.8, 0.25), st.Block(0.6, 0.2)])
_T = np.arange(0.0, 0.8, 0.01)
_LONG = np.arange(0.0, 3.0, 0.01)
_SHORT = np.arange(0.0, 0.5, 0.01)
MOTIONS = {
    "sine": st.Motion(_T, 4.0 * np.sin(9.0 * _T), name="sine"),            # rocks
    "push": st.Motion.uniform(0.01, 3.0 * np.sin(np.linspace(0, 6, 200)),  # overturns
                              name="push"),
    "weak": st.Motion(_T, 0.5 * np.sin(9.0 * _T), np.cos(5.0 * _T),         # stays at rest
                      name="weak"),
    "strong": st.Motion(_T, 7.0 * np.sin(12.0 * _T), name="strong"),       # past alpha
    "pulse": st.Motion(_LONG, np.where(_LONG < 0.35, 4.0 * np.sin(9.0 * _LONG), 0.0),
                       name="pulse"),                    # rocks, then rests (COR 0.7)
    "lift": st.Motion(_SHORT, 3.0 * np.sin(9.0 * _SHORT), -48.0 * _SHORT,  # airborne
                      name="lift"),
}
STACKS = {"two": TWO, "three": THREE}
LAWS = ("plastic", 0.7)


@pytest.fixture(scope="module")
def frame():
    return simulate_many(STACKS, MOTIONS, LAWS, threads=2)


def _result(stack, motion, law):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if law == "plastic":
            return simulate_stack(stack, motion)
        return simulate_stack(stack, motion, impact="cor", cor=law)


def _expected(result, mu: float, widest: int) -> dict:
    """The row's results, from the result object (``widest``: the batch's tallest stack)."""
    summary = result.summary()
    peaks = np.abs(result.theta).max(axis=0)
    alphas = np.array([block.alpha for block in result.stack.blocks])
    standing = result.peak_before_past_alpha()
    expected = {
        "status": result.status, "overturned": result.status == "overturned",
        "airborne": result.status == "airborne",
        "overturned block": result.overturned_block, "verdict": result.verdict(),
        "t_overturn [s]": result.t_overturn, "t_airborne [s]": result.t_airborne,
        "max_theta_ratio [-]": math.nan if result.status == "overturned"
        else (peaks / alphas).max(),
        "max |theta| bottom [rad]": peaks[0], "max |theta| top [rad]": peaks[-1],
        "t_start [s]": summary["t_start [s]"],
        "first pattern": next((pattern_name(e["pattern_after"]) for e in result.events
                               if e["kind"] == "uplift"), ""),
        "n_impacts": summary["impacts"], "n_events": result.n_events,
        "events not unique": summary["events not unique"],
        "peak top-corner excursion [m]": result.peak_excursion,
        "max F/N [-]": summary["max F/N [-]"],
        "t_friction_exceeded [s]": result.t_friction_exceeded(mu),
        "tension": not math.isnan(result.t_tension), "t_tension [s]": result.t_tension,
        "t_past_alpha [s]": result.t_past_alpha,
        "max F/N before past alpha [-]": standing[0],
        "peak top-corner excursion before past alpha [m]": standing[1],
        "still moving": result.still_moving, "t_end [s]": result.t[-1],
        "solver steps": result.statistics["steps"],
        "solver evaluations": result.statistics["evaluations"],
    }
    for i in range(widest):
        inside = i < result.n_blocks
        expected[f"max |theta| block {i} [rad]"] = peaks[i] if inside else math.nan
        expected[f"max |theta|/alpha block {i} [-]"] = peaks[i] / alphas[i] if inside \
            else math.nan
    return expected


def _same(a, b) -> bool:
    if isinstance(b, float) and math.isnan(b):
        return isinstance(a, float) and math.isnan(a)
    return bool(a == b)


def _check_row(row, result, mu=1.0) -> None:
    widest = sum(1 for key in row.index if key.startswith("max |theta| block "))
    wrong = {key: (row[key], value) for key, value in _expected(result, mu, widest).items()
             if not _same(row[key], value)}
    assert not wrong, wrong


def test_every_row_equals_its_result_object_bit_for_bit(frame):
    # the order: product(stacks, motions, scales, cors), the last fastest
    order = [(s, m, law) for s in STACKS for m in MOTIONS for law in LAWS]
    assert len(frame) == len(order)
    assert list(zip(frame["stack"], frame["motion"])) == [(s, m) for s, m, _ in order]
    assert list(frame["impact"]) == ["plastic" if law == "plastic" else "cor"
                                     for _, _, law in order]
    for k, (s, m, law) in enumerate(order):
        _check_row(frame.iloc[k], _result(STACKS[s], MOTIONS[m], law))
    # the runs cover what they are meant to: every status, rest, rocking that ends at rest
    assert set(frame["status"]) == {"completed", "overturned", "airborne"}
    assert (frame["verdict"] == "stayed at rest").any()
    assert (frame["verdict"].str.startswith("rocked") & ~frame["still moving"]).any()
    assert frame["tension"].any() and (frame["t_past_alpha [s]"].notna()).any()
    assert (frame["blocks"] == 3).any() and frame["max |theta| block 2 [rad]"].isna().any()
    # the inputs
    first = frame.iloc[0]
    assert first["stack"] == "two" and first["blocks"] == 2 and first["method"] == "compiled"
    assert first["stack height [m]"] == 1.8 and first["base width [m]"] == 0.3
    assert math.isnan(first["cor [-]"]) and frame["cor [-]"].iloc[1] == 0.7
    assert first["pga [m/s^2]"] == MOTIONS["sine"].pga and first["duration [s]"] == 0.79
    assert list(frame["stack_index"].unique()) == [0, 1]
    assert frame["n_impacts"].dtype == np.int64 and frame["overturned"].dtype == bool


def test_scales_duration_mu_and_cases():
    strong = MOTIONS["strong"]
    rows = simulate_many(TWO, [strong], scales=(1.0, 0.5), duration=0.5, mu=0.3, threads=1)
    assert list(rows["scale [-]"]) == [1.0, 0.5]
    assert rows["pga [m/s^2]"].iloc[1] == strong.pga * 0.5
    assert rows["duration [s]"].iloc[0] == 0.5 and rows["mu [-]"].iloc[0] == 0.3
    for k, scale in enumerate((1.0, 0.5)):
        motion = extended(strong if scale == 1.0 else strong.scaled(scale), 0.5)
        _check_row(rows.iloc[k], _result(TWO, motion, "plastic"), mu=0.3)
    cases = [Case(THREE, MOTIONS["sine"], 0.7, stack_label="three"),
             Case(TWO, strong, scale=0.5, motion_label="half")]
    listed = simulate_cases(cases, threads=1)
    assert list(listed["stack"]) == ["three", TWO.describe()]
    assert list(listed["motion"]) == ["sine", "half"]
    _check_row(listed.iloc[0], _result(THREE, MOTIONS["sine"], 0.7))
    _check_row(listed.iloc[1], _result(TWO, strong.scaled(0.5), "plastic"))


def test_the_rows_do_not_depend_on_the_threads(frame):
    one = simulate_many(STACKS, MOTIONS, LAWS, threads=1)
    pd.testing.assert_frame_equal(one, frame, check_exact=True)


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda: simulate_many(TWO, [], threads=1), ValueError, "motions must not be empty"),
    (lambda: simulate_many([], MOTIONS["sine"]), ValueError, "stacks must not be empty"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], threads=0), ValueError, "threads"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], []), ValueError, "cors must not be empty"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], 1.5), ValueError, r"cors\[0\]"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], "elastic"), ValueError, r"cors\[0\]"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], scales=(0.0,)), ValueError, r"scales\[0\]"),
    (lambda: simulate_many([TWO, st.Block(1.0, 0.3)], MOTIONS["sine"]), TypeError,
     r"stacks\[1\]"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], mu=-1.0), ValueError, "mu"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], rtol=0.1), ValueError, "rtol"),
    (lambda: simulate_many(TWO, MOTIONS["sine"], theta0=0.1), ValueError, "theta0"),
    (lambda: simulate_cases([]), ValueError, "cases must not be empty"),
    (lambda: simulate_cases([TWO]), TypeError, r"cases\[0\]"),
    (lambda: Case(TWO, MOTIONS["sine"], cor=-0.1), ValueError, "Case.cor"),
])
def test_bad_input_is_refused_by_name(call, error, match):
    with pytest.raises(error, match=match):
        call()
