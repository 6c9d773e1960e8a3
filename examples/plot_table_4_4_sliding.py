"""
Table 4.4: how far a block slides
=================================

Section 4.5 of the report lets the block slide instead of rock (a squat block on a
slippery table) and tabulates the maximum sliding displacement relative to the ground
for dynamic friction coefficients 0.1, 0.2 and 0.3. :func:`shaketable.studies.sliding.table_4_4`
recomputes it with the Coulomb stick-slip block, exact between samples.
"""

import matplotlib.pyplot as plt

from shaketable.studies.sliding import table_4_4

frame = table_4_4()
print(frame.round(3).to_string(index=False))

# %%
# Reproduced displacement against the report's, one point per cell; open markers are the
# columns run on SUBSTITUTE motions (the report's artificial records are not available).
fig, ax = plt.subplots(figsize=(4.5, 4.5))
for substitute, style in ((False, "o"), (True, "s")):
    part = frame[frame["substitute motion"] == substitute]
    ax.loglog(part["report [in]"], part["reproduced [in]"], style,
              mfc="none" if substitute else None,
              label="substitute motion" if substitute else "recorded motion")
low = min(frame["report [in]"].min(), frame["reproduced [in]"].min())
high = max(frame["report [in]"].max(), frame["reproduced [in]"].max())
ax.plot([low, high], [low, high], "k--", lw=0.8)
ax.set_xlabel("report [in]")
ax.set_ylabel("reproduced [in]")
ax.set_title("Table 4.4: maximum sliding displacement")
ax.legend(frameon=False)
fig.tight_layout()
