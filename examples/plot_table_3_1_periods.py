"""
Table 3.1 and Fig. 3.6: periods of the free-rocking 36 x 9 in block
===================================================================

The report's Table 3.1 prints the measured and computed periods of the 36 x 9 in block
rocking freely from several amplitudes. :func:`shaketable.studies.report_tables.table_3_1`
puts them beside Eq. (2-5), the exact nonlinear period and a virtual test read the way
the report read its records (period = 4 x the time from a maximum to zero).
"""

from shaketable.plots.studies import figure_3_6
from shaketable.studies.report_tables import table_3_1

frame = table_3_1()
print(frame.round(3).to_string(index=False))
worst = 100 * abs(frame["test / exact [-]"] - 1).max()
print(f"\nprinted test periods against the exact period: within {worst:.1f} %")

# %%
# Fig. 3.6 of the report: period against amplitude, the printed points on the curves.
figure_3_6(frame)
