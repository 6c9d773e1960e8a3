"""``scenes.catalog.study_kind``: a scene file's ``[study] kind`` without parsing the scene
(what ``reproduce`` schedules by)."""

from __future__ import annotations

import pytest

from shaketable.scenes.catalog import study_kind
from shaketable.scenes.parse import SceneError


def test_kinds_of_bundled_scenes():
    # experiments/table-4-1.toml: [study] kind = "report-table"; fig-4-1 is a single scene
    assert study_kind("table-4-1") == "report-table"
    assert study_kind("mode-map-pacoima") == "mode-map"
    assert study_kind("fig-4-1") is None


def test_a_file_that_is_not_toml_names_itself(tmp_path):
    bad = tmp_path / "broken.toml"
    bad.write_text("[study\nkind = 1\n")
    with pytest.raises(SceneError, match="broken.toml"):
        study_kind(str(bad))


def test_an_unknown_name_is_a_scene_error():
    with pytest.raises(SceneError, match="no scene"):
        study_kind("no-such-scene")
