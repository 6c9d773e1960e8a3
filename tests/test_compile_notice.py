"""The one-line notice before a first compile names what will compile.

The planar engine costs ~13 s of CPU to compile and the stack engine ~28 s (measured,
`commands/common.py`), five and twelve times the rocking engine: a command that will run
one must say so before the wait.
"""

from shaketable.commands import common
from shaketable.scenes.catalog import scene_names, uses_planar, uses_stack


def test_the_scenes_that_run_the_planar_block_are_found_from_their_toml():
    uses = {name for name in scene_names() if uses_planar(name)}
    # block.static_friction (teaching-slide-or-rock), a mode-map study, Table 4.4's section
    assert {"teaching-slide-or-rock", "mode-map-pacoima", "table-4-4"} <= uses
    assert "fig-3-7" not in uses and "table-4-1" not in uses


def test_the_scenes_that_run_the_stack_model_are_found_from_their_toml():
    # the stack engine is the costliest first compile: the [stack] scenes and the stacks
    # study must name it before the wait
    uses = {name for name in scene_names() if uses_stack(name)}
    assert {"stack-kick", "stack-step", "stacks"} <= uses
    assert "fig-3-7" not in uses and "teaching-slide-or-rock" not in uses


def test_three_engines_are_named_in_one_sentence(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    common.notice_first_compile(which=("engine", "planar", "stack"))
    message = capsys.readouterr().err
    assert "the engine (~3 s), the planar engine (" in message
    assert " and the stack engine (" in message and "load them from the cache" in message


def test_run_names_the_stack_engine_for_a_stack_scene(tmp_path, monkeypatch):
    # which engines `run` announces, the scene's run itself replaced (not what is tested)
    from shaketable.cli import main
    from shaketable.commands import run as run_command

    announced = []
    monkeypatch.setattr(common, "notice_first_compile",
                        lambda quiet=False, which=("engine",): announced.append(which))
    monkeypatch.setattr(run_command, "_run_stack", lambda scene, out, args: 0)
    assert main(["run", "stack-kick", "--out", str(tmp_path / "out")]) == 0
    assert announced == [("stack",)]


def test_an_empty_cache_names_each_engine_that_will_compile(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    common.notice_first_compile(which=("engine", "planar"))
    message = capsys.readouterr().err
    assert "the engine (~3 s)" in message and "the planar engine (~13 s)" in message
    common.notice_first_compile(quiet=True, which=("planar",))
    assert capsys.readouterr().err == ""


def test_a_compiled_engine_is_found_in_the_cache(tmp_path, monkeypatch):
    import hashlib
    import sys

    # the package's cache locator names the folder from its path inside the package
    cache = tmp_path / f"planar_{hashlib.sha1(b'shaketable/models/planar').hexdigest()}"
    cache.mkdir()
    tag = f"py{sys.version_info.major}{sys.version_info.minor}"
    (cache / f"engine.integrate-191.{tag}.nbi").write_bytes(b"")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert common.compiled_before("planar")
    assert not common.compiled_before("engine")
