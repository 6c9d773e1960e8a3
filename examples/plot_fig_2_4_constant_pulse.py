"""
Fig. 2.4: how long a constant acceleration must last to overturn a block
========================================================================

A constant ground acceleration a, larger than the rocking threshold g b/h, lasting t1
seconds overturns the 16 x 4 ft block when t1 is long enough. The report's closed form,
Eq. (2-7), is compared with the engine (the exact nonlinear equation, bisection on t1):
:func:`shaketable.studies.section2.figure_2_4`.
"""

from shaketable.plots.studies import section_2_figure
from shaketable.studies import section2

frame = section2.figure_2_4()
print(frame.round(4).to_string(index=False))

# %%
section_2_figure(frame, "2.4")
