"""
Teaching gallery: four lessons of the report in pictures
========================================================

Each item is one function of :mod:`shaketable.studies.teaching` (the numbers) drawn by
its ``plot`` method (:mod:`shaketable.plots.teaching`); the user guide's
:doc:`/teaching` page explains what each shows. Run as a script it also writes the
figures, into a folder given with ``--out`` (default: a temporary folder)::

    python examples/plot_teaching_gallery.py --out teaching-figures
"""

import argparse
import tempfile
from pathlib import Path

from shaketable.plots.teaching import save_item
from shaketable.studies import teaching

parser = argparse.ArgumentParser(description="Draw the teaching gallery's figures.")
parser.add_argument("--out", type=Path, default=None,
                    help="folder for the PNG files (default: a temporary folder)")
out = parser.parse_args().out or Path(tempfile.mkdtemp(prefix="shaketable-teaching-"))
out.mkdir(parents=True, exist_ok=True)


def show(name):
    """Run one gallery item, print its highlights and numbers, draw it and save it."""
    item = teaching.run_item(name)
    print("\n".join(item.highlights()))
    print(item.to_frame().round(4).head(10).to_string(index=False))
    item.plot()
    save_item(item, out / f"teaching_{name.replace('-', '_')}.png")


# %%
# Period against amplitude
# ------------------------
# A rocking block is not a pendulum: its period grows with the amplitude (Eq. 2-5, the
# exact period, the engine, and the linear oscillator that gets it wrong).
show("period-amplitude")

# %%
# The coefficient of restitution
# ------------------------------
# Max theta/alpha of the 6 x 2 ft block under Pacoima Dam S74W against the COR: the
# response is not monotone in the energy lost at impacts.
show("cor-sweep")

# %%
# Similar blocks
# --------------
# Geometrically similar blocks: the bigger block is the safer one (the p t scaling law).
show("similar-blocks")

# %%
# When does rocking start?
# ------------------------
# Eq. (2-1): the block rocks when the horizontal acceleration exceeds (g + vertical) b/h.
show("rocking-onset")

# %%
print(f"figures written to {out}")
