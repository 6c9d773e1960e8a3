"""``inventory=``: instrument responses from station metadata instead of ObsPy's
deprecated ``stream.attach_response``.

Data: files ObsPy itself ships. ObsPy ships no station metadata for its one
accelerometer waveform (``io/ascii/tests/data/miniseed_record.mseed``, CI.AGO..HNZ,
counts), and no waveform for its accelerometer inventories, so the tests relabel
that trace with the codes of an accelerometer channel of each inventory (a
StationXML, a dataless SEED and a RESP file, all with input units M/S**2).

Reference values: always ObsPy's own ``Trace.remove_sensitivity(inventory)`` (the
counts divided by the overall sensitivity that ObsPy finds in the inventory),
checked against ``trace.data / inventory.get_response(...).instrument_sensitivity.value``
written out -- never a value computed by shaketable.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

obspy = pytest.importorskip("obspy")

from shaketable.core.motion import Motion  # noqa: E402
from shaketable.ground import records  # noqa: E402
from shaketable.ground.readers import waveform  # noqa: E402
from shaketable.ground.readers.common import RecordError  # noqa: E402

OBSPY = Path(obspy.__file__).parent
ACCELEROGRAM = OBSPY / "io" / "ascii" / "tests" / "data" / "miniseed_record.mseed"
STATIONXML = OBSPY / "core" / "tests" / "data" / "Modified_IRIS_response_level_station.xml"
DATALESS = OBSPY / "io" / "xseed" / "tests" / "data" / "bug165.dataless"
RESP = OBSPY / "io" / "xseed" / "tests" / "data" / "RESP.JM.NMIA0.00.HHN"
KNET = OBSPY / "io" / "nied" / "tests" / "data" / "test.knet"

#: (inventory file, network, station, location, channel): accelerometer channels
#: (input units M/S**2) whose epochs cover the trace's start, 2016-06-20.
ACCELEROMETERS = [(STATIONXML, "IU", "ANMO", "20", "HNZ"),
                  (DATALESS, "NZ", "DCZ", "20", "HNZ"),
                  (RESP, "JM", "NMIA0", "00", "HNN")]


def _counts(network: str, station: str, location: str, channel: str) -> obspy.Trace:
    """ObsPy's accelerometer counts (CI.AGO..HNZ) relabelled with other codes."""
    trace = obspy.read(str(ACCELEROGRAM))[0]
    trace.stats.network, trace.stats.station = network, station
    trace.stats.location, trace.stats.channel = location, channel
    return trace


def _obspy_acceleration(trace: obspy.Trace, inventory) -> np.ndarray:
    """ObsPy's own sensitivity removal [m/s^2], checked against the division by hand."""
    corrected = trace.copy()
    corrected.remove_sensitivity(inventory)
    sensitivity = inventory.get_response(trace.id, trace.stats.starttime) \
        .instrument_sensitivity.value
    np.testing.assert_allclose(corrected.data, trace.data / sensitivity, rtol=1e-12)
    return corrected.data


@pytest.mark.parametrize("path, network, station, location, channel", ACCELEROMETERS,
                         ids=["stationxml", "dataless", "resp"])
def test_an_accelerometer_inventory_gives_obspys_acceleration(path, network, station,
                                                              location, channel):
    trace = _counts(network, station, location, channel)
    inventory = obspy.read_inventory(str(path))
    expected = _obspy_acceleration(trace, inventory)
    assert trace.stats.calib == 1.0 and np.max(np.abs(trace.data)) == 25333  # raw counts
    for given in (inventory, path, str(path)):  # an Inventory, a Path, a str
        record = records.read(trace, inventory=given)  # no units=: the response's M/S**2
        np.testing.assert_allclose(record.acceleration, expected, rtol=1e-12, atol=0)
        assert record.units_in_file == "m/s2"
    assert record.metadata["sensitivity"] == \
        inventory.get_response(trace.id, trace.stats.starttime).instrument_sensitivity.value
    assert "inventory file" in record.metadata["units_source"]
    assert np.max(np.abs(trace.data)) == 25333  # the trace is not changed


def test_a_waveform_file_and_its_stationxml_read_by_path(tmp_path):
    """records.read(path, inventory=path): the everyday use, both as files."""
    trace = _counts("IU", "ANMO", "20", "HNZ")
    waveform_file = tmp_path / "IU.ANMO.20.HNZ.mseed"
    trace.write(str(waveform_file), format="MSEED")
    expected = _obspy_acceleration(trace, obspy.read_inventory(str(STATIONXML)))
    for read in (records.read, waveform.read_obspy):
        record = read(waveform_file, inventory=STATIONXML)
        assert record.pga == pytest.approx(np.max(np.abs(expected)), rel=1e-12)
    # a file of unknown extension is offered to ObsPy, and inventory= is an ObsPy option
    other = tmp_path / "record.bin"
    other.write_bytes(waveform_file.read_bytes())
    assert records.read(other, inventory=STATIONXML).pga == pytest.approx(
        np.max(np.abs(expected)), rel=1e-12)


def test_motion_from_stream_applies_each_traces_response():
    inventory = obspy.read_inventory(str(STATIONXML))
    vertical = _counts("IU", "ANMO", "20", "HNZ")
    horizontal = _counts("IU", "ANMO", "20", "HN1")
    horizontal.data = -horizontal.data[::-1].copy()  # a different record on the other channel
    stream = obspy.Stream([horizontal, vertical])
    motion = Motion.from_stream(stream, horizontal="HN1", vertical="HNZ", inventory=inventory)
    np.testing.assert_allclose(motion.horizontal, _obspy_acceleration(horizontal, inventory),
                               rtol=1e-12, atol=0)
    np.testing.assert_allclose(motion.vertical, _obspy_acceleration(vertical, inventory),
                               rtol=1e-12, atol=0)
    assert motion.metadata["vertical"]["units_in_file"] == "m/s2"
    single = Motion.from_trace(vertical, inventory=STATIONXML)
    np.testing.assert_allclose(single.horizontal, motion.vertical, rtol=0, atol=0)


def test_units_that_contradict_the_inventory_response_are_refused():
    trace = _counts("IU", "ANMO", "20", "HNZ")
    with pytest.raises(ValueError, match=r"units='g' contradicts the response in inventory "
                                         r"file .*Modified_IRIS_response_level_station\.xml"):
        records.read(trace, inventory=STATIONXML, units="g")
    assert records.read(trace, inventory=STATIONXML, units="m/s2").units_in_file == "m/s2"


def test_a_velocity_inventory_is_refused_with_what_to_do_and_the_advice_works():
    """ObsPy's example stream and inventory (``obspy.read()``, ``obspy.read_inventory()``:
    BW.RJOB, a seismometer, input units M/S). The reference of the converted record is
    ObsPy's own ``remove_response(output="ACC")``."""
    stream = obspy.read()
    inventory = obspy.read_inventory()
    trace = stream.select(channel="EHZ")[0]
    with pytest.raises(ValueError, match=r"BW\.RJOB\.\.EHZ: the response in the given "
                                         r"inventory .* has input units 'M/S', not an "
                                         r"acceleration but a velocity.*never differentiates"
                                         r".*remove_response\(inventory=\.\.\., "
                                         r"output='ACC'\)"):
        records.read(trace, inventory=inventory)
    with pytest.raises(ValueError, match="not an acceleration but a velocity"):
        Motion.from_stream(stream, horizontal="EHE", vertical="EHZ", inventory=inventory)
    # the advice, followed
    converted = stream.copy()
    converted.remove_response(inventory=inventory, output="ACC")
    expected = np.max(np.abs(converted.select(channel="EHZ")[0].data))  # ObsPy's m/s^2
    record = records.read(converted, component="EHZ", units="m/s2")
    assert record.pga == pytest.approx(expected, rel=1e-12)
    # ... but not with the inventory still given: the response is already removed
    with pytest.raises(ValueError, match=r"BW\.RJOB\.\.EHZ: its response was already "
                                         r"removed \(remove_response in trace\.stats\."
                                         r"processing\).*leave inventory= out"):
        records.read(converted, component="EHZ", inventory=inventory)


def test_an_attached_response_is_not_applied_twice_after_remove_response():
    """A stream with a response attached (the deprecated way) and then removed by
    ObsPy is in m/s^2 already; dividing by the sensitivity again would shrink it
    by about 5e8. Reference: ObsPy's corrected samples."""
    stream = obspy.read()
    inventory = obspy.read_inventory()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # attach_response is deprecated in newer ObsPy
        stream.attach_response(inventory)
    stream.remove_response(output="ACC")
    trace = stream.select(channel="EHZ")[0]
    assert "response" in trace.stats  # still attached
    record = records.read(trace, units="m/s2")
    assert record.pga == pytest.approx(np.max(np.abs(trace.data)), rel=1e-12)
    with pytest.raises(ValueError, match="already removed.*pass units="):
        records.read(trace)


def test_a_trace_the_inventory_does_not_hold_is_named_with_the_inventory():
    trace = obspy.read(str(ACCELEROGRAM))[0]  # CI.AGO..HNZ: not in ObsPy's IU.ANMO StationXML
    with pytest.raises(ValueError, match=r"CI\.AGO\.\.HNZ: inventory file .*"
                                         r"Modified_IRIS_response_level_station\.xml has no "
                                         r"response for this channel at 2016-06-20"):
        records.read(trace, inventory=STATIONXML)
    with pytest.raises(ValueError, match=r"CI\.AGO\.\.HNZ: the given inventory \(channels "
                                         r"NZ\.DCZ\.10\.HHZ, NZ\.DCZ\.20\.HNZ\) has no response"):
        records.read(trace, inventory=obspy.read_inventory(str(DATALESS)))
    # right codes, wrong epoch: IU.ANMO.20.HNZ starts 2012-05-04 in that file
    early = _counts("IU", "ANMO", "20", "HNZ")
    early.stats.starttime = obspy.UTCDateTime(2010, 1, 1)
    with pytest.raises(ValueError, match=r"IU\.ANMO\.20\.HNZ: .* no response .* at "
                                         r"2010-01-01.*epoch"):
        Motion.from_trace(early, inventory=STATIONXML)


def test_an_inventory_overrides_an_attached_response():
    """As in ObsPy's ``remove_response(inventory=...)``: the explicit inventory wins."""
    from obspy.core.inventory.response import Response

    trace = _counts("IU", "ANMO", "20", "HNZ")
    trace.stats.response = Response.from_paz([], [], 1.0, input_units="M/S**2",
                                             output_units="COUNTS")
    inventory = obspy.read_inventory(str(STATIONXML))
    expected = _obspy_acceleration(trace, inventory)
    np.testing.assert_allclose(records.read(trace, inventory=inventory).acceleration, expected,
                               rtol=1e-12, atol=0)
    # without inventory= the attached response (1 count per m/s^2) is used, as before
    assert records.read(trace).pga == pytest.approx(25333.0, rel=1e-12)


def test_bad_inventory_arguments_name_the_parameter(tmp_path):
    trace = _counts("IU", "ANMO", "20", "HNZ")
    missing = tmp_path / "station.xml"
    with pytest.raises(RecordError, match=r"inventory='.*station\.xml': no such file"):
        records.read(trace, inventory=missing)
    with pytest.raises(RecordError, match=r"inventory='.*miniseed_record\.mseed': ObsPy "
                                          r"cannot read it"):
        records.read(trace, inventory=ACCELEROGRAM)  # a waveform, not station metadata
    with pytest.raises(TypeError, match="inventory= must be an obspy.Inventory"):
        records.read(trace, inventory=42)
    with pytest.raises(ValueError, match=r"text options \['dt'\] and ObsPy options "
                                         r"\['inventory'\]"):
        records.read(tmp_path / "record.txt", dt=0.01, inventory=STATIONXML)


def test_read_of_a_knet_file_needs_no_units_the_format_declares_them():
    """``read``'s docstring and ``read_obspy``'s: units= is required *unless the
    format declares it*. A ``.knet`` file goes through ObsPy's detection, which used
    to ask for units= anyway. Reference: ObsPy's ``data * calib`` (m/s^2), mean removed
    as NIED's format requires."""
    trace = obspy.read(str(KNET))[0]
    calibrated = trace.data * trace.stats.calib
    record = records.read(KNET)
    assert record.pga == pytest.approx(np.max(np.abs(calibrated - calibrated.mean())),
                                       rel=1e-12)
    assert record.metadata["units_source"] == "the KNET format"
