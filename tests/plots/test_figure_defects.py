"""Figure defects a newcomer found: every run shown where runs are overlaid, reference
lines across the plotted range, panels not squeezed by their legends, tick labels apart.

Every check measures the drawn figure (artists' data and display extents after a draw),
not the code's own placement arithmetic."""

from __future__ import annotations

import numpy as np

import shaketable as st
from shaketable.plots.base import pyplot


def _drawn(fig):
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _texts(fig) -> str:
    return "\n".join(text.get_text() for axis in fig.axes for text in axis.texts)


def test_calcomp_of_two_runs_shows_both_and_says_which_one_ends():
    """A small block that falls early overlaid on a large one that rocks on: the rates
    panel carries the large block's velocity to the end of the axis, and the note at the
    fall names the small block (the other run does not end there)."""
    from shaketable.plots.calcomp import calcomp

    small, large = st.Block.from_feet(4, 0.8), st.Block.from_feet(12, 2.4)
    falls = st.simulate(small, None, cor=0.9, theta0=1.2 * small.alpha, duration=4.0)
    rocks = st.simulate(large, None, cor=0.9, theta0=0.5 * large.alpha, duration=4.0)
    assert falls.overturned and not rocks.overturned and falls.t[-1] < 0.5 * rocks.t[-1]
    fig = calcomp(falls, others=[rocks])
    rates = fig.axes[-2]
    stop = rates.get_xlim()[1]
    reach = max(float(np.nanmax(line.get_xdata())) for line in rates.get_lines())
    assert reach >= 0.99 * stop
    note = _texts(fig)
    assert note.startswith(small.describe()) and "overturned (" in note
    assert "its run ends here" in note and large.describe() not in note
    pyplot().close(fig)
