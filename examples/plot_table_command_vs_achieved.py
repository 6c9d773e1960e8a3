"""
Section 3.7: target vs achieved table acceleration, with and without pitch
==========================================================================

For a 2 Hz, 0.5 g harmonic (Fig. 3.7 of the report) and the artificial
"olive-view" record (a substitute for the San Fernando-like record of
Section 3.6), this script

1. derives the displacement command (:func:`shaketable.lab.command.displacement_command`)
   and checks it against the assumed limits of the Berkeley table;
2. passes it through the assumed servo (:class:`shaketable.lab.servo.Actuator`);
3. adds the 12 Hz, 0.22 rad/s^2 pitch the report measured, for a block 1 m
   from the pitch axis (:func:`shaketable.lab.pitch.motion_at_block`);
4. plots the three and runs the 30 x 6 in block (COR 0.925) on the achieved
   motion without and with pitch.

Run from anywhere::

    python examples/plot_table_command_vs_achieved.py [--outdir DIR] [--docs-figure PNG]

Writes ``table_command_vs_achieved_<case>.png`` (whole record) and
``..._<case>_zoom.png`` (one second) into DIR (default: a temporary folder) and
draws the two one-second windows side by side; ``--docs-figure PNG`` saves that
figure too (``docs/figures/table_command_vs_achieved.png`` is made that way).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from shaketable import Block, G, simulate
from shaketable.ground import generators as motions
from shaketable.lab.command import displacement_command
from shaketable.lab.limits import check_limits
from shaketable.lab.pitch import Pitch, motion_at_block
from shaketable.lab.servo import Actuator, achieved
from shaketable.plots.table import plot_command_vs_achieved

#: Horizontal distance of the block from the table's pitch axis [m] (assumed).
BLOCK_POSITION = 1.0
#: Coefficient of restitution of the 30 x 6 in block (Section 3.5).
COR = 0.925

CASES = {
    # name: (motion, high-pass corner [Hz], zoom window [s])
    # ends a quarter period after 20 cycles, where the table's velocity is ~0
    "harmonic-2Hz-0.5g": (motions.harmonic(2.0, horizontal=0.5 * G, duration=10.125,
                                           dt=0.0025, ramp=1.0),
                          0.1, (3.0, 4.0)),
    # 0.5 Hz: about the lowest corner at which olive-view fits the assumed +-5 in
    # stroke. Subdivided to dt = 0.0025 s so the 12 Hz pitch has 33 samples a period.
    "olive-view": (motions.artificial("olive-view", seed=1).subdivided(4), 0.5, (3.0, 4.0)),
}


def achieved_pair(motion, highpass, pitch: Pitch, actuator: Actuator):
    """The command, the servo's achieved motion and that motion felt on the pitching table."""
    command = displacement_command(motion, highpass=highpass)
    servo = achieved(command, actuator)
    felt = motion_at_block(servo, pitch=pitch, block_position=BLOCK_POSITION)
    return command, servo, felt


def title_of(motion, highpass, pitch: Pitch, actuator: Actuator) -> str:
    return (f"{motion.name}: command high-passed at {highpass:g} Hz\nservo "
            f"{actuator.natural_frequency:g} Hz, ζ = {actuator.damping:g}; pitch "
            f"{pitch.frequency:g} Hz, {pitch.amplitude:g} rad/s², block {BLOCK_POSITION:g} m "
            "from the pitch axis")


def docs_figure(path: Path | None, pitch: Pitch, actuator: Actuator):
    """The one-second windows of both cases side by side, target vs achieved with and
    without pitch (the figure of docs/table.md); saved to ``path`` when given."""
    from shaketable.plots.base import pyplot

    plt = pyplot()
    fig = plt.figure(figsize=(16.0, 7.8), layout="constrained")
    for panel, (motion, highpass, zoom) in zip(fig.subfigures(1, 2, wspace=0.03),
                                                CASES.values()):
        axes = panel.subplots(3, 1, sharex=True,
                              gridspec_kw={"height_ratios": [1.2, 1.2, 1.0]})
        _, servo, felt = achieved_pair(motion, highpass, pitch, actuator)
        plot_command_vs_achieved(motion, servo, felt, ax=axes, window=zoom,
                                 title=title_of(motion, highpass, pitch, actuator))
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=100)
        print(f"wrote {path}")
    return fig


def run_case(name, motion, highpass, zoom, outdir: Path, pitch: Pitch, actuator: Actuator):
    """Command, limits, achieved motion, figure and block response for one motion."""
    from shaketable.plots.base import pyplot

    command, servo, felt = achieved_pair(motion, highpass, pitch, actuator)
    print(f"\n== {name}: high-pass {highpass} Hz, peak command displacement "
          f"{np.max(np.abs(command.horizontal_displacement)) * 1000:.1f} mm, velocity "
          f"{np.max(np.abs(command.horizontal_velocity)):.3f} m/s")
    exceeded = check_limits(command)
    verdict = "; ".join(map(str, exceeded)) if exceeded else "within the assumed limits"
    print("   limits: " + verdict)
    print(f"   peak vertical acceleration at the block from pitch: "
          f"{np.max(np.abs(felt.vertical_or_zero - servo.vertical_or_zero)):.3f} m/s^2")

    plt = pyplot()
    title = title_of(motion, highpass, pitch, actuator)
    for suffix, window in (("", None), ("_zoom", zoom)):
        fig = plot_command_vs_achieved(motion, servo, felt, window=window, title=title)
        path = outdir / f"table_command_vs_achieved_{name}{suffix}.png"
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        print(f"   wrote {path}")

    block = Block.parse("30x6in")
    for label, ground in (("target", motion), ("achieved", servo), ("achieved + pitch", felt)):
        result = simulate(block, ground, cor=COR, duration=motion.duration + 5.0)
        print(f"   30x6 in block on {label:>16}: status {result.status:>10}, "
              f"max |theta|/alpha = {result.max_theta_ratio:.3f}, "
              f"t_start = {result.t_start:.3f} s, t_overturn = {result.t_overturn:.3f} s")


def main(argv=None):
    parser = argparse.ArgumentParser(description="Target vs achieved table acceleration, with and without pitch.")
    parser.add_argument("--outdir", type=Path, default=None,
                        help="directory for the PNG files (default: a temporary folder)")
    parser.add_argument("--docs-figure", type=Path, default=None,
                        help="also write both one-second windows side by side to this PNG")
    args = parser.parse_args(argv)
    args.outdir = args.outdir or Path(tempfile.mkdtemp(prefix="shaketable-table-"))
    args.outdir.mkdir(parents=True, exist_ok=True)
    pitch = Pitch(seed=1)
    actuator = Actuator()
    print(f"pitch: {pitch.frequency} Hz, {pitch.amplitude} rad/s^2, phase "
          f"{pitch.realised_phase():.3f} rad; angle amplitude {pitch.angle_amplitude:.2e} rad, "
          f"g sin(phi) up to {G * np.sin(pitch.angle_amplitude):.2e} m/s^2")
    for name, (motion, highpass, zoom) in CASES.items():
        run_case(name, motion, highpass, zoom, args.outdir, pitch, actuator)
    docs_figure(args.docs_figure, pitch, actuator)


if __name__ == "__main__":
    main()
