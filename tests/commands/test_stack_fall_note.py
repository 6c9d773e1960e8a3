"""A stack that overturns: the warnings raised once the column was falling become one
short note line after the answer, silenced by --quiet (the model still warns in Python)."""

from __future__ import annotations

import pytest

from shaketable.cli import main

#: The model's two warnings of a falling column, as simulate --stack said them (trial 4).
TENSION = ("a contact of the stack carried a tensile force from t = 3.85 s: the model (no "
           "flight) is outside its assumptions there (after a block passed its alpha at "
           "t = 3.19 s: the column was already falling; the motion of the fall is outside "
           "the model, not the fall)")
FRICTION = ("a contact of the stack needed a friction coefficient F/N above 1 from t = 3.84 s:"
            " real blocks would slide there, the model (no slip) is outside its assumptions "
            "(after a block passed its alpha at t = 3.19 s: the column was already falling; "
            "the motion of the fall is outside the model, not the fall)")


def test_the_warnings_after_the_fall_become_one_note():
    from shaketable.scenes.stack import fall_note

    early = "a contact of the stack carried a tensile force from t = 0.5 s: outside"
    note, rest = fall_note([TENSION, FRICTION, early])
    assert note == ("note: the lift-off and sliding came after the column began to fall "
                    "(t = 3.19 s): the fall is the model's answer, not its motion "
                    "(summary.json: warnings)")
    assert rest == [early]           # a warning while the column stands is said whole
    assert fall_note([]) == ("", [])


STEP = """name = "step-short"
[stack]
blocks = ["1x0.1m", "1x0.1m"]
duration = "1.0 s"
[motion]
kind = "constant-pulse"
acceleration = "0.7 g"
pulse_duration = "0.1 s"
duration = "1.0 s"
dt = "0.005 s"
"""


@pytest.mark.usefixtures("figure_drafts")
@pytest.mark.parametrize("quiet", [False, True])
def test_a_falling_stack_prints_one_note_and_quiet_silences_it(tmp_path, capsys, quiet):
    # stack-step's column (docs/stack.md): a block passes its alpha early, then its
    # contacts pull and slide while it falls; cut at 1 s
    scene = tmp_path / "step.toml"
    scene.write_text(STEP)
    assert main(["run", str(scene), "--out", str(tmp_path / "o")]
                + (["--quiet"] if quiet else [])) == 0
    out, err = capsys.readouterr()
    assert "warning" not in err, err
    notes = [line for line in out.splitlines() if line.startswith("note: ")]
    assert notes == ([] if quiet else [notes[0]])
    if not quiet:
        assert "came after the column began to fall (t = " in notes[0]
