"""The one TOML reader of the input files (data and text, errors naming file and line,
the line of a dotted key) and the one unknown-key check."""

from __future__ import annotations

import pytest

from shaketable.core.tomlfile import key_line, read_toml
from shaketable.core.validation import unknown_keys

TEXT = """name = "demo"          # line 1

[block]                  # line 3
size = "16x4ft"
rods = { stiffness = 1 } # line 5

[[records]]              # line 7
name = "pacoima-dam-s16e"
rocking.cor = 0.9        # line 9
"""


@pytest.mark.parametrize("path, line", [
    (["name"], 1),
    (["block"], 3),
    (["block", "size"], 4),
    (["block", "rods", "stiffness"], 5),     # inside an inline table: the table's line
    (["block", "colour"], 3),                # not written: its section's line
    (["records", "rocking", "cor"], 9),      # a dotted key under an array of tables
    (["motion", "kind"], None),              # nothing of it written
])
def test_key_line_finds_the_key_or_its_longest_written_prefix(path, line):
    # the line numbers are those marked in TEXT's comments
    assert key_line(TEXT, path) == line


def test_read_toml_returns_the_data_and_the_text(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(TEXT, encoding="utf-8")
    data, text = read_toml(path, "scene")
    assert text == TEXT
    assert data["block"]["rods"] == {"stiffness": 1}
    assert data["records"][0]["rocking"] == {"cor": 0.9}


class CustomError(ValueError):
    pass


def test_read_toml_errors_name_the_file_and_use_the_callers_class(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "x"\n[block\n', encoding="utf-8")
    with pytest.raises(CustomError, match=r"bad\.toml: not valid TOML: .*line 2"):
        read_toml(bad, "scene", CustomError)
    deep = tmp_path / "deep.toml"
    deep.write_text("a = " + "[" * 5000 + "]" * 5000 + "\n", encoding="utf-8")
    with pytest.raises(CustomError, match=r"deep\.toml: arrays or tables nested too deeply "
                                          r"to read \(an object file needs a few levels\)"):
        read_toml(deep, "object file", CustomError)
    with pytest.raises(CustomError, match=r"missing\.toml: cannot read the sweep spec"):
        read_toml(tmp_path / "missing.toml", "sweep spec", CustomError)


def test_unknown_keys_are_sorted_so_the_first_named_is_always_the_same():
    assert unknown_keys({"cor": 1, "zeta": 2, "alpha": 3}, {"cor"}) == ["alpha", "zeta"]
    assert unknown_keys({"cor": 1}, ("cor", "rtol")) == []
