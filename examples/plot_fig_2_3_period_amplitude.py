"""
Fig. 2.3: period of free rocking against amplitude
==================================================

The period of a rocking block grows with its amplitude, unlike a pendulum's. The report
plots Housner's slender-block formula, Eq. (2-5); here it is drawn beside the exact period
of Eq. (2-3) (quadrature of the energy integral) and the engine's time between impacts at
COR 1 (:func:`shaketable.studies.section2.figure_2_3`).
"""

from shaketable.plots.studies import section_2_figure
from shaketable.studies import section2

frame = section2.figure_2_3()
print(frame.round(4).head(12).to_string(index=False))

# %%
# The figure: period against amplitude theta0/alpha, one line per block.
section_2_figure(frame, "2.3")
