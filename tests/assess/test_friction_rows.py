"""An assessment whose low- and high-friction rows agree says why (the object rocks at
both, and friction enters a rocking run only where its base slips), and its slip column
shows a slip of a few micrometres as such, not as 0 mm."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from shaketable.studies.assess import format_slip_mm, same_friction_note


def _free(high_excursions):
    """The MCE rows of ``assess lab-cabinet`` (2 x 0.5 m, B/H 0.25, mu 0.3 and 0.5): 6 of 8
    records overturn it at both; the two it survives rock, with these corner excursions
    [m] and peak base slips [m] (runs.csv); at mu 0.3 one run slid 4.6 micrometres."""
    rows = []
    for case, mu, excursions, slips in (
            ("low", 0.3, [0.202129, 0.240810], [2.016214e-17, 4.585855e-06]),
            ("high", 0.5, high_excursions, [2.016214e-17, 2.699663e-17]),
            ("let it slide", 0.15, [0.2, 0.6], [0.2, 0.6])):
        rows.append({"level": 1, "case": case, "mu [-]": mu, "overturned": 6,
                     "excursion median [m]": float(np.median(excursions)),
                     "excursion p84 [m]": float(np.percentile(excursions, 84)),
                     "slip max [m]": max(slips)})
    return pd.DataFrame(rows)


def test_rows_that_agree_say_why():
    note = same_friction_note(_free([0.202129, 0.240814]), 1, 0.25)
    assert "rocks at both frictions (Section 2.1)" in note
    assert "only where its base slips (at most 0.0046 mm in a run it survives)" in note
    # one mm apart, or a friction below B/H (it slides there): no note
    assert same_friction_note(_free([0.202129, 0.2420]), 1, 0.25) == ""
    assert same_friction_note(_free([0.202129, 0.240814]), 1, 0.35) == ""
    assert same_friction_note(_free([0.202129, 0.240814]), 0, 0.25) == ""   # no such level


def test_a_slip_of_micrometres_is_not_zero_mm():
    assert format_slip_mm(4.585855e-06) == "0.0046"
    assert format_slip_mm(2.016214e-17) == "0"       # rounding: the corner did not slide
    assert format_slip_mm(0.208) == "208"
    assert format_slip_mm(math.nan) == "-"
