"""The answer echoes the inputs as typed: the floor and record, SI without inches, tonnes."""

from __future__ import annotations

import json
import re

import pytest

from shaketable.cli import main


@pytest.mark.usefixtures("figure_drafts")
def test_simulate_on_a_floor_says_the_floor_and_the_record(tmp_path, capsys):
    assert main(["simulate", "--block", "30x6in", "--cor", "0.9", "--record",
                 "el-centro-1940-180", "--floor", "3", "--building", "0.6s,17.5m,5",
                 "--duration", "1s", "--out", str(tmp_path / "f")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].startswith("  motion: ") and "El Centro" in lines[1], lines[:3]
    assert lines[1].endswith("at floor 3 of 5"), lines[1]


@pytest.mark.usefixtures("figure_drafts")
def test_slide_without_a_block_answers_in_si(tmp_path, capsys):
    out = tmp_path / "s"
    assert main(["slide", "--record", "pacoima-dam-s16e", "--static-friction", "0.3",
                 "--out", str(out)]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    said = re.match(r"\w+: peak slip (\S+) (mm|m), residual (\S+) (mm|m), ", first)
    assert said and " in" not in first, first
    peak = json.loads((out / "summary.json").read_text())["peak slip [m]"]
    scale = 1e-3 if said[2] == "mm" else 1.0
    assert float(said[1]) * scale == pytest.approx(peak, rel=5e-3)   # 3 digits


def test_masses_typed_in_tonnes_are_said_in_tonnes():
    from shaketable.scenes.stack import mass_line, stack_from_text, typed_mass_unit

    masses = ["10 t", "10 t", "5 t"]
    stack = stack_from_text("2x0.5m,2x0.5m,1x0.4m", masses)
    assert list(stack.mass) == pytest.approx([1e4, 1e4, 5e3])   # 1 t = 1000 kg
    assert typed_mass_unit(masses) == typed_mass_unit("10t,10t,5t") == "t"
    assert mass_line(stack, typed_mass_unit(masses)) == "masses: 10, 10, 5 t (given, bottom first)"
    assert typed_mass_unit(["10 t", "400 kg", "5 t"]) == typed_mass_unit(None) == "kg"
