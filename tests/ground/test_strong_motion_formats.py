"""Strong-motion formats through gmprocess (optional extra ``formats``).

The sample is a file gmprocess itself ships in its wheel
(``gmprocess/data/demo/ci38457511/raw/CICLC.v1``: CSMIP/DMG V1, 2019
Ridgecrest, station CI.CLC, three channels, header ``Max = .344 g`` for
channel 1). Expected peaks are gmprocess's own reading of the file (and the
file's header) -- never values produced by shaketable.
"""

from __future__ import annotations

import builtins
from pathlib import Path

import numpy as np
import pytest

from shaketable.core.constants import G
from shaketable.ground.readers import strong_motion


def _gmprocess_sample():
    gmprocess = pytest.importorskip(
        "gmprocess", reason="optional extra 'formats' (gmprocess) is not installed")
    path = Path(gmprocess.__file__).parent / "data" / "demo" / "ci38457511" / "raw" / "CICLC.v1"
    if not path.is_file():
        pytest.skip(f"gmprocess does not ship {path.name} in this version")
    return path


def test_csmip_v1_reads_to_gmprocess_peak_and_the_header_max():
    path = _gmprocess_sample()
    from gmprocess.io.read import read_data

    traces = [trace for stream in read_data(str(path)) for trace in stream]
    for trace in traces:
        assert trace.stats.standard.units == "cm/s^2"
        expected = np.max(np.abs(trace.data)) * 0.01  # gmprocess gives cm/s^2
        record = strong_motion.read_strong_motion(path, component=trace.stats.channel)
        assert record.pga == pytest.approx(expected, rel=1e-12)
        assert record.metadata["format"] == "DMG"
    # the text header of channel 1 (90 deg): "Max = .344 g"
    first = strong_motion.read_strong_motion(path, component=0)
    assert round(first.pga / G, 3) == 0.344


def test_load_strong_motion_builds_a_motion_with_metadata():
    path = _gmprocess_sample()
    motion = strong_motion.load_strong_motion(path, horizontal=0, vertical="Z")
    assert motion.metadata["horizontal"]["station"] == "CLC"
    assert motion.metadata["vertical"]["channel"] == "HNZ"
    assert motion.metadata["vertical_positive"] == "up"


def test_without_the_extra_the_message_names_it(monkeypatch, tmp_path):
    real_import = builtins.__import__

    def no_gmprocess(name, *args, **kwargs):
        if name == "gmprocess" or name.startswith("gmprocess."):
            raise ModuleNotFoundError(f"No module named {name!r}")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_gmprocess)
    with pytest.raises(strong_motion.MissingExtraError, match=r"shaketable\[formats\]"):
        strong_motion.read_strong_motion(tmp_path / "record.V2")
    with pytest.raises(ImportError, match="formats"):
        strong_motion.load_strong_motion(tmp_path / "record.V2")
