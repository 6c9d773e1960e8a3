"""Inputs parsed once: a scene file is read once by ``run``; scenes and sweep specs share
one block-and-rod parser, one unknown-key check and one error-line finder."""

from __future__ import annotations

import argparse
import builtins
import io
from pathlib import Path

import pytest

from shaketable.scenes.parse import SceneError, load_scene, scene_from_dict
from shaketable.sweeps.base import SweepError
from shaketable.sweeps.spec import load_spec, spec_from_dict

SCENE = """name = "once"
[block]
size = "30x6in"
static_friction = 0.6
[motion]
kind = "free"
[rocking]
cor = 0.925
theta0 = "0.2 alpha"
duration = "1 s"
"""

SPEC = {"name": "rods", "blocks": {"sizes": ["30x6in"]}, "rocking": {"cor": 0.9},
        "records": [{"preset": "A-1"}]}


class _Stop(Exception):
    """Raised in place of running the scene: what was read before is counted."""


def test_run_reads_the_scene_file_once(tmp_path, monkeypatch):
    """``shaketable run`` asks whether the file is a sweep spec and whether it runs the
    planar engine, and parses it: from one reading of the file."""
    import shaketable.scenes.run as pipeline
    from shaketable.commands.run import _run

    path = tmp_path / "once.toml"
    path.write_text(SCENE)
    opened = []
    real_open, real_io_open = builtins.open, io.open

    def counting(opener):
        def open_(file, *args, **kwargs):
            if isinstance(file, (str, Path)) and Path(file).name == path.name:
                opened.append(file)
            return opener(file, *args, **kwargs)
        return open_

    monkeypatch.setattr(builtins, "open", counting(real_open))
    monkeypatch.setattr(io, "open", counting(real_io_open))
    seen = []

    def stop(scene):
        seen.append(scene)
        raise _Stop

    monkeypatch.setattr(pipeline, "run_scene", stop)
    args = argparse.Namespace(scene=str(path), out=str(tmp_path / "out"), quiet=True,
                              parquet=False, svg=False)
    with pytest.raises(_Stop):
        _run(args)
    assert len(opened) == 1
    assert seen[0].name == "once" and seen[0].static_friction == 0.6


@pytest.mark.parametrize("rods, key", [
    ({"stiffness": "0.4 W/in", "force": "0.4 W"}, "needs edge_distance"),
    ({"stiffness": "0.4 W/in", "force": "0.4 W", "edge_distance": "12 in", "grade": 8},
     "unknown key 'grade' in [{section}]; expected one of edge_distance, force, stiffness"),
    ({"stiffness": "0.4", "force": "0.4 W", "edge_distance": "12 in"},
     ".stiffness: '0.4' has no unit"),
    ({"stiffness": "0.4 W/in", "force": "0.4 W", "edge_distance": "12 in"},
     ": PrestressRods.edge_distance"),
])
def test_scene_and_sweep_rods_give_one_message(tmp_path, rods, key):
    """One parser: the same rods give the same message, naming ``block.rods`` in a scene
    and ``blocks.rods`` in a sweep spec (a 12 in edge distance on a 6 in wide block)."""
    data = {"name": "rods", "block": {"size": "30x6in", "rods": rods},
            "motion": {"kind": "free"}, "rocking": {"cor": 0.9, "duration": "1 s"}}
    with pytest.raises(SceneError) as scene:
        scene_from_dict(data, where="scene.toml")
    with pytest.raises(SweepError) as sweep:
        spec_from_dict(dict(SPEC, blocks={"sizes": ["30x6in"], "rods": rods}),
                       where="spec.toml")
    scene_text = str(scene.value).replace("scene.toml: ", "")
    sweep_text = str(sweep.value).replace("spec.toml: ", "")
    assert scene_text.replace("block.rods", "blocks.rods").replace(
        "block.size:", "blocks.sizes:") == sweep_text
    assert key.format(section="block.rods") in scene_text
    assert key.format(section="blocks.rods") in sweep_text


def test_sizes_unknown_keys_and_lines_are_said_alike(tmp_path):
    """A bad size names its key the same way; the error-line finder of the scenes gives the
    sweep spec's ``[stacks]`` and ``[friction]`` keys their line."""
    with pytest.raises(SceneError, match=r"^scene.toml: block.size '0x6in': the height"):
        scene_from_dict({"name": "s", "block": {"size": "0x6in"}, "motion": {"kind": "free"},
                         "rocking": {"cor": 0.9, "duration": "1 s"}}, where="scene.toml")
    with pytest.raises(SweepError, match=r"^spec.toml: blocks.sizes '0x6in': the height"):
        spec_from_dict(dict(SPEC, blocks={"sizes": ["0x6in"]}), where="spec.toml")
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE.replace('theta0 = "0.2 alpha"', 'theta0 = "0.2 alpha"\ncolour = 1'))
    with pytest.raises(SceneError, match=r"unknown key 'colour' in \[rocking\]; .* \(line 10\)$"):
        load_scene(scene)
    spec = tmp_path / "spec.toml"
    spec.write_text('name = "s"\n[stacks]\nsizes = ["30x6in"]\nblocks = 0\n'
                    '[[records]]\npreset = "A-1"\n')
    with pytest.raises(SweepError, match=r"stacks.blocks must be a positive integer, got 0 "
                                         r"\(line 4\)$"):
        load_spec(spec)
    spec.write_text('name = "s"\n[blocks]\nsizes = ["30x6in"]\n[rocking]\ncor = 0.9\n'
                    '[friction]\nstatic = "0.3"\n[[records]]\npreset = "A-1"\n')
    with pytest.raises(SweepError, match=r"friction.static .* \(line 7\)$"):
        load_spec(spec)
