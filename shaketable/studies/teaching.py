"""A gallery for a class: four lessons of rocking, each closed forms against the engine.

Every function returns a frozen result object with the numbers (``to_frame()``)
and a figure (``plot()``, drawn by :mod:`shaketable.plots.teaching`):

* :func:`period_amplitude` -- the free-rocking period grows with the amplitude
  (Eq. (2-5) and the exact period of Eq. (2-3)), unlike a linear oscillator.
* :func:`cor_sweep` -- a lower coefficient of restitution can *raise* the peak
  response (Section 4.3 (3), Figs. 4.13-4.14).
* :func:`similar_blocks` -- geometrically similar blocks: the larger survives
  (Section 2.4 (1), Tables 4.2-4.3), and the scaling law behind it.
* :func:`rocking_onset` -- rocking starts at a lower horizontal acceleration
  while the ground accelerates downward (Eq. (2-1)).

:data:`ITEMS` maps the names used by scenes (``[study] kind = "teaching"``) to
these functions.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from shaketable.core import theory
from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.models.api import simulate

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["ITEMS", "CorSweep", "PeriodAmplitude", "RockingOnset", "SimilarBlocks",
           "cor_sweep", "period_amplitude", "rocking_onset", "run_item", "similar_blocks",
           "time_stretched"]


def _block(name: str, value: Block | str) -> Block:
    if isinstance(value, str):
        return Block.parse(value)
    if not isinstance(value, Block):
        raise ValueError(f"{name} must be a shaketable.Block or a size such as '36x9in', "
                         f"got {value!r}")
    return value


def _record(name: str, value: Motion | str) -> Motion:
    if isinstance(value, str):
        from shaketable.ground import records

        return records.load(value)
    if not isinstance(value, Motion):
        raise ValueError(f"{name} must be a shaketable.Motion or a bundled record name, "
                         f"got {value!r}")
    return value


def _ratios(name: str, values: npt.ArrayLike, low: float, high: float) -> np.ndarray:
    array = np.asarray(values, dtype=float).ravel()
    if array.size == 0 or not np.all((array > low) & (array < high)):
        raise ValueError(f"{name} must be numbers strictly between {low:g} and {high:g}, "
                         f"got {values!r}")
    return array


@dataclass(frozen=True)
class PeriodAmplitude:
    """Free-rocking period against amplitude, closed forms and engine.

    Attributes
    ----------
    block : Block
    amplitude_ratios : ndarray
        Release amplitudes theta0/alpha [-].
    housner_period : ndarray
        Eq. (2-5), slender-block approximation [s].
    exact_period : ndarray
        Exact period of Eq. (2-3) by quadrature of the energy integral [s].
    engine_period : ndarray
        Engine (COR 1, released at rest): 4 x the time from release to the
        first impact, which is a quarter period [s].
    engine_half_period : ndarray
        Engine: time between the first and second impacts, half a period [s].
    linear_period : float
        Period of the linear oscillator matched to the exact rocking period at
        ``reference_ratio`` [s]; a linear oscillator has it at every amplitude.
    reference_ratio : float
        theta0/alpha where the linear oscillator is matched [-].
    """

    block: Block
    amplitude_ratios: np.ndarray
    housner_period: np.ndarray
    exact_period: np.ndarray
    engine_period: np.ndarray
    engine_half_period: np.ndarray
    linear_period: float
    reference_ratio: float

    def to_frame(self) -> pd.DataFrame:
        """One row per amplitude, units in the column names."""
        import pandas as pd

        return pd.DataFrame({
            "theta0/alpha [-]": self.amplitude_ratios,
            "Eq. 2-5 period [s]": self.housner_period,
            "exact period [s]": self.exact_period,
            "engine period (4 x first quarter) [s]": self.engine_period,
            "engine 2 x (t2 - t1) [s]": 2 * self.engine_half_period,
            "linear oscillator period [s]": np.full(self.amplitude_ratios.size,
                                                    self.linear_period),
        })

    def highlights(self) -> list[str]:
        """The numbers a class should take away, as sentences."""
        ratios = self.amplitude_ratios
        first, last = 0, len(ratios) - 1
        error = np.max(np.abs(self.engine_period / self.exact_period - 1))
        slender = np.max(np.abs(self.housner_period / self.exact_period - 1))
        return [
            f"{self.block.describe()} block (alpha = {self.block.alpha:.3f} rad, p = "
            f"{self.block.p:.2f} rad/s): the exact period grows from "
            f"{self.exact_period[first]:.3f} s at theta0/alpha = {ratios[first]:g} to "
            f"{self.exact_period[last]:.3f} s at {ratios[last]:g} "
            f"({self.exact_period[last] / self.exact_period[first]:.1f} times).",
            f"Eq. 2-5 is within {100 * slender:.2f} % of the exact period; the engine "
            f"(4 x the quarter period) within {error:.1e} of it.",
            f"A linear oscillator matched at theta0/alpha = {self.reference_ratio:g} keeps "
            f"T = {self.linear_period:.3f} s at every amplitude.",
        ]

    def plot(self, ax: Axes | None = None) -> Axes:
        """Period against amplitude; see :func:`shaketable.plots.teaching.plot_period_amplitude`."""
        from shaketable.plots.teaching import plot_period_amplitude

        return plot_period_amplitude(self, ax=ax)


def period_amplitude(block: Block | str = "36x9in", amplitude_ratios: npt.ArrayLike | None = None, *,
                     reference_ratio: float = 0.5) -> PeriodAmplitude:
    """The period of free rocking grows with the amplitude (Section 2.2, Fig. 2.3).

    Eq. (2-5) of [1]_, ``T = (4/p) arccosh(1 / (1 - theta0/alpha))``, goes from
    zero at small amplitude to infinity at theta0 = alpha: a rocking block has
    no natural period. The engine releases the block at rest from theta0 with
    COR 1; the first impact comes a quarter period later.

    Parameters
    ----------
    block : Block or str
        Default the 36 x 9 in block of Table 3.1.
    amplitude_ratios : array_like, optional
        theta0/alpha [-], each in (0, 1); default 0.05 ... 0.95.
    reference_ratio : float
        theta0/alpha [-] at which the linear oscillator's period equals the
        exact rocking period.

    Returns
    -------
    PeriodAmplitude
    """
    block = _block("block", block)
    ratios = _ratios("amplitude_ratios",
                     np.linspace(0.05, 0.95, 19) if amplitude_ratios is None
                     else amplitude_ratios, 0.0, 1.0)
    reference_ratio = float(_ratios("reference_ratio", reference_ratio, 0.0, 1.0)[0])
    housner, exact, engine, half = [], [], [], []
    for ratio in ratios:
        amplitude = ratio * block.alpha
        period = theory.exact_period(block, amplitude)
        housner.append(theory.housner_period(block, amplitude))   # Eq. (2-5)
        exact.append(period)
        run = simulate(block, cor=1.0, theta0=amplitude, duration=0.8 * period,
                       output_dt=period / 40)
        engine.append(4.0 * run.impact_times[0])                   # quarter period x 4
        half.append(run.impact_times[1] - run.impact_times[0])     # half period
    return PeriodAmplitude(
        block=block, amplitude_ratios=ratios, housner_period=np.array(housner),
        exact_period=np.array(exact), engine_period=np.array(engine),
        engine_half_period=np.array(half),
        linear_period=theory.exact_period(block, reference_ratio * block.alpha),
        reference_ratio=reference_ratio)


@dataclass(frozen=True)
class CorSweep:
    """Peak response against the coefficient of restitution under one record.

    Attributes
    ----------
    block : Block
    motion_name : str
    cors : ndarray
        Coefficients of restitution [-], decreasing from the first.
    max_theta_ratio : ndarray
        max |theta| / alpha [-] of each run (NaN where the block overturned).
    overturned : ndarray of bool
    histories : dict
        COR -> (t [s], theta/alpha [-]) for the runs drawn in the figure: the
        highest COR and the COR of the largest response.
    report_points : tuple
        The report's (COR, max theta/alpha) for this block and record, if any
        (Tables 4.2-4.3 / Figs. 4.13-4.14: 6 x 2 ft under S74W).
    """

    block: Block
    motion_name: str
    cors: np.ndarray
    max_theta_ratio: np.ndarray
    overturned: np.ndarray
    histories: dict[float, tuple[np.ndarray, np.ndarray]]
    report_points: tuple[tuple[float, float], ...] = ()

    @property
    def worst_cor(self) -> float:
        """The COR with the largest response [-] (an overturn counts as largest)."""
        score = np.where(self.overturned, np.inf, self.max_theta_ratio)
        return float(self.cors[int(np.argmax(score))])

    @property
    def rises_when_cor_drops(self) -> bool:
        """True when some lower COR gives a larger peak than the highest COR."""
        first = np.inf if self.overturned[0] else self.max_theta_ratio[0]
        later = np.where(self.overturned[1:], np.inf, self.max_theta_ratio[1:])
        return bool(np.any(later > first))

    def to_frame(self) -> pd.DataFrame:
        """One row per COR."""
        import pandas as pd

        return pd.DataFrame({"cor [-]": self.cors,
                             "max theta/alpha [-]": self.max_theta_ratio,
                             "overturned": self.overturned})

    def highlights(self) -> list[str]:
        """The numbers a class should take away, as sentences."""
        first = "F" if self.overturned[0] else f"{self.max_theta_ratio[0]:.3f}"
        index = int(np.flatnonzero(self.cors == self.worst_cor)[0])
        worst = "F" if self.overturned[index] else f"{self.max_theta_ratio[index]:.3f}"
        lines = [f"{self.block.describe()} block, {self.motion_name}: max θ/α = "
                 f"{first} at COR {self.cors[0]:g} but {worst} at COR {self.worst_cor:g}.",
                 f"Over COR {self.cors[-1]:g}-{self.cors[0]:g} the peak rises "
                 f"{int(np.sum(np.diff(self.max_theta_ratio) > 0))} times and falls "
                 f"{int(np.sum(np.diff(self.max_theta_ratio) < 0))} times as COR drops: "
                 "not monotonic."]
        if self.report_points:
            lines.append("The report (Tables 4.2-4.3, its own digitisation of the record): " +
                         ", ".join(f"{ratio:g} at COR {cor:g}" for cor, ratio
                                   in self.report_points) + ".")
        return lines

    def plot(self, fig: Figure | None = None) -> Figure:
        """Sweep and two time histories; see :func:`shaketable.plots.teaching.plot_cor_sweep`."""
        from shaketable.plots.teaching import plot_cor_sweep

        return plot_cor_sweep(self, fig=fig)


#: Tables 4.2 (COR 1.0) and 4.3 (COR 0.90) for the 6 x 2 ft block under Pacoima Dam S74W,
#: the case of Figs. 4.13-4.14 and Section 4.3 (3).
_REPORT_6X2_S74W = ((1.0, 0.38), (0.90, 0.58))


def cor_sweep(block: Block | str = "6x2ft", motion: Motion | str = "pacoima-dam-s74w",
              cors: npt.ArrayLike | None = None) -> CorSweep:
    """Max theta/alpha against COR: a lower COR can raise the peak (Section 4.3 (3)).

    "The response of a rocking block actually may increase with a reduction in
    nu (which is equivalent to an increase in damping)" -- Section 4.3 (3) of
    [1]_, shown there with the 6 x 2 ft block under Pacoima Dam S74W (Figs.
    4.13-4.14). The period depends on the amplitude, so a slightly different
    energy loss puts the block in a different phase with the next strong
    pulses of the record.

    Parameters
    ----------
    block : Block or str
        Default 6 x 2 ft (Figs. 4.13-4.14).
    motion : Motion or str
        Ground motion or a bundled record name; default Pacoima Dam S74W
        with the recorded vertical.
    cors : array_like, optional
        COR values [-] in (0, 1], sorted here from high to low; default 1.00
        down to 0.70 by 0.01.

    Returns
    -------
    CorSweep
    """
    block = _block("block", block)
    motion = _record("motion", motion)
    cors = np.asarray(np.round(np.arange(1.0, 0.695, -0.01), 2) if cors is None else cors,
                      dtype=float).ravel()
    if cors.size < 2 or not np.all((cors > 0) & (cors <= 1)):
        raise ValueError(f"cors must be at least two numbers in (0, 1], got {cors!r}")
    cors = np.sort(cors)[::-1]
    runs = [simulate(block, motion, cor=float(cor)) for cor in cors]
    overturned = np.array([run.overturned for run in runs])
    peaks = np.array([np.nan if run.overturned else run.max_theta_ratio for run in runs])
    sweep = CorSweep(block=block, motion_name=motion.name, cors=cors, max_theta_ratio=peaks,
                     overturned=overturned, histories={})
    shown = {}
    for cor in (float(cors[0]), sweep.worst_cor):
        run = runs[int(np.flatnonzero(cors == cor)[0])]
        shown[cor] = (run.t, run.theta / block.alpha)
    report = (_REPORT_6X2_S74W if motion.name.lower().find("s74w") >= 0
              and abs(block.height - Block.from_feet(6, 2).height) < 1e-9
              and abs(block.width - Block.from_feet(6, 2).width) < 1e-9 else ())
    return CorSweep(block=block, motion_name=motion.name, cors=cors, max_theta_ratio=peaks,
                    overturned=overturned, histories=shown, report_points=report)


# ---------------------------------------------------------------- (c) similar blocks
def time_stretched(motion: Motion, factor: float) -> Motion:
    """The same accelerations played ``factor`` times slower: a(t / factor) [m/s^2].

    The samples are unchanged and every time is multiplied by ``factor``
    (> 0): the input of the scaling law of :func:`similar_blocks`.
    """
    if not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable.Motion, got {type(motion).__name__}")
    factor = float(factor)
    if not (math.isfinite(factor) and factor > 0):
        raise ValueError(f"factor must be a positive number, got {factor!r}")
    return Motion(motion.t * factor, motion.horizontal, motion.vertical,
                  name=f"{motion.name} (time x {factor:.4g})", rotation=motion.rotation)


@dataclass(frozen=True)
class SimilarBlocks:
    """Geometrically similar blocks under one record, and the scaling law.

    Attributes
    ----------
    aspect_ratio : float
        H/B of every block [-].
    heights : ndarray
        Block heights H [m].
    cor : float
    motion_name : str
    max_theta_ratio : ndarray
        max |theta| / alpha [-] (NaN where the block overturned).
    overturned : ndarray of bool
    scaling_blocks : tuple of Block
        The small block and the block ``scale`` times larger.
    scale : float
        Length ratio lambda of the two blocks [-]; the larger one's record is
        played sqrt(lambda) times slower.
    scaling_pt : ndarray
        Dimensionless time p t [-] at the small block's output samples.
    scaling_theta_small, scaling_theta_large : ndarray
        theta [rad] of the small block at t and of the large block at
        sqrt(lambda) t (the same p t).
    """

    aspect_ratio: float
    heights: np.ndarray
    cor: float
    motion_name: str
    max_theta_ratio: np.ndarray
    overturned: np.ndarray
    scaling_blocks: tuple[Block, Block]
    scale: float
    scaling_pt: np.ndarray
    scaling_theta_small: np.ndarray
    scaling_theta_large: np.ndarray

    @property
    def scaling_difference(self) -> float:
        """max |theta_large(sqrt(lambda) t) - theta_small(t)| / max |theta_small| [-]."""
        return float(np.max(np.abs(self.scaling_theta_large - self.scaling_theta_small))
                     / np.max(np.abs(self.scaling_theta_small)))

    def to_frame(self) -> pd.DataFrame:
        """One row per block size."""
        import pandas as pd

        foot = Block.from_feet(1, 1).height
        return pd.DataFrame({"height [ft]": self.heights / foot,
                             "width [ft]": self.heights / self.aspect_ratio / foot,
                             "height [m]": self.heights,
                             "max theta/alpha [-]": self.max_theta_ratio,
                             "overturned": self.overturned})

    def highlights(self) -> list[str]:
        """The numbers a class should take away, as sentences."""
        foot = Block.from_feet(1, 1).height
        cells = [f"{height / foot:g} ft: " + ("F" if fell else f"{ratio:.2f}")
                 for height, ratio, fell in zip(self.heights, self.max_theta_ratio,
                                                self.overturned)]
        small, large = self.scaling_blocks
        return [f"H/B = {self.aspect_ratio:g}, {self.motion_name}, COR {self.cor:g}: "
                + ", ".join(cells) + ".",
                f"Scaling law: {large.height / foot:g} ft block under the record slowed "
                f"sqrt({self.scale:g}) = {math.sqrt(self.scale):.4f} times against the "
                f"{small.height / foot:g} ft block under the record: theta(p t) differs by "
                f"{self.scaling_difference:.1e} of the peak (solver tolerance)."]

    def plot(self, fig: Figure | None = None) -> Figure:
        """Response vs size and the scaling law; see
        :func:`shaketable.plots.teaching.plot_similar_blocks`."""
        from shaketable.plots.teaching import plot_similar_blocks

        return plot_similar_blocks(self, fig=fig)


def similar_blocks(aspect_ratio: float = 5.0, heights_ft: npt.ArrayLike | None = None,
                   motion: Motion | str = "pacoima-dam-s74w", *, cor: float = 0.9,
                   scaling_pair: tuple[float, float] = (10.0, 15.0)) -> SimilarBlocks:
    """Similar blocks (same alpha): the larger one rocks less (Section 2.4 (1)).

    In the time tau = p t, Eq. (2-13) of [1]_ divided by (4/3) R^2 p^2 reads
    ``theta'' = [u(tau) (cos alpha cos theta ...) - (g + v)(...)] / (g ...)``:
    it depends on alpha and on the ground accelerations in g as functions of
    p t only. Two similar blocks with sizes R and lambda R (p and
    p / sqrt(lambda)) therefore move identically when the larger one's record
    is played sqrt(lambda) times slower: ``theta_large(sqrt(lambda) t) =
    theta_small(t)``. Under the *same* record the larger block sees the
    record's pulses as shorter (relative to its 1/p) and, by Eq. (2-10), needs
    a larger amplitude x duration to overturn: it survives, "although ... the
    exact mathematical relationship does not hold under arbitrary ground
    motion" (Section 4.3 (1)).

    Parameters
    ----------
    aspect_ratio : float
        H/B of every block [-]; default 5 (10 x 2 ft and 15 x 3 ft, the pair of
        Section 4.3 (1)).
    heights_ft : array_like, optional
        Heights [ft]; default 2, 3, 4, 6, 8, 10, 12, 15, 20.
    motion : Motion or str
        Default Pacoima Dam S74W with the recorded vertical.
    cor : float
        Coefficient of restitution [-]; default 0.9 (Table 4.3).
    scaling_pair : (float, float)
        Heights [ft] of the two blocks of the scaling-law check.

    Returns
    -------
    SimilarBlocks
    """
    aspect_ratio = float(aspect_ratio)
    if not (math.isfinite(aspect_ratio) and aspect_ratio > 0):
        raise ValueError(f"aspect_ratio must be a positive number (H/B), got {aspect_ratio!r}")
    motion = _record("motion", motion)
    heights_ft = np.asarray([2, 3, 4, 6, 8, 10, 12, 15, 20] if heights_ft is None
                            else heights_ft, dtype=float).ravel()
    if heights_ft.size == 0 or not np.all(heights_ft > 0):
        raise ValueError(f"heights_ft must be positive heights [ft], got {heights_ft!r}")
    small_ft, large_ft = (float(value) for value in scaling_pair)
    if not 0 < small_ft < large_ft:
        raise ValueError(f"scaling_pair must be two heights [ft], smaller first, "
                         f"got {scaling_pair!r}")
    blocks = [Block.from_feet(height, height / aspect_ratio) for height in heights_ft]
    runs = [simulate(block, motion, cor=cor) for block in blocks]
    small = Block.from_feet(small_ft, small_ft / aspect_ratio)
    large = Block.from_feet(large_ft, large_ft / aspect_ratio)
    scale = large.R / small.R
    run_small = simulate(small, motion, cor=cor)
    run_large = simulate(large, time_stretched(motion, math.sqrt(scale)), cor=cor)
    count = min(run_small.t.size, run_large.t.size)   # same samples, t_large = sqrt(scale) t
    return SimilarBlocks(
        aspect_ratio=aspect_ratio, heights=np.array([block.height for block in blocks]),
        cor=float(cor), motion_name=motion.name,
        max_theta_ratio=np.array([np.nan if run.overturned else run.max_theta_ratio
                                  for run in runs]),
        overturned=np.array([run.overturned for run in runs]),
        scaling_blocks=(small, large), scale=scale,
        scaling_pt=small.p * run_small.t[:count],
        scaling_theta_small=run_small.theta[:count],
        scaling_theta_large=run_large.theta[:count])


@dataclass(frozen=True)
class RockingOnset:
    """Horizontal acceleration that starts rocking against the vertical acceleration.

    Attributes
    ----------
    block : Block
    vertical_g : ndarray
        Constant vertical table acceleration [g], positive up.
    eq_2_1_g : ndarray
        Eq. (2-1): (B/H)(1 + v/g) [g].
    engine_onset_g : ndarray
        Horizontal acceleration [g] at the engine's first uplift under a slow
        horizontal ramp with that vertical acceleration.
    ramp_rate_g : float
        Slope of the horizontal ramp [g/s].
    harmonic_horizontal_g, harmonic_vertical_g, harmonic_frequency : float
        The harmonic demonstration: horizontal amplitude below the at-rest
        threshold [g], vertical amplitude [g], frequency [Hz].
    harmonic_t : ndarray
        Time [s] of the demonstration.
    theta_without_vertical, theta_with_vertical : ndarray
        theta/alpha [-] with the horizontal alone and with the vertical added.
    t_start_with_vertical : float
        First uplift with the vertical added [s] (NaN if none).
    """

    block: Block
    vertical_g: np.ndarray
    eq_2_1_g: np.ndarray
    engine_onset_g: np.ndarray
    ramp_rate_g: float
    harmonic_horizontal_g: float
    harmonic_vertical_g: float
    harmonic_frequency: float
    harmonic_t: np.ndarray
    theta_without_vertical: np.ndarray
    theta_with_vertical: np.ndarray
    t_start_with_vertical: float

    def to_frame(self) -> pd.DataFrame:
        """One row per vertical acceleration."""
        import pandas as pd

        return pd.DataFrame({"vertical [g]": self.vertical_g,
                             "Eq. 2-1 threshold [g]": self.eq_2_1_g,
                             "engine onset [g]": self.engine_onset_g,
                             "engine / Eq. 2-1 [-]": self.engine_onset_g / self.eq_2_1_g})

    def highlights(self) -> list[str]:
        """The numbers a class should take away, as sentences."""
        ratio = self.block.width / self.block.height
        rest = int(np.argmin(np.abs(self.vertical_g)))
        low = int(np.argmin(self.vertical_g))
        error = np.nanmax(np.abs(self.engine_onset_g / self.eq_2_1_g - 1))
        start = (f"rocks from {self.t_start_with_vertical:.2f} s, max |theta|/alpha = "
                 f"{np.max(np.abs(self.theta_with_vertical)):.2f}"
                 if math.isfinite(self.t_start_with_vertical) else "does not rock")
        return [f"{self.block.describe()} block (B/H = {ratio:.3f}): rocking starts at "
                f"{self.engine_onset_g[rest]:.3f} g with v = {self.vertical_g[rest]:+g} g "
                f"and at {self.engine_onset_g[low]:.3f} g with v = {self.vertical_g[low]:+g} g "
                f"(Eq. 2-1: {self.eq_2_1_g[rest]:.3f} g and {self.eq_2_1_g[low]:.3f} g; "
                f"largest relative difference {error:.1e}).",
                f"{self.harmonic_frequency:g} Hz, {self.harmonic_horizontal_g:g} g horizontal "
                f"alone: max |theta| = {np.max(np.abs(self.theta_without_vertical)):.2g} "
                f"alpha; with {self.harmonic_vertical_g:g} g vertical: {start}."]

    def plot(self, fig: Figure | None = None) -> Figure:
        """Threshold line and the harmonic demonstration; see
        :func:`shaketable.plots.teaching.plot_rocking_onset`."""
        from shaketable.plots.teaching import plot_rocking_onset

        return plot_rocking_onset(self, fig=fig)


def rocking_onset(block: Block | str = "30x6in", vertical_g: npt.ArrayLike | None = None, *,
                  ramp_rate_g: float = 0.5,
                  dt: float = 0.002, harmonic_horizontal_g: float = 0.18,
                  harmonic_vertical_g: float = 0.3, harmonic_frequency: float = 2.0,
                  harmonic_duration: float = 3.0) -> RockingOnset:
    """Rocking starts earlier while the ground accelerates downward (Eq. (2-1)).

    Uplift needs ``M u h > M (g + v) b``, i.e. ``u > (B/H)(g + v)``
    (Eq. (2-1) of [1]_): a downward table acceleration (v < 0) lowers the
    effective gravity and with it the threshold. The engine is driven by a
    slow horizontal ramp ``u = ramp_rate t`` on a table accelerating
    vertically at a constant ``v`` and the horizontal acceleration at its
    first uplift is read off. A harmonic demonstration follows: a horizontal
    amplitude below the at-rest threshold does nothing alone and rocks the
    block once a vertical motion is added.

    Parameters
    ----------
    block : Block or str
        Default the 30 x 6 in block (B/H = 0.2).
    vertical_g : array_like, optional
        Vertical accelerations [g], each above -1 (the block would leave the
        ground); default -0.6 ... 0.6.
    ramp_rate_g : float
        Slope of the horizontal ramp [g/s], positive.
    dt : float
        Sample interval of the ramp [s].
    harmonic_horizontal_g, harmonic_vertical_g : float
        Amplitudes of the demonstration [g].
    harmonic_frequency : float
        Its frequency [Hz] (both components, in phase).
    harmonic_duration : float
        Its length [s].

    Returns
    -------
    RockingOnset
    """
    block = _block("block", block)
    vertical_g = np.asarray(np.linspace(-0.6, 0.6, 13) if vertical_g is None else vertical_g,
                            dtype=float).ravel()
    if vertical_g.size == 0 or not np.all(vertical_g > -1.0):
        raise ValueError(f"vertical_g must be accelerations above -1 g, got {vertical_g!r}")
    ramp_rate_g = float(ramp_rate_g)
    if not (math.isfinite(ramp_rate_g) and ramp_rate_g > 0):
        raise ValueError(f"ramp_rate_g must be a positive slope [g/s], got {ramp_rate_g!r}")
    ratio = block.width / block.height
    thresholds = ratio * (1.0 + vertical_g)                          # Eq. (2-1) [g]
    onsets = []
    for vertical, threshold in zip(vertical_g, thresholds):
        duration = 1.5 * threshold / ramp_rate_g                     # the ramp passes it
        t = dt * np.arange(int(math.ceil(duration / dt)) + 1)
        motion = Motion(t, ramp_rate_g * G * t, np.full(t.size, vertical * G),
                        name=f"ramp {ramp_rate_g:g} g/s, vertical {vertical:+.2f} g")
        run = simulate(block, motion, cor=1.0)
        onsets.append(ramp_rate_g * run.t_start if math.isfinite(run.t_start) else np.nan)

    from shaketable.ground.generators import harmonic

    alone = harmonic(harmonic_frequency, horizontal=harmonic_horizontal_g * G,
                     duration=harmonic_duration, dt=0.002)
    both = harmonic(harmonic_frequency, horizontal=harmonic_horizontal_g * G,
                    vertical=harmonic_vertical_g * G, duration=harmonic_duration, dt=0.002)
    run_alone = simulate(block, alone, cor=0.9)
    run_both = simulate(block, both, cor=0.9)
    count = min(run_alone.t.size, run_both.t.size)
    return RockingOnset(
        block=block, vertical_g=vertical_g, eq_2_1_g=thresholds,
        engine_onset_g=np.array(onsets), ramp_rate_g=ramp_rate_g,
        harmonic_horizontal_g=float(harmonic_horizontal_g),
        harmonic_vertical_g=float(harmonic_vertical_g),
        harmonic_frequency=float(harmonic_frequency), harmonic_t=run_both.t[:count],
        theta_without_vertical=run_alone.theta[:count] / block.alpha,
        theta_with_vertical=run_both.theta[:count] / block.alpha,
        t_start_with_vertical=float(run_both.t_start))


# ---------------------------------------------------------------- registry
#: What a gallery item returns.
TeachingItem = PeriodAmplitude | CorSweep | SimilarBlocks | RockingOnset

#: Gallery items by the name a ``[study] kind = "teaching"`` scene gives.
ITEMS: dict[str, Callable[[], TeachingItem]] = {
    "period-amplitude": period_amplitude,
    "cor-sweep": cor_sweep,
    "similar-blocks": similar_blocks,
    "rocking-onset": rocking_onset,
}


def run_item(name: str) -> TeachingItem:
    """Run one gallery item with its defaults by name (one of :data:`ITEMS`)."""
    if name not in ITEMS:
        raise ValueError(f"unknown teaching item {name!r}; expected one of {sorted(ITEMS)}")
    return ITEMS[name]()


def _list(values, unit: str = "") -> str:
    """``"2, 3 and 4 ft"``: numbers in a sentence."""
    words = [f"{value:g}" for value in values]
    text = words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]
    return f"{text}{unit}"


def teaching_answer(item: str, frame: pd.DataFrame) -> str:
    """The lesson of gallery item ``item`` (one of :data:`ITEMS`) in one line, with its
    numbers read from the table it wrote (``to_frame()``, i.e. numbers.csv): what a class
    checks first, before the description; "" for an item registered from outside. The
    lesson is stated only where the numbers show it; otherwise the line gives the numbers
    alone (a table of other inputs need not teach the gallery's lesson)."""
    if item == "similar-blocks":
        fell = frame["overturned"].to_numpy(bool)
        heights = frame["height [ft]"].to_numpy(float)
        ratio = float(np.median(frame["height [ft]"] / frame["width [ft]"]))
        parts = []
        if fell.any():
            parts.append(f"{_list(heights[fell], ' ft')} overturn")
        if (~fell).any():
            peaks = ", ".join(f"{value:.2f}" for value in frame["max theta/alpha [-]"][~fell])
            parts.append(f"{_list(heights[~fell], ' ft')} survive (max θ/α {peaks})")
        return f"similar blocks of H/B = {ratio:g}: " + "; ".join(parts)
    if item == "cor-sweep":
        return _cor_sweep_answer(frame)
    if item == "period-amplitude":
        return _period_answer(frame)
    if item == "rocking-onset":
        return _onset_answer(frame)
    return ""


def _cor_sweep_answer(frame: pd.DataFrame) -> str:
    """``"max θ/α = 0.200 at COR 1 but F (overturns) at COR 0.9: a lower COR can raise the
    peak"`` when a lower COR than the highest gave a larger peak (or an overturn); else
    each COR's peak."""
    cors = frame["cor [-]"].to_numpy(float)
    fell = frame["overturned"].to_numpy(bool)
    peaks = frame["max theta/alpha [-]"].to_numpy(float)
    score = np.where(fell, np.inf, peaks)
    worst, top = int(np.argmax(score)), int(np.argmax(cors))

    def said(index: int) -> str:
        return "F (overturns)" if fell[index] else f"{peaks[index]:.3f}"
    if cors[worst] < cors[top] and score[worst] > score[top]:
        return (f"max θ/α = {said(top)} at COR {cors[top]:g} but {said(worst)} at COR "
                f"{cors[worst]:g}: a lower COR can raise the peak")
    return "max θ/α = " + ", ".join(f"{said(k)} at COR {cors[k]:g}"
                                    for k in np.argsort(-cors, kind="stable"))


def _period_answer(frame: pd.DataFrame) -> str:
    """``"the rocking period grows from ... to ..."`` when it grows with the amplitude
    (from each amplitude to the next larger); else the first and last periods."""
    ratios = frame["theta0/alpha [-]"].to_numpy(float)
    period = frame["exact period [s]"].to_numpy(float)
    linear = float(frame["linear oscillator period [s]"].iloc[0])
    order = np.argsort(ratios, kind="stable")
    ratios, period = ratios[order], period[order]
    if ratios.size > 1 and np.all(np.diff(ratios) > 0) and np.all(np.diff(period) > 0):
        return (f"the rocking period grows from {period[0]:.3f} s at θ0/α = {ratios[0]:g} "
                f"to {period[-1]:.3f} s at {ratios[-1]:g} ({period[-1] / period[0]:.1f} "
                f"times); a linear oscillator keeps {linear:.3f} s")
    return (f"the rocking period is {period[0]:.3f} s at θ0/α = {ratios[0]:g} and "
            f"{period[-1]:.3f} s at {ratios[-1]:g}; the linear oscillator's {linear:.3f} s")


def _onset_answer(frame: pd.DataFrame) -> str:
    """``"rocking starts at 0.200 g on a table at rest vertically and at 0.140 g while it
    accelerates downward at 0.3 g (Eq. 2-1)"`` when a table accelerating downward started
    it at a lower acceleration than one at rest vertically; else the onset at the vertical
    nearest zero and at the lowest."""
    vertical = frame["vertical [g]"].to_numpy(float)
    onset = frame["engine onset [g]"].to_numpy(float)
    rest, low = int(np.argmin(np.abs(vertical))), int(np.argmin(vertical))
    if vertical[rest] == 0.0 and vertical[low] < 0.0 and onset[low] < onset[rest]:
        return (f"rocking starts at {onset[rest]:.3f} g on a table at rest vertically and "
                f"at {onset[low]:.3f} g while it accelerates downward at {-vertical[low]:g} "
                "g (Eq. 2-1)")
    rows = dict.fromkeys((rest, low))
    return "rocking starts at " + " and ".join(
        f"{onset[k]:.3f} g at a vertical acceleration of {vertical[k]:+g} g" for k in rows)
