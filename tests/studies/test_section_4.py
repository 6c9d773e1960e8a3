"""Section 4 of the report: Tables 4.1-4.3 with the bundled Pacoima Dam records.

Reference values are the printed tables (data/report/*.csv, transcribed from the
report) and statements of Section 4.3. The bundled records are NGA-West2
re-processings of what the report used, so cells near the overturning threshold
can differ; the checks below are the report's robust statements.
"""

import math

import pytest

import shaketable as st
from shaketable.core import theory
from shaketable.core.constants import G
from shaketable.ground import records
from shaketable.studies.report_tables import printed_table, reproduce_table, table_3_1


@pytest.fixture(scope="module")
def table_4_2():
    return reproduce_table("table_4_2", columns=["pacoima S16E", "pacoima S74W"]).to_frame()


@pytest.fixture(scope="module")
def table_4_3():
    return reproduce_table("table_4_3", columns=["pacoima S16E", "pacoima S74W"]).to_frame()


def test_printed_tables_are_complete():
    assert len(printed_table("table_4_2")) == 12 and len(printed_table("table_4_3")) == 12
    assert len(printed_table("table_4_1")) == 6 and len(printed_table("table_3_1")) == 5


def test_table_4_2_every_block_overturns_under_s16e_at_cor_1(table_4_2):
    # Table 4.2, column S16E: F for all twelve blocks.
    s16e = table_4_2[table_4_2["column"] == "pacoima S16E"]
    assert (s16e["reproduced"] == "F").all()


def test_table_4_3_the_3_ft_wide_blocks_that_survive_s16e(table_4_3):
    # Table 4.3 (COR 0.90), S16E: 6 x 3 ft 0.38 and 9 x 3 ft 0.75 survive, all others F.
    s16e = table_4_3[table_4_3["column"] == "pacoima S16E"].set_index(["height [ft]",
                                                                        "width [ft]"])
    survivors = s16e[s16e["reproduced"] != "F"]
    assert set(survivors.index) == {(6.0, 3.0), (9.0, 3.0)}
    # within the report's stated ~10 % agreement (Summary, item 3)
    assert float(survivors.loc[(6.0, 3.0), "reproduced"]) == pytest.approx(0.38, abs=0.04)
    assert float(survivors.loc[(9.0, 3.0), "reproduced"]) == pytest.approx(0.75, abs=0.08)


@pytest.mark.parametrize("fixture", ["table_4_2", "table_4_3"])
def test_overturn_verdicts_agree_in_most_pacoima_cells(fixture, request):
    frame = request.getfixturevalue(fixture)
    # The report's own test/theory agreement is about 10 % on amplitudes; near the
    # threshold a verdict can flip with the record's processing. At least 21 of the 24
    # printed verdicts must agree (measured: 23/24 for Table 4.2 and 22/24 for Table 4.3;
    # 22 and 16 with the vertical read the other way, docs/section4.md).
    assert frame["verdict_agrees"].sum() >= 21


def test_table_4_1_pacoima_cells():
    # Table 4.1 (printed, data/report/table_4_1.csv): 11 of its 12 Pacoima verdicts agree;
    # the exception is 16 x 4 ft at COR 0.95 under S16E (0.82 printed, 0.78 in Fig. 4.2),
    # which overturns here (docs/section4.md). Section 4.3 (1): the 15 x 5 ft block at
    # COR 0.95 is the one that survives S16E; its printed 0.55 within the report's ~10 %.
    frame = reproduce_table("table_4_1", columns=["pacoima S16E", "pacoima S74W"]).to_frame()
    assert frame["verdict_agrees"].sum() >= 10
    cell = frame[(frame["height [ft]"] == 15) & (frame["width [ft]"] == 5)
                 & (frame["cor [-]"] == 0.95) & (frame["column"] == "pacoima S16E")].iloc[0]
    assert cell["report"] == "0.55"
    assert float(cell["reproduced"]) == pytest.approx(0.55, rel=0.1)
    counts = reproduce_table("table_4_1", columns=["pacoima S16E", "A-1"]).counts()
    # the substitute columns are counted apart from the recorded ones
    assert counts["recorded records only"]["cells"] == 6 and counts["all"]["cells"] == 12


def test_larger_blocks_of_the_same_aspect_ratio_respond_less():
    # Section 4.3 (1): at a fixed aspect ratio the larger block is generally more stable
    # (4 x 2 ft vs 6 x 3 ft vs 8 x 4 ft under S74W, COR 0.90).
    motion = records.load("pacoima-dam-s74w")
    ratios = [st.simulate(st.Block.from_feet(2 * w, w), motion, cor=0.9).max_theta_ratio
              for w in (2, 3, 4)]
    assert ratios[0] > ratios[2]


def test_table_3_1_exact_period_against_test_column():
    frame = table_3_1()
    # Section 3.7 (1): test and theory within 2 % (the table's own ratios reach 3 %).
    assert (abs(frame["test / exact [-]"] - 1) <= 0.03).all()


def test_section_4_3_4_single_pulse_by_eq_2_9():
    # Section 4.3 (4): a single sine pulse of 0.1 s duration must reach "at least 4.6 g"
    # to overturn the 16 x 4 ft block by Eq. (2-9).
    block = st.Block.from_feet(16, 4)
    amplitude = theory.half_sine_overturn_amplitude_large_frequency(block, 0.2) / G
    assert amplitude == pytest.approx(4.6, rel=0.03)


@pytest.mark.parametrize("vertical_sign", ["up", "down", None])
def test_fig_4_16_4_17_prestress_rods_keep_the_block_standing(vertical_sign):
    # Section 4.4: the 8 x 2 ft block overturns under Pacoima Dam S16E at COR 1.0 and 0.90
    # (Tables 4.2, 4.3) and still at 0.70 (Fig. 4.16); tied down at its centre by a rod of
    # stiffness 0.4 W/in and prestress 0.4 W (Fig. 4.17, COR 0.95) it stays stable. The report
    # finds max theta/alpha = 0.3; here 0.60 (vertical as written), 0.72 (reversed), 0.45
    # (none): the bundled record differs from the report's (docs/section4.md), so the test
    # holds the report's robust statement, under every reading of the vertical.
    if vertical_sign is None:
        motion = records.load("pacoima-dam-s16e", vertical=False)
    else:
        motion = records.load("pacoima-dam-s16e", pacoima_vertical_sign=vertical_sign)
    free = st.Block.from_feet(8, 2)
    if vertical_sign == "up":  # the package's reading (records.load); reversed, COR 0.7 survives
        for cor in (1.0, 0.9, 0.7):
            assert st.simulate(free, motion, cor=cor).overturned
    tied = st.Block.parse("8x2ft", rods=st.PrestressRods.from_inches(0.4, 0.4, 12))
    result = st.simulate(tied, motion, cor=0.95)
    assert not result.overturned and not result.unstable
    assert result.max_theta_ratio < 0.8
    # Section 4.4: the foundation carries "0.4W + .4W Delta", Delta the rod's extension [in]
    # at the largest rotation, 12 in from the pivot corner
    delta_in = 12.0 * math.sin(result.max_abs_theta)
    assert result.max_rod_force == pytest.approx(0.4 + 0.4 * delta_in, rel=1e-12)
    assert result.summary()["max_rod_force [W]"] == result.max_rod_force
    assert st.simulate(free, motion, cor=0.95).max_rod_force == 0.0
