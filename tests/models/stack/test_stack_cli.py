"""``shaketable simulate --stack``: the answer, the files and the refusals.

Reference numbers are closed forms: the uplift threshold of a two-block stack
|u''| = g min(A1, A2), A1 = b1 (m1 + m2) / (m1 h1 + m2 (2 h1 + h2)), A2 = b2 / h2
(docs/stack.md, check 3 of the stack's validation), and the top corner's excursion of a
stack tilted as one body by theta about its base corner, 2 H sin(theta) + 2 b (1 - cos(theta)).
"""

from __future__ import annotations

import json
import math

import pytest

from tests.test_bad_input import run_cli

STACK = ["simulate", "--stack", "30x6in,30x6in", "--history", "none"]


def _step(tmp_path, acceleration, *extra):
    """A constant table acceleration for 0.1 s (a step), 0.12 s in all."""
    return run_cli(STACK + ["--pulse", f"constant,{acceleration},0.1s", "--duration", "0.12s",
                            "--out", tmp_path / "out", *extra], cwd=tmp_path)


@pytest.mark.usefixtures("figure_drafts")
def test_the_stack_uplifts_as_one_body_at_the_closed_form_threshold(tmp_path):
    # masses 1 : 3: A1 = 3 (4) / (15 + 3 (45)) = 0.08 < A2 = 0.2
    status, out, err = _step(tmp_path, "0.07992g", "--masses", "1kg,3kg")
    assert status == 0, err
    assert "stayed at rest" in out and "uplift: none (the stack stood on the table)" in out
    status, out, err = _step(tmp_path, "0.08008g", "--masses", "1kg,3kg")
    assert status == 0, err
    assert "first uplift at t = 0.000 s: stack as one body (+)" in out


def test_densities_give_masses_in_proportion_to_density_times_area():
    from shaketable.scenes.stack import stack_from_text

    stack = stack_from_text("30x6in,30x2in", densities="2.4t/m3,7800kg/m3")
    area = 30 * 0.0254 * 0.0254
    assert stack.m == pytest.approx([2400 * 6 * area, 7800 * 2 * area], rel=1e-14)
    assert stack_from_text(["1x0.5m"], masses=["2 t"]).m == pytest.approx([2000.0])


@pytest.mark.usefixtures("figure_drafts")
def test_a_release_gives_the_top_corner_excursion_and_writes_the_files(tmp_path):
    status, out, err = run_cli(["simulate", "--stack", "30x6in,30x6in", "--theta0", "0.05rad",
                                "--duration", "0.1s", "--mu", "0.6", "--out",
                                tmp_path / "out"], cwd=tmp_path)
    assert status == 0, err
    lines = out.splitlines()
    assert lines[0].startswith("2 blocks: 30 x 6 in on 30 x 6 in, plastic impacts: rocked")
    excursion = 60 * math.sin(0.05) + 6 * (1 - math.cos(0.05))     # 3.006 in
    assert f"the clearance the stack needs) {excursion:.3g} in" in out
    assert "block 0 (bottom) 30 x 6 in: max |θ| 0.05 rad = 0.253 α" in out   # 0.05 / atan(0.2)
    assert "needed friction: peak F/N" in out and "within mu 0.6" in out
    folder = tmp_path / "out"
    assert {path.name for path in folder.iterdir()} == {
        "history.csv", "events.csv", "summary.json", "calcomp.png"}
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["blocks"] == 2 and summary["mu [-]"] == 0.6
    assert summary["max |theta| [rad]"] == pytest.approx([0.05, 0.05], rel=1e-12)


@pytest.mark.parametrize("argv, message", [
    (["--stack", "30x6in,0x6in"], "--stack: block 1 (top): block size '0x6in': the height"),
    (["--stack", "30x6in,30x8in"], "--stack: block 1 (top) (30 x 8 in) is wider than block 0 "
                                   "(bottom) (30 x 6 in) below it"),
    (["--stack", ","], "--stack: give at least one block"),
    (["--stack", "30x6,30x6in"], "--stack: block 0 (bottom): block size '30x6' has no unit"),
    (["--stack", "30x6in,30x6in", "--masses", "1kg"], "--masses: 1 value(s) for 2 block(s)"),
    (["--stack", "30x6in,30x6in", "--masses", "1kg,0kg"],
     "--masses: block 1 (top): the mass must be positive"),
    (["--stack", "30x6in,30x6in", "--masses", "1,2"], "--masses: block 0 (bottom): '1' has no unit"),
    (["--stack", "30x6in,30x6in", "--masses", "1kg,2kg", "--densities", "1t/m3,1t/m3"],
     "give --masses or --densities, not both"),
    (["--stack", "30x6in,30x6in", "--theta0", "0.1rad,0.1rad,0rad"],
     "--theta0: 3 values for 2 blocks"),
    (["--stack", "30x6in,30x6in", "--friction", "0.5"], "--friction '0.5' cannot be used with"),
    (["--stack", "30x6in,30x6in", "--cor", "1.5"], "--cor must be in [0.0, 1.0]"),
    (["--stack", "30x6in,30x6in", "--mu", "-1"], "--mu must be a friction coefficient >= 0"),
    # assess's upper bound (object.friction in (0, 1.5]); a percentage is not a coefficient
    (["--stack", "30x6in,30x6in", "--mu", "6"], "--mu must be at most 1.5 (a friction "
                                               "coefficient [-], as assess takes it"),
    (["--stack", "30x6in,30x6in", "--mu", "60%"], "argument --mu: '60%': give the friction "
                                                 "coefficient as a number [-], e.g. 0.6"),
    (["--block", "30x6in", "--cor", "0.9", "--mu", "0.5"], "--mu is for a column of blocks"),
    (["--block", "30x6in"], "give --block and --cor (one block), or --stack"),
])
def test_bad_stack_input_is_refused_naming_the_option_and_the_block(tmp_path, argv, message):
    status, out, err = run_cli(["simulate", *argv, "--duration", "1s", "--out",
                                tmp_path / "out"], cwd=tmp_path)
    assert status == 2 and message in err, err
    assert not (tmp_path / "out").exists()
