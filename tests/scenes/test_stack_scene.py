"""Scenes with ``[stack]``: parsed with the file, key, line and block in every refusal; run
with the stack model; the teaching scene's kick where an independent engine puts it."""

from __future__ import annotations

import math

import pytest

from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import SceneError, load_scene
from shaketable.scenes.stack import StackScene, run_stack_scene

GOOD = '''name = "two"
[stack]
blocks = ["30x6in", "30x6in"]
masses = ["100 kg", "50 kg"]
theta0 = "0.5 alpha"
duration = "0.05 s"
mu = 0.5
[motion]
kind = "free"
'''


def _write(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_a_stack_scene_is_read_bottom_first_in_si(tmp_path):
    scene = load_scene(_write(tmp_path, GOOD))
    assert isinstance(scene, StackScene)
    assert scene.stack.n == 2 and list(scene.stack.m) == [100.0, 50.0]
    assert scene.theta0 == pytest.approx([0.5 * math.atan(0.2)] * 2, rel=1e-15)
    assert scene.duration == 0.05 and scene.mu == 0.5 and scene.cor is None


@pytest.mark.parametrize("old, new, message", [
    ('"30x6in", "30x6in"', '"30x6in", "30x8in"',
     "stack.blocks: block 1 (top) (30 x 8 in) is wider than block 0 (bottom) (30 x 6 in) below "
     "it: an overhanging block is not offered by the stack model (docs/stack.md) (line 3)"),
    ('"30x6in", "30x6in"', '"30x6in", "0x6in"',
     "stack.blocks: block 1 (top): block size '0x6in': the height must be positive (line 3)"),
    ('"30x6in", "30x6in"', '', "stack.blocks: give at least one block"),
    ('["100 kg", "50 kg"]', '["100 kg"]', "stack.masses: 1 value(s) for 2 block(s)"),
    ('["100 kg", "50 kg"]', '["100 kg", "-5 kg"]',
     "stack.masses: block 1 (top): the mass must be positive"),
    ('theta0 = "0.5 alpha"', 'theta0 = ["1 deg", "2 deg", "3 deg"]',
     "stack.theta0: 3 values for 2 blocks"),
    ('mu = 0.5', 'mu = "high"', "stack.mu must be a friction coefficient >= 0"),
    ('mu = 0.5', 'mu = 2', "stack.mu must be at most 1.5 (a friction coefficient [-]"),
    ('mu = 0.5', 'cor = 1.5', "stack.cor must be a number in [0, 1]"),
    ('mu = 0.5', 'colour = "red"', "unknown key 'colour' in [stack]"),
    ('duration = "0.05 s"\n', '', "stack.duration is needed for free rocking"),
    ('[motion]', '[rocking]\ncor = 0.9\n[motion]', "unknown key 'rocking' in [top level of a "
                                                  "stack scene]"),
])
def test_bad_stack_scenes_name_the_file_key_line_and_block(tmp_path, old, new, message):
    path = _write(tmp_path, GOOD.replace(old, new))
    with pytest.raises(SceneError) as error:
        load_scene(path)
    assert str(error.value).startswith(str(path)) and message in str(error.value), error.value


def test_the_kick_comes_when_the_top_block_lands_as_a_block_alone_on_a_fixed_base():
    """stack-kick: until its landing the top block rocks on a bottom block at rest, i.e. as
    one block on a fixed base; the single-block engine (its own code, reference method)
    gives that landing time, and the bottom block starts moving there."""
    from dataclasses import replace

    import shaketable as st

    scene = load_scene(resolve_scene_path("stack-kick"))
    result = run_stack_scene(replace(scene, duration=0.3))   # the kick only (0.265 s)
    first = result.run.events[0]
    assert first["kind"] == "impact" and first["interface"] == 1
    top = scene.stack.blocks[1]
    alone = st.simulate(top, None, cor=0.9, theta0=0.1, duration=0.3, method="reference")
    assert first["t"] == pytest.approx(alone.impact_times[0], abs=1e-9)   # 0.2648 s
    assert first["pattern_after"][0] != 0                      # the bottom block kicked
    lines = "\n".join(result.lines())
    assert "at rest until t = 0.265 s (impact)" in lines
    # the uplift line agrees: the landing lifted the bottom block (no "none")
    assert "block 0 (bottom) lifted by the impact at t = 0.265 s" in lines
    assert "uplift: none" not in lines


@pytest.mark.usefixtures("figure_drafts")
def test_a_scene_with_mu_writes_the_friction_keys_simulate_writes(tmp_path):
    # `simulate --stack --mu` writes "mu [-]" and "t_friction_exceeded(mu) [s]"; a scene
    # with stack.mu must write the same keys, the time tested against the scene's own mu
    import json

    scene = load_scene(_write(tmp_path, GOOD))
    result = run_stack_scene(scene)
    result.write(tmp_path / "out")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["mu [-]"] == 0.5
    expected = result.run.t_friction_exceeded(0.5)
    got = summary["t_friction_exceeded(mu) [s]"]
    assert (got is None and math.isnan(expected)) or got == expected


def test_a_misspelt_section_is_refused_with_its_line(tmp_path):
    # "[motoin]" for "[motion]": the refusal names the file, the key and the line it is on
    text = GOOD.replace("[motion]", "[motoin]")
    line = text.splitlines().index("[motoin]") + 1
    with pytest.raises(SceneError, match=rf"unknown key 'motoin' in \[top level.*\(line {line}\)"):
        load_scene(_write(tmp_path, text))


OFFSET = GOOD.replace('"30x6in", "30x6in"', '"30x6in", "20x2in"').replace(
    'masses = ["100 kg", "50 kg"]', 'masses = ["100 kg", "50 kg"]\noffsets = ["1.5 in"]')


def test_offsets_in_a_stack_scene_are_lengths_with_units(tmp_path):
    # 1.5 in = 0.0381 m (1 in = 0.0254 m exactly); the top block (2 in wide) may sit up to
    # 3 - 1 = 2 in off the bottom one's (6 in wide) centre
    scene = load_scene(_write(tmp_path, OFFSET))
    assert scene.stack.offsets == (1.5 * 0.0254,)
    for new, message in (('["-2.5 in"]', "stack.offsets: block 1 (top) (20 x 2 in) offset "
                                         "-2.50 in would overhang block 0 (bottom) (30 x 6 in): "
                                         "its offset may be at most 2.00 in either way"),
                         ('["1 in", "1 in"]', "stack.offsets: 2 value(s) for 2 block(s); give 1"),
                         ('["1.5"]', "stack.offsets: block 1 (top)")):
        path = _write(tmp_path, OFFSET.replace('["1.5 in"]', new))
        with pytest.raises(SceneError) as error:
            load_scene(path)
        assert str(error.value).startswith(str(path)) and message in str(error.value), \
            error.value
