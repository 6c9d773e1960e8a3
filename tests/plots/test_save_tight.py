"""``plots.base.save_tight`` writes the file ``savefig(bbox_inches="tight")`` writes.

The shortcut measures the tight box of a figure without a layout engine directly
instead of drawing the figure once more; the reference is matplotlib's own
``savefig(..., bbox_inches="tight")`` of the same figure, compared byte for byte.
"""

from __future__ import annotations

import io

import numpy as np
import pytest

from shaketable.plots.base import pyplot, save_tight


def _figure(layout):
    plt = pyplot()
    fig, axes = plt.subplots(2, 1, figsize=(5, 4), layout=layout)
    t = np.linspace(0.0, 10.0, 2001)
    axes[0].plot(t, np.sin(3 * t), label="θ [rad]")
    axes[0].legend(loc="best")          # placed where it is drawn
    axes[1].plot(t, np.cos(t) * 1e3, ls="--")
    axes[1].set_ylabel("a very long\nlabel [m/s²]")
    axes[1].annotate("outside", (10.5, 0.0), annotation_clip=False)   # beyond the axes
    fig.suptitle("caption\nsecond line")
    if layout is None:
        fig.tight_layout()
    return fig


@pytest.mark.parametrize("layout", [None, "constrained"])
def test_the_same_png_as_savefig_tight(tmp_path, layout):
    plt = pyplot()
    reference = io.BytesIO()
    fig = _figure(layout)
    fig.savefig(reference, format="png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    fig = _figure(layout)
    save_tight(fig, tmp_path / "figure.png", dpi=110)
    plt.close(fig)
    assert (tmp_path / "figure.png").read_bytes() == reference.getvalue()
