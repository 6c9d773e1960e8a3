"""ObsPy in and out, checked on sample files ObsPy itself ships.

Every expected peak is computed here from ObsPy's own reading of the file
(``obspy.read(path)[0].data * calib``) or from the file's header as ObsPy
parses it -- never from shaketable.
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

DATA = Path(obspy.__file__).parent / "io"
KNET = DATA / "nied" / "tests" / "data" / "test.knet"
SAC = DATA / "sac" / "tests" / "data" / "seism.sac"
MSEED = DATA / "mseed" / "tests" / "data" / "BW.BGLD.__.EHE.D.2008.001.first_10_records"


def test_knet_reads_with_calib_and_mean_removed_to_the_header_peak():
    # obspy's own K-NET test file: raw counts peak at 35,310; calib (Scale Factor
    # 2000 gal / 8388608, times 0.01 to m/s^2) applied; NIED's format asks the
    # user to remove the offset, after which the peak is the header's
    # "Max. Acc. (gal) 4.383", which obspy parses into stats.knet.accmax.
    trace = obspy.read(str(KNET))[0]
    calibrated = trace.data * trace.stats.calib
    header_peak = trace.stats.knet.accmax * 0.01  # gal -> m/s^2
    record = records.read(KNET, units="m/s2")
    assert record.pga == pytest.approx(np.max(np.abs(calibrated - calibrated.mean())), rel=1e-12)
    assert record.pga == pytest.approx(header_peak, abs=0.0005e-2)  # header rounds to 0.001 gal
    assert record.metadata["mean_removed"] is True
    raw = records.read(KNET, remove_mean=False)  # units declared by the format
    assert raw.pga == pytest.approx(np.max(np.abs(calibrated)), rel=1e-12)  # about 0.084 m/s^2
    assert 0.08 < raw.pga < 0.09
    assert record.metadata["station"] == "AKT013" and record.metadata["channel"] == "EW"


def test_knet_units_that_contradict_the_format_are_refused():
    with pytest.raises(ValueError, match="contradicts the KNET format"):
        records.read(KNET, units="gal")


@pytest.mark.parametrize("path, units, factor", [(SAC, "m/s2", 1.0), (MSEED, "cm/s2", 0.01)])
def test_sac_and_mseed_read_to_obspys_calibrated_peak(path, units, factor):
    trace = obspy.read(str(path))[0]
    expected = np.max(np.abs(trace.data * trace.stats.calib)) * factor  # no mean removed
    record = records.read(path, units=units)
    assert record.pga == pytest.approx(expected, rel=1e-12)
    assert record.metadata["mean_removed"] is False
    assert record.metadata["starttime"] == str(trace.stats.starttime)


def test_units_are_required_where_the_format_does_not_declare_them():
    with pytest.raises(ValueError, match="pass units="):
        records.read(SAC)


def test_read_accepts_a_trace_and_a_stream():
    stream = obspy.read(str(KNET))
    from_trace = records.read(stream[0])
    from_stream = records.read(stream, component=0)
    expected = stream[0].data * stream[0].stats.calib
    assert from_trace.pga == from_stream.pga == pytest.approx(
        np.max(np.abs(expected - expected.mean())), rel=1e-12)
    assert np.max(np.abs(stream[0].data)) == 35310.0  # the stream is not changed


def _stream():
    """Three float64 traces [m/s^2] built from obspy's K-NET sample with calib applied."""
    trace = obspy.read(str(KNET))[0]
    values = trace.data * trace.stats.calib
    traces = []
    for channel, scale in (("HNE", 1.0), ("HNN", -0.5), ("HNZ", 0.25)):
        header = {"network": "BO", "station": "AKT013", "location": "00", "channel": channel,
                  "delta": trace.stats.delta, "starttime": trace.stats.starttime}
        traces.append(obspy.Trace(np.array(values * scale, dtype=np.float64), header=header))
    return obspy.Stream(traces)


def test_a_stream_round_trips_through_motion():
    stream = _stream()
    motion = Motion.from_stream(stream, horizontal="HNE", vertical="Z", units="m/s2")
    assert motion.metadata["horizontal"]["station"] == "AKT013"
    assert motion.metadata["vertical"]["channel"] == "HNZ"
    back = motion.to_stream()
    assert [trace.id for trace in back] == ["BO.AKT013.00.HNE", "BO.AKT013.00.HNZ"]
    for original, written in zip((stream[0], stream[2]), back):
        assert written.stats.starttime == original.stats.starttime
        assert written.stats.delta == pytest.approx(original.stats.delta, rel=1e-12)
        np.testing.assert_allclose(written.data, original.data, rtol=0, atol=1e-12)


def test_from_trace_and_index_selection():
    stream = _stream()
    motion = Motion.from_trace(stream[1], units="m/s2")
    np.testing.assert_allclose(motion.horizontal, stream[1].data, rtol=0, atol=1e-12)
    assert motion.vertical is None
    with pytest.raises(Exception, match="expected exactly one trace"):
        Motion.from_stream(stream, units="m/s2")


def test_a_generated_motion_is_written_as_mseed_and_sac(tmp_path):
    t = np.arange(0, 2.0, 0.01)
    motion = Motion(t, 3.0 * np.sin(2 * np.pi * t), 0.5 * np.cos(2 * np.pi * t), name="sine")
    stream = motion.to_stream(network="XX", station="TABLE")
    stream.write(str(tmp_path / "motion.mseed"), format="MSEED")
    back = Motion.from_stream(obspy.read(str(tmp_path / "motion.mseed")), horizontal="HN1",
                              vertical="HNZ", units="m/s2")
    np.testing.assert_allclose(back.horizontal, motion.horizontal, rtol=0, atol=1e-12)
    np.testing.assert_allclose(back.vertical, motion.vertical, rtol=0, atol=1e-12)
    stream[0].write(str(tmp_path / "motion.sac"), format="SAC")
    sac = records.read(tmp_path / "motion.sac", units="m/s2")
    np.testing.assert_allclose(sac.acceleration, motion.horizontal, rtol=1e-6, atol=1e-6)


def test_to_stream_refuses_nonuniform_sampling():
    motion = Motion([0.0, 0.01, 0.03], [0.0, 1.0, 0.0])
    with pytest.raises(ValueError, match="not uniformly sampled"):
        motion.to_stream()


def test_metadata_survives_scaling_and_is_read_only():
    motion = Motion.from_stream(_stream(), horizontal="HNE", units="m/s2")
    scaled = motion.scaled(2.0).mirrored().subdivided(2)
    assert scaled.metadata["horizontal"]["station"] == "AKT013"
    with pytest.raises(TypeError):
        scaled.metadata["x"] = 1  # type: ignore[index]
    assert Motion([0.0, 1.0], [0.0, 0.0]).metadata == {}


# ------------------------------------------------------------- vertical sign
def test_combine_of_a_dwn_vertical_warns_and_states_the_reading():
    horizontal = records.load_record("pacoima-dam-s16e")
    down = records.load_record("pacoima-dam-down")
    with pytest.warns(records.VerticalSignWarning, match="pacoima_vertical_sign='up'"):
        by_label = records.combine(horizontal, down)
    assert by_label.metadata["vertical_positive"] == "down"
    assert by_label.metadata["vertical_sign_source"] == "label"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        explicit = records.combine(horizontal, down, vertical_positive="up")
    bundled = records.load("pacoima-dam-s16e")
    # the bundled name's default is the "up" reading, stated in its metadata
    np.testing.assert_array_equal(bundled.vertical, explicit.vertical)
    assert bundled.metadata["vertical_positive"] == "up"
    assert "pacoima_vertical_sign='up'" in bundled.metadata["vertical_sign_source"]
    np.testing.assert_array_equal(records.load("pacoima-dam-s16e",
                                               pacoima_vertical_sign="down").vertical,
                                  by_label.vertical)
    assert "positive UP" in records.available(details=True)["pacoima-dam-s16e"]
    assert records.available() == sorted(records.available(details=True))


def test_waveform_module_does_not_import_obspy_at_import_time():
    import subprocess
    import sys
    code = ("import sys, shaketable.ground.records, shaketable.core.motion; "
            "print('obspy' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True)
    assert result.stdout.strip() == "False"
    assert waveform.DECLARED_UNITS["KNET"] == "m/s2"


# --------------------------------------------------------------- response-derived units
def _trace_with_response(input_units: str, gain: float) -> obspy.Trace:
    """A trace of counts with an instrument response made by ObsPy's own
    ``Response.from_paz`` (flat: no poles or zeros; the overall sensitivity is
    ``gain`` counts per ``input_units``)."""
    from obspy.core.inventory.response import Response

    rng = np.random.default_rng(7)
    counts = rng.integers(-40_000, 40_000, size=500).astype(np.int32)
    trace = obspy.Trace(counts, header={"delta": 0.01, "network": "XX", "station": "ABC",
                                        "location": "00", "channel": "HNE", "calib": 1.0})
    trace.stats.response = Response.from_paz([], [], gain, input_units=input_units,
                                             output_units="COUNTS")
    return trace


@pytest.mark.filterwarnings("ignore:ObsPy can not map unit:UserWarning")  # CM/S**2: evalresp only
@pytest.mark.parametrize("input_units, factor", [("M/S**2", 1.0), ("CM/S**2", 0.01)])
def test_attached_response_gives_the_units_and_obspys_sensitivity_removal(input_units, factor):
    """No units= given: the response's input units (its instrument sensitivity) are the
    units; the expected peak is ObsPy's own ``Trace.remove_sensitivity()`` (counts over
    the overall sensitivity), converted to m/s^2 -- not a value from shaketable."""
    trace = _trace_with_response(input_units, 4.0e5)
    corrected = trace.copy()
    corrected.remove_sensitivity()
    expected = np.max(np.abs(corrected.data)) * factor
    record = records.read(trace)
    assert record.pga == pytest.approx(expected, rel=1e-12)
    assert record.units_in_file == ("m/s2" if factor == 1.0 else "cm/s2")
    motion = Motion.from_stream(obspy.Stream([trace]), horizontal="HNE")
    assert np.max(np.abs(motion.horizontal)) == pytest.approx(expected, rel=1e-12)
    assert motion.metadata["horizontal"]["units_in_file"] == record.units_in_file


def test_units_that_contradict_the_attached_response_are_refused():
    trace = _trace_with_response("M/S**2", 4.0e5)
    with pytest.raises(ValueError, match="contradicts its attached instrument response"):
        records.read(trace, units="g")
    assert records.read(trace, units="m/s2").units_in_file == "m/s2"  # agreeing units pass


def test_a_velocity_response_is_refused_naming_the_trace():
    """ObsPy's own example stream and inventory (``obspy.read()``,
    ``obspy.read_inventory()``: BW.RJOB, a seismometer whose response has input
    units M/S) are velocities: the error names the trace and says so."""
    stream = obspy.read()
    inventory = obspy.read_inventory()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # attach_response is deprecated in newer ObsPy
        stream.attach_response(inventory)
    trace = stream.select(channel="EHZ")[0]
    assert trace.stats.response.instrument_sensitivity.input_units == "M/S"
    with pytest.raises(ValueError, match=r"BW\.RJOB\.\.EHZ.*'M/S', not an acceleration"):
        records.read(trace)


def test_without_response_or_format_units_the_message_asks_for_units():
    trace = _trace_with_response("M/S**2", 4.0e5)
    del trace.stats.response
    with pytest.raises(ValueError, match="pass units="):
        records.read(trace)
