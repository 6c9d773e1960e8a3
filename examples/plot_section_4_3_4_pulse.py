"""
Section 4.3 (4): one half-sine pulse that overturns the 16 x 4 ft block
=======================================================================

The report quotes 4.6 g, by Eq. (2-9), for a single half-sine pulse of 0.1 s that
overturns the 16 x 4 ft block. :func:`shaketable.studies.pulses.section_4_3_4` gives the
closed form and the engine's exact threshold for pulses of 0.1 to 0.01 s.
"""

from shaketable.plots.studies import section_2_figure
from shaketable.studies import pulses

frame = pulses.section_4_3_4()
print(frame.round(3).to_string(index=False))
row = frame[frame["pulse duration [s]"] == 0.1].iloc[0]
print(f"\n0.1 s pulse: Eq. 2-9 gives {row['Eq. 2-9 [g]']:.2f} g (report: 4.6 g), "
      f"the engine {row['engine [g]']:.2f} g")

# %%
section_2_figure(frame, "4.3.4")
