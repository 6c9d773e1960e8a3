"""
Table 4.2: which blocks overturn under four earthquake records
==============================================================

Table 4.2 of the report gives max theta/alpha (or F, overturned) for twelve blocks at
COR 1.0 under the Pacoima Dam S16E and S74W records (with their verticals) and the
artificial A-1 and B-1 records. The Pacoima Dam records are bundled (NGA-West2); the
artificial ones are SUBSTITUTES generated in their spirit (the originals are not
available), so only the Pacoima Dam columns are a like-for-like comparison.
:func:`shaketable.studies.report_tables.reproduce_table` recomputes every cell.
"""

import matplotlib.pyplot as plt
import pandas as pd

from shaketable.studies.report_tables import reproduce_table

comparison = reproduce_table("table_4_2")
frame = comparison.to_frame()
wide = frame.assign(cell=frame["report"] + " / " + frame["reproduced"]).pivot_table(
    index=["height [ft]", "width [ft]", "cor [-]"], columns="column", values="cell",
    aggfunc="first", sort=False).reset_index()
print("Each cell: report / reproduced (F = overturns)\n")
print(wide.to_string(index=False))

# %%
# Agreement column by column:
print(pd.DataFrame(comparison.counts()).T.to_string())

# %%
# The verdicts as a picture: green where the report and the run agree on overturning.
agree = frame.pivot_table(index=["height [ft]", "width [ft]"], columns="column",
                          values="verdict_agrees", aggfunc="first", sort=False)
fig, ax = plt.subplots(figsize=(6, 5))
ax.imshow(agree.to_numpy(dtype=float), cmap="RdYlGn", vmin=0, vmax=1, aspect="auto")
ax.set_xticks(range(agree.shape[1]), agree.columns, rotation=30, ha="right")
ax.set_yticks(range(agree.shape[0]), [f"{h:g} x {w:g} ft" for h, w in agree.index])
ax.set_title("Table 4.2: overturning verdict agrees (green) or not (red)")
fig.tight_layout()
