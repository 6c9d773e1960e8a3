"""Every command leads with the engineer's answer, in the user's own units: verdict, max
θ/α, overturn time, peak slip, corner excursion (clearance) and when the block came
to rest; time spent in each mode comes last.
"""

from __future__ import annotations

import math

import pytest

from shaketable.cli import main
from shaketable.core.geometry import Block
from shaketable.core.units import format_length


def test_lengths_are_written_in_the_users_unit():
    # 0.2248 m for a block given in metres: mm below one metre, m above
    assert format_length(0.2248, "m") == "225 mm"
    assert format_length(2.47, "m") == "2.47 m"
    assert format_length(0.2248, "in") == "8.85 in"          # 0.2248 / 0.0254
    assert format_length(0.2248, "ft") == "8.85 in"          # under a foot: inches
    assert format_length(-0.0216, "m", signed=True) == "-21.6 mm"
    assert format_length(math.nan, "m") == "n/a"
    assert Block.parse("2x0.5m").length_unit == "m"
    assert Block.parse("4x0.8ft").length_unit == "ft"
    with pytest.raises(ValueError, match="unit must be one of"):
        format_length(1.0, "furlong")


@pytest.mark.usefixtures("figure_drafts")
def test_simulate_friction_leads_with_the_answer_in_metres(tmp_path, capsys):
    # free rocking of a 2 x 0.5 m block from 0.5 alpha on a base that does not slide (mu 1)
    block = Block.parse("2x0.5m")
    theta0 = 0.5 * block.alpha
    assert main(["simulate", "--block", "2x0.5m", "--theta0", "0.5alpha", "--cor", "0.9",
                 "--friction", "1.0", "--duration", "12s", "--out", str(tmp_path / "f")]) == 0
    planar = capsys.readouterr().out.splitlines()
    assert main(["simulate", "--block", "2x0.5m", "--theta0", "0.5alpha", "--cor", "0.9",
                 "--duration", "12s", "--out", str(tmp_path / "r")]) == 0
    rocking = capsys.readouterr().out.splitlines()
    import json

    # the rocking engine (the report's model, another solver) gives the rest time
    rest = json.loads((tmp_path / "r" / "summary.json").read_text())["t_rest [s]"]
    assert planar[0] == "2 x 0.5 m block, COR 0.9: rocked"
    # the console's one notation, θ/α; the peak is the release itself
    assert planar[1] == "  max θ/α 0.5 at the release (t = 0.00 s); did not overturn"
    # mu 1 > B/H: the corner it rocks on never slides (the midpoint moves with the rocking)
    assert planar[2] == "  peak slip 0: the base never slid"
    # the far top corner at the release: B (1 - cos theta0) + H sin theta0 from rest
    excursion = block.width * (1 - math.cos(theta0)) + block.height * math.sin(theta0)
    assert planar[3] == (f"  corner excursion (the clearance it needs) "
                         f"{excursion * 1000:.3g} mm")
    assert planar[4] == f"  came to rest at t = {rest:.2f} s"
    assert planar[5].startswith("  time in each mode: rest ")
    assert " in" not in "\n".join(planar[:6]).replace(" in each", "")
    # free rocking: when it came to rest first, the impacts, the max said as the release
    assert rocking[1] == f"  came to rest at t = {rest:.2f} s"
    assert rocking[2].endswith(" impacts") or " summed cascade" in rocking[2]
    assert rocking[3] == "  max θ/α 0.5 at the release (t = 0.00 s); did not overturn"


def test_a_block_that_only_slid_did_not_rock():
    # a squat 0.5 m high, 2 m wide block (B/H = 4) on mu 0.1 under 2 Hz 0.3 g: Section 2.1's
    # rule (it slides when mu < B/H) says it slides and cannot rock
    import shaketable as st
    from shaketable.commands.answers import planar_answer
    from shaketable.ground import generators

    block = Block.parse("0.5x2m")
    motion = generators.harmonic(2.0, horizontal=0.3 * st.G, duration=1.0)
    result = st.simulate(block, motion, cor=0.9, friction=st.Friction(0.1))
    assert result.peak_base_slip > 0.0
    assert planar_answer(result)[0] == "max θ/α 0: did not rock; did not overturn"


def test_sweeps_label_blocks_in_the_users_units(tmp_path):
    from shaketable import sweeps

    def blocks(table):
        spec = sweeps.spec_from_dict(
            {"name": "u", "blocks": table, "rocking": {"cor": 0.9, "duration": "1 s"},
             "records": [{"name": "el-centro-chopra"}],
             "intensity": {"measure": "pga", "levels": ["0.1 g"]}}, directory=tmp_path)
        return spec, [block.describe() for block in spec.blocks]

    assert blocks({"sizes": ["2x0.5m", "16x4ft"]})[1] == ["2 x 0.5 m", "16 x 4 ft"]
    assert blocks({"height": ["2 m"], "width": ["0.5 m", "0.25 m"]})[1] == [
        "2 x 0.5 m", "2 x 0.25 m"]
    assert blocks({"height": ["4 ft"], "aspect": [4.0]})[1] == ["4 x 1 ft"]
    spec, _ = blocks({"sizes": ["2x0.5m"]})
    table = sweeps.run_sweep(spec, tmp_path / "out", workers=1, progress=False).table
    assert list(table["block"]) == ["2 x 0.5 m"]


@pytest.mark.parametrize("command", [
    ["simulate", "--cor", "0.9", "--duration", "1s"],
    ["animate", "--cor", "0.9", "--duration", "1s", "--out", "a.gif"],
    ["slide", "--record", "el-centro-chopra"],
    ["spectrum"],
    ["modemap", "--cor", "0.9", "--record", "el-centro-chopra"],
])
@pytest.mark.parametrize("size, reason", [
    ("0x6in", "the height must be positive"),
    ("30x0in", "the width must be positive"),
    ("-30x6in", "the height and the width must be positive"),
])
def test_a_zero_or_negative_block_size_is_named_by_its_option(tmp_path, capsys, monkeypatch,
                                                               command, size, reason):
    monkeypatch.chdir(tmp_path)
    extra = [] if "--out" in command else ["--out", "out"]
    assert main(command[:1] + [f"--block={size}"] + command[1:] + extra) == 2
    assert f"error: --block {size}: {reason}\n" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())    # checked before any output is made


@pytest.mark.parametrize("command", [
    ["simulate", "--block", "30x6in", "--duration", "1s", "--out", "out"],
    ["animate", "--block", "30x6in", "--duration", "1s", "--out", "a.gif"],
    ["spectrum", "--block", "30x6in", "--out", "out"],
    ["modemap", "--block", "30x6in", "--record", "el-centro-chopra", "--out", "out"],
])
@pytest.mark.parametrize("cor", ["2", "-0.1"])
def test_an_out_of_range_cor_is_named_by_its_option(tmp_path, capsys, monkeypatch, command,
                                                    cor):
    monkeypatch.chdir(tmp_path)
    assert main(command + [f"--cor={cor}"]) == 2
    err = capsys.readouterr().err
    assert "error: --cor must be" in err and "[0" in err
    assert not any(tmp_path.iterdir())


def test_a_scene_names_the_block_size_its_line_and_the_cor_key(tmp_path, capsys):
    scene = tmp_path / "s.toml"
    scene.write_text('name = "s"\n[block]\nsize = "0x6in"\n[motion]\nkind = "free"\n'
                     '[rocking]\ncor = 0.9\ntheta0 = "0.5 alpha"\nduration = "1 s"\n')
    assert main(["run", str(scene), "--out", str(tmp_path / "o")]) == 2
    assert "block.size '0x6in': the height must be positive (line 3)" in capsys.readouterr().err
    scene.write_text(scene.read_text().replace('"0x6in"', '"30x6in"').replace("0.9", "2"))
    assert main(["run", str(scene), "--out", str(tmp_path / "o")]) == 2
    assert "rocking.cor must be a number in [0, 1]" in capsys.readouterr().err
