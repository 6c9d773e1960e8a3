"""plot_measurement draws what a Measurement has, including one built by hand
with ``theta`` but no ``theta_exact`` (it used to raise TypeError on ``None / alpha``).

Expected values are computed here by hand: alpha = atan(B/H) of a 1.0 m x 0.2 m
block, standard gravity 9.80665 m/s^2 (the conventional value, written out).
"""

from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from matplotlib import pyplot as plt  # noqa: E402

from shaketable import Block  # noqa: E402
from shaketable.lab.sensors import Measurement  # noqa: E402
from shaketable.plots.calibration import plot_measurement  # noqa: E402

HEIGHT, WIDTH = 1.0, 0.2            # [m]
ALPHA = math.atan(WIDTH / HEIGHT)   # [rad], by hand
STANDARD_GRAVITY = 9.80665          # [m/s^2]


def _hand_built(with_exact: bool) -> Measurement:
    t = np.linspace(0.0, 4.0, 801)
    theta = 0.5 * ALPHA * np.exp(-0.4 * t) * np.cos(2 * np.pi * 1.5 * t)
    return Measurement(t=t, top_displacement=None, theta=theta,
                       theta_exact=1.01 * theta if with_exact else None,
                       table_horizontal=2.0 * np.sin(2 * np.pi * t), table_vertical=None,
                       rate=200.0, block=Block(HEIGHT, WIDTH), name="by hand")


def _legend_covers_no_data(ax) -> bool:
    fig = ax.figure
    fig.canvas.draw()
    box = ax.get_legend().get_window_extent(fig.canvas.get_renderer())
    for line in ax.get_lines():
        xy = ax.transData.transform(line.get_xydata())
        inside = ((xy[:, 0] > box.x0) & (xy[:, 0] < box.x1)
                  & (xy[:, 1] > box.y0) & (xy[:, 1] < box.y1))
        if inside.any():
            return False
    return True


def test_a_hand_built_measurement_without_theta_exact_is_drawn(tmp_path):
    measurement = _hand_built(with_exact=False)
    fig = plot_measurement(measurement)
    path = tmp_path / "measurement.png"
    fig.savefig(path, dpi=80)
    assert path.stat().st_size > 10_000  # a rendered figure, not an empty file
    angle, horizontal = fig.axes       # two panels: no vertical channel, no empty panel
    lines = angle.get_lines()
    assert len(lines) == 1             # the exact-angle trace is skipped, not drawn as NaN
    np.testing.assert_allclose(lines[0].get_ydata(), measurement.theta / ALPHA, rtol=1e-12)
    assert lines[0].get_ydata().max() == pytest.approx(0.5, rel=1e-12)  # 0.5 alpha at t = 0
    (table,) = horizontal.get_lines()
    np.testing.assert_allclose(table.get_ydata(), measurement.table_horizontal / STANDARD_GRAVITY,
                               rtol=1e-12)
    labels = [text.get_text() for text in angle.get_legend().get_texts()]
    assert labels == ["-top displacement / H (report)"]
    assert _legend_covers_no_data(angle)
    plt.close(fig)


def test_with_theta_exact_both_angles_are_drawn_and_the_legend_is_off_the_data():
    measurement = _hand_built(with_exact=True)
    fig = plot_measurement(measurement)
    angle = fig.axes[0]
    report, exact = angle.get_lines()
    assert exact.get_linestyle() == "--"
    np.testing.assert_allclose(exact.get_ydata(), 1.01 * measurement.theta / ALPHA, rtol=1e-12)
    assert [text.get_text() for text in angle.get_legend().get_texts()] == [
        "-top displacement / H (report)", "exact geometry"]
    assert _legend_covers_no_data(angle)
    plt.close(fig)


def test_a_measurement_without_channels_is_refused():
    empty = Measurement(t=np.linspace(0, 1, 11), top_displacement=None, theta=None,
                        theta_exact=None, table_horizontal=None, table_vertical=None,
                        rate=10.0, block=Block(HEIGHT, WIDTH))
    with pytest.raises(ValueError, match="no channel to plot"):
        plot_measurement(empty)
