"""
The classroom's three lessons: two blocks that differ by one thing
==================================================================

The lessons of the live page ``shaketable classroom`` (the user guide's :doc:`/teaching`
page), as a notebook: each runs the same two blocks as its bundled scene
(``shaketable run teaching-period-grows``, ``teaching-lower-cor``,
``teaching-small-block-falls``) through the function the page itself calls,
:func:`shaketable.classroom.model.compute`, and draws theta/alpha of both blocks. Change a
value of a lesson's :class:`~shaketable.classroom.model.Settings` (a height, a COR, a
table motion, written with its unit) and run the cell again, as a student would move a
slider on the page.
"""

from dataclasses import replace

import matplotlib.pyplot as plt

from shaketable.classroom.model import LESSONS, compute


def show(name, **changes):
    """Run a lesson (with some of its settings changed), print what to look for and the
    numbers, draw theta/alpha of its two blocks."""
    lesson = LESSONS[name]
    picture = compute(replace(lesson.settings, **changes))
    print(f"{lesson.title}: {lesson.look_for}")
    for label, verdict, numbers in zip(picture.labels, picture.verdicts, picture.numbers):
        print(f"  {label}: {verdict}; " + ", ".join(f"{key} {value}"
                                                    for key, value in numbers.items()))
    fig, ax = plt.subplots(figsize=(8, 3.2), layout="constrained")
    for label, (times, ratio) in zip(picture.labels, picture.traces):
        ax.plot(times, ratio, lw=1.0, label=label)
    for sign in (1, -1):
        ax.axhline(sign, color="tab:red", ls="--", lw=0.8)
    ax.set_ylim(-1.6, 1.6)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("θ/α [-]")
    ax.set_title(lesson.title)
    ax.legend(loc="upper right", fontsize=8)
    return picture


# %%
# The period grows with the amplitude
# -----------------------------------
# The 36 x 9 in block of Table 3.1 rocking freely without losses (COR 1), released from
# 0.2 and 0.8 of its block angle: the larger swing takes longer (Eq. 2-5).
show("period")

# %%
# A lower COR can raise the response
# ----------------------------------
# The 6 x 2 ft block under Pacoima Dam S74W (with its vertical), COR 1.0 and 0.93
# (Section 4.3 (3)): the lossier block rocks to twice the angle.
show("lower-cor")

# %%
# The small block falls first
# ---------------------------
# Two blocks of the same shape (H/B = 5), 4 ft and 12 ft tall, on the same record at COR
# 0.9 (Section 2.4 (1)): the small one overturns near 4.3 s (the trace leaves the picture).
show("small-falls")

# %%
# Your turn
# ---------
# The same small block with a taller twin of 8 ft instead of 12 ft, the record scaled to
# 0.8 of itself: does the 8 ft block survive?
show("small-falls", second="8 ft", record_scale="0.8")
