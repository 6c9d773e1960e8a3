"""The stack's animation: each block drawn where the chain of pivots puts it (checked on a
rigidly tilted column against the closed-form corners), written frame by frame, and the
``animate`` command's stack paths."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from shaketable.core.geometry import Block
from shaketable.models.stack import Stack
from shaketable.plots.stack_animation import stack_outlines
from tests.test_bad_input import run_cli


@pytest.mark.parametrize("theta, pattern", [(0.07, (1, 0)), (-0.05, (-1, 0))])
def test_a_column_tilted_as_one_body_turns_about_its_base_corner(theta, pattern):
    b, h = 0.1, 0.5                                   # two 1 x 0.2 m blocks
    stack = Stack((Block(2 * h, 2 * b), Block(2 * h, 2 * b)))
    result = SimpleNamespace(stack=stack, theta=np.array([[theta, theta]]),
                             theta_dot=np.zeros((1, 2)), patterns=np.array([pattern]))
    outlines = stack_outlines(result, [0])[0]
    side = -1.0 if theta > 0 else 1.0                 # the pivot: the -x corner for theta > 0
    pivot = np.array([side * b, 0.0])

    def turned(x, y):                                 # a point of the upright column, turned
        dx, dy = x - pivot[0], y - pivot[1]
        return pivot + [dx * math.cos(theta) - dy * math.sin(theta),
                        dx * math.sin(theta) + dy * math.cos(theta)]

    upright = {0: [(-b, 0), (b, 0), (b, 2 * h), (-b, 2 * h)],
               1: [(-b, 2 * h), (b, 2 * h), (b, 4 * h), (-b, 4 * h)]}
    for block, corners in upright.items():
        expected = np.array([turned(x, y) for x, y in corners])
        assert outlines[block, :4] == pytest.approx(expected, abs=1e-14)


def test_animate_writes_a_stack_scene_and_refuses_what_it_would_ignore(tmp_path):
    status, out, err = run_cli(["animate", "stack-kick", "--end", "0.2s", "--fps", "5",
                                "--size", "320x180", "--out", tmp_path / "kick.gif"],
                               cwd=tmp_path)
    assert status == 0, err
    assert "wrote" in out and "(2 frames of 320 x 180 pixels" in out
    from PIL import Image

    with Image.open(tmp_path / "kick.gif") as image:
        assert image.n_frames == 2
    status, _, err = run_cli(["animate", "stack-kick", "--run", "1", "--out",
                              tmp_path / "k.gif"], cwd=tmp_path)
    assert status == 2 and "--run '1' cannot be used with a stack scene" in err
    status, _, err = run_cli(["animate", "--stack", "30x6in,30x8in", "--duration", "1s",
                              "--out", tmp_path / "s.gif"], cwd=tmp_path)
    assert status == 2 and "block 1 (top) (30 x 8 in) is wider than block 0" in err


def test_animate_stack_takes_the_masses_and_densities_simulate_takes(tmp_path, monkeypatch):
    import shaketable.scenes.stack as stack_scenes

    given = []

    def stop(stack, motion, **options):   # the run is simulate's; only its input is checked
        given.append(stack)
        raise ValueError("stopped before the run")

    monkeypatch.setattr(stack_scenes, "run_quietly", stop)
    base = ["animate", "--stack", "8x4ft,6x4ft", "--theta0", "0.1alpha", "--duration", "1s",
            "--out", tmp_path / "s.gif"]
    status, _, err = run_cli(base + ["--masses", "6.5t,4.9t"], cwd=tmp_path)
    assert status == 2 and "stopped before the run" in err
    assert given[-1].masses == (6500.0, 4900.0)
    status, _, err = run_cli(base + ["--densities", "2400kg/m3,7800kg/m3"], cwd=tmp_path)
    assert status == 2 and "stopped before the run" in err
    foot = 0.3048                                     # density x B x H over 1 m of depth
    assert given[-1].masses == pytest.approx((2400 * 32 * foot ** 2, 7800 * 24 * foot ** 2),
                                             rel=1e-12)
    status, _, err = run_cli(base + ["--masses", "6.5t"], cwd=tmp_path)
    assert status == 2 and "--masses: 1 value(s) for 2 block(s)" in err
    status, _, err = run_cli(["animate", "--block", "30x6in", "--cor", "0.9", "--masses",
                              "1t", "--out", tmp_path / "b.gif"], cwd=tmp_path)
    assert status == 2 and "--masses is for a column of blocks: give --stack" in err
    status, _, err = run_cli(["animate", "stack-kick", "--masses", "1t,1t,1t", "--out",
                              tmp_path / "k.gif"], cwd=tmp_path)
    assert status == 2 and "not both (got the scene 'stack-kick' and --masses)" in err
