"""Strong-motion formats through gmprocess (optional extra ``formats``).

The samples come from gmprocess itself (gmprocess 2.8.0 ships no COSMOS file in
its wheel or sdist; its test data live only in its git repository):

* ``gmprocess/data/demo/ci38457511/raw/CICLC.v1``, shipped in the wheel: CSMIP/DMG
  V1, 2019 Ridgecrest, station CI.CLC, three channels, header ``Max = .344 g``
  for channel 1;
* COSMOS V2 files (``*.acc.V2c``) that gmprocess's own COSMOS writer
  (``gmprocess.io.cosmos.cosmos_writer.CosmosWriter``, ``Volume.PROCESSED``)
  makes from the processed workspace gmprocess ships
  (``gmprocess/data/demo/nc72282711/workspace.h5``: 2014 South Napa, station
  CE.68150 Napa College).

Expected peaks are gmprocess's own reading of each file (and the file's
``Max =`` header line) -- never values produced by shaketable.
"""

from __future__ import annotations

import builtins
import re
import sys
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


def test_without_the_extra_even_when_gmprocess_was_imported_the_message_names_it(
        monkeypatch, tmp_path):
    """``None`` in ``sys.modules`` makes every gmprocess import fail (installed or not,
    imported before or not): the reader raises MissingExtraError naming the extra."""
    for name in [name for name in sys.modules if name.split(".")[0] == "gmprocess"]:
        monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.setitem(sys.modules, "gmprocess", None)
    monkeypatch.setitem(sys.modules, "gmprocess.io", None)
    monkeypatch.setitem(sys.modules, "gmprocess.io.read", None)
    with pytest.raises(strong_motion.MissingExtraError) as raised:
        strong_motion.read_strong_motion_stream(tmp_path / "record.V2")
    message = str(raised.value)
    assert 'pip install "shaketable[formats]"' in message
    assert "COSMOS" in message


def _cosmos_v2_files(folder: Path) -> list[Path]:
    """COSMOS V2 acceleration files written by gmprocess's own writer from its demo workspace."""
    gmprocess = pytest.importorskip(
        "gmprocess", reason="optional extra 'formats' (gmprocess) is not installed")
    workspace = Path(gmprocess.__file__).parent / "data" / "demo" / "nc72282711" / "workspace.h5"
    if not workspace.is_file():
        pytest.skip(f"gmprocess does not ship {workspace.name} in this version")
    from gmprocess.io.cosmos.cosmos_writer import CosmosWriter, Volume

    CosmosWriter(folder, workspace, volume=Volume.PROCESSED, concatenate_channels=False).write()
    files = sorted(folder.glob("*.acc.V2*"))
    assert files, f"gmprocess wrote no COSMOS V2 acceleration file into {folder}"
    return files


def test_cosmos_v2_reads_to_gmprocess_peak_and_the_header_max(tmp_path):
    """Each COSMOS V2 acceleration file reads to the peak gmprocess's reader gives
    (cm/s^2 -> m/s^2) and to the ``Processed: Max = ... cm/s^2`` line of its header."""
    files = _cosmos_v2_files(tmp_path)
    from gmprocess.io.read import read_data

    for path in files:
        (trace,) = [trace for stream in read_data(str(path)) for trace in stream]
        assert trace.stats.standard.process_level == "corrected physical units"
        assert trace.stats.standard.units in ("cm/s/s", "cm/s^2")
        expected = float(np.max(np.abs(trace.data))) * 0.01
        record = strong_motion.read_strong_motion(path)
        assert record.pga == pytest.approx(expected, rel=1e-12)
        assert record.metadata["format"] == "COSMOS"
        assert record.dt == pytest.approx(trace.stats.delta, rel=1e-12)
        header = path.read_text(encoding="ascii", errors="replace")
        stated = float(re.search(r"Max\s*=\s*([-+.\d]+)\s*cm/s\^2", header)[1])
        assert record.pga == pytest.approx(stated * 0.01, abs=0.5e-3 * 0.01)

