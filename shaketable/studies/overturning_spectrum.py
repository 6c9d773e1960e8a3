"""Overturning spectra of pulses: every overturn/safe band edge, not one threshold.

Section 2.4 of [1]_ gives one amplitude (Eq. 2-8) above which a half-sine
pulse overturns a block. Under other pulses the exact model (Eq. 2-13) has
several bands: under a one-sine pulse the block overturns after one impact
in a lower band, without impact in an upper one, and is safe between them
(Zhang & Makris [2]_). :func:`overturning_spectrum` finds every band edge in
a/(g tan alpha) up to a ceiling, for a list of omega/p.

How a verdict is decided
------------------------
The engine (:func:`shaketable.models.rocking.batch.simulate_cases`, the pulse
sampled by :func:`shaketable.ground.pulses.pulse_motion`) runs **only while
the pulse acts**. After it the table is at rest, the block rocks freely and
its energy per unit I0, E = theta'^2/2 + p^2 (cos(alpha - |theta|) - cos alpha),
is conserved between impacts and multiplied by cor^2 at each (Section 2.7 (5)).
:func:`decide_after_pulse` settles the verdict exactly from the state at the
end of the pulse: the block overturns without a further impact when it moves
outward with E above the barrier p^2 (1 - cos alpha) (or is already past
alpha and cannot return), after one more impact when cor^2 E is above the
barrier, and never otherwise. No run length has to be guessed (the old
12/p tail missed slow overturns near the threshold). The rules, for the exact
and for the linearised model, are written out in :mod:`shaketable.core.fate`.

Methods
-------
``method="fast"`` (default) and ``"predictor-corrector"`` integrate the exact
Eq. (2-13); ``"linear"`` integrates Housner's linearised Eq. (2-4) (uplift at
a = g alpha, runaway past alpha) and decides after the pulse with that model's
energy. Its band edges are those of the closed forms of
:func:`shaketable.core.theory.linear_pulse_bands` (in a/(g alpha), for every
alpha) to the chord-area limit of the sampled pulse, (2 pi / n)^2 / 12
relative for ``samples_per_cycle`` n (4.9e-8 at the default 8192). The
engine stops a linearised run at |theta| = pi/2; that is the linearised
block's runaway exactly when pi/2 > alpha + a/g (true for slender blocks at
the amplitudes of a spectrum).

Scan and bisection
------------------
Amplitudes x = a/(g tan alpha) from 1 (below it the block does not rock) to
``ceiling`` are scanned on a geometric grid of relative step ``scan_step``.
Each scan point gets a class: ``safe`` or ``overturns after n impacts``.
Every neighbouring pair of differing classes is bisected, all brackets of
all omega/p in one batch per round, until its relative width is below
``tolerance`` (default 1e-8); a midpoint whose class differs from both ends
splits the bracket (a band found inside).

How the scan step is chosen: the default, 0.5 % relative, puts about a dozen
scan points across the narrowest band known in these spectra (the one-sine
safe window at omega/p = 4, 5.00928-5.32302, is 6.3 % wide [2]_) at a cost of
about 200 log(ceiling) scan runs per omega/p. A band narrower than the step
is seen only when the verdicts on its two sides differ (the bisection then
finds it); a window narrower than the step between two scan points of the
same verdict is invisible to any scan. Such places are **flagged, not
hidden**: the band table's ``flagged`` column is true and its ``note`` says
why, :attr:`OverturningSpectrum.windows` lists the amplitude intervals
concerned (the figure marks them) and :attr:`OverturningSpectrum.flags`
repeats them in words (also in the CSV header). Three kinds:

* a band narrower than the scan step: found, because the verdicts on its
  two sides differ (bisecting a bracket whose ends differ keeps a band
  lying wholly inside it until a midpoint lands in it), but its like could
  hide between scan points of equal verdict elsewhere: scan finer;
* a change of overturning mode (e.g. after one impact -> without impact)
  with no safe band found between: a safe window narrower than
  ``tolerance`` cannot be excluded at that edge;
* safe scan points that all became unstable (|theta| > alpha) and
  recovered: an overturning window narrower than the step may lie between.

References
----------
.. [1] Aslam, M., Godden, W. G. and Scalise, D. T., "Rocking and overturning
   response of rigid bodies to earthquake motions", LBL-7539, 1978.
.. [2] Zhang, J. and Makris, N., "Rocking response of free-standing blocks
   under cycloidal pulses", J. Eng. Mech. 127(5), 473-483, 2001.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from shaketable.core.constants import G
from shaketable.core.fate import free_rocking_fate
from shaketable.core.geometry import Block
from shaketable.ground.pulses import Pulse, pulse_motion
from shaketable.models.rocking.batch import Case, simulate_cases

__all__ = ["COLUMNS", "METHODS", "WINDOW_COLUMNS", "OverturningSpectrum", "decide_after_pulse", "housner_cor",
           "overturn_verdicts", "overturning_spectrum", "threshold"]

#: Columns of :meth:`OverturningSpectrum.to_frame`.
COLUMNS = ["pulse", "omega/p [-]", "from a/(g tan alpha) [-]", "to a/(g tan alpha) [-]",
           "verdict", "how", "impacts", "flagged", "note"]

#: Columns of :attr:`OverturningSpectrum.windows`: where a window narrower than the scan
#: may hide (amplitudes a/(g tan alpha) [-]).
WINDOW_COLUMNS = ["pulse", "omega/p [-]", "from a/(g tan alpha) [-]",
                  "to a/(g tan alpha) [-]", "reason"]


def housner_cor(block: Block) -> float:
    """Housner's coefficient of restitution 1 - 1.5 sin^2 alpha [-] (angular momentum at impact)."""
    return 1.0 - 1.5 * math.sin(block.alpha) ** 2


def _cor(block, cor):
    if isinstance(cor, str):
        if cor.lower() != "housner":
            raise ValueError(f"cor must be a number in [0, 1] or 'housner', got {cor!r}")
        value = housner_cor(block)
        if not 0.0 <= value <= 1.0:
            raise ValueError(f"cor 'housner' is 1 - 1.5 sin^2 alpha = {value:.4g} for alpha "
                             f"{block.alpha:.4g} rad, below 0 (a block this squat): give the "
                             "COR as a number in [0, 1]")
        return value
    if isinstance(cor, bool) or not isinstance(cor, (int, float)) or not 0.0 <= cor <= 1.0:
        raise ValueError(f"cor must be a number in [0, 1] or 'housner', got {cor!r}")
    return float(cor)


#: Most scan points of one pulse and omega/p (each is a run): a finer scan or a higher
#: ceiling would exhaust memory before the first run.
MAX_SCAN_POINTS = 1_000_000


def decide_after_pulse(theta, theta_dot, alpha: float, p: float, cor: float,
                       model: str = "exact"):
    """Fate of a block rocking freely from (theta, theta_dot) on a table at rest.

    The rules, for the exact and the linearised model, are those of
    :mod:`shaketable.core.fate` (:func:`~shaketable.core.fate.free_rocking_fate`).

    Parameters
    ----------
    theta, theta_dot : array_like
        State at the end of the pulse [rad], [rad/s] (signed theta, Section 2.7).
    alpha, p : float
        Block angle [rad] and frequency parameter [rad/s].
    cor : float
        Coefficient of restitution [-], theta' -> cor theta' at each impact.
    model : {"exact", "linear"}
        Eq. (2-3), or Housner's linearised Eq. (2-4) (the ``linear`` method).

    Returns
    -------
    overturns : ndarray of bool
    impacts : ndarray of int
        Impacts after the pulse before it overturns (0 or 1); for a block that
        does not overturn, 0.
    """
    overturns, impacts, _, _ = free_rocking_fate(theta, theta_dot, alpha, p, cor, model)
    return overturns, impacts


def overturn_verdicts(block: Block, cor, pulses, amplitudes, *, samples_per_cycle: int = 8192,
                      threads=None, method: str = "fast") -> pd.DataFrame:
    """Verdicts for (pulse, a/(g tan alpha)) pairs, one batch run each.

    Parameters
    ----------
    block : Block
    cor : float or "housner"
    pulses : sequence of Pulse
        One per amplitude (the same object may repeat: it is sampled once).
    amplitudes : sequence of float
        a/(g tan alpha) [-], positive.
    method : str
        Solver (:data:`METHODS`): ``"fast"`` and ``"predictor-corrector"`` integrate
        the exact Eq. (2-13), ``"linear"`` Housner's linearised Eq. (2-4); the verdict
        after the pulse uses the energy of the same model.

    Returns
    -------
    pandas.DataFrame
        ``overturns`` (bool), ``impacts`` (total before overturning, or during the
        pulse for a safe block), ``max_theta_ratio [-]`` (during the pulse).
    """
    cor = _cor(block, cor)
    unit = G * math.tan(block.alpha)
    motions = {}
    cases = []
    for shape, x in zip(pulses, amplitudes):
        if shape not in motions:
            motions[shape] = pulse_motion(shape, unit, samples_per_cycle=samples_per_cycle)
        cases.append(Case(block, motions[shape], cor, scale=float(x)))
    frame = simulate_cases(cases, threads=threads, method=_method(method))
    during = frame["overturned"].to_numpy()
    after, extra = decide_after_pulse(frame["theta_end [rad]"].to_numpy(),
                                      frame["theta_dot_end [rad/s]"].to_numpy(), block.alpha,
                                      block.p, cor, _model(method))
    impacts = frame["n_impacts"].to_numpy() + np.where(during, 0, extra)
    return pd.DataFrame({"overturns": during | after, "impacts": impacts,
                         "max_theta_ratio [-]": frame["max_theta_ratio [-]"].to_numpy()})


#: Solvers a spectrum or a threshold can use (``reference`` is one SciPy run at a time).
METHODS = ("fast", "linear", "predictor-corrector")


def _method(method):
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    return method


def _model(method):
    return "linear" if method == "linear" else "exact"


def _classes(verdicts):
    return [int(n) if o else -1 for o, n in zip(verdicts["overturns"], verdicts["impacts"])]


def _how(cls):
    if cls < 0:
        return ""
    return "without impact" if cls == 0 else f"after {cls} impact" + ("s" if cls > 1 else "")


@dataclass
class OverturningSpectrum:
    """Overturn/safe bands of a block under pulses.

    Attributes
    ----------
    block : Block
    cor : float
        Coefficient of restitution used [-].
    bands : pandas.DataFrame
        One row per band, columns :data:`COLUMNS` (amplitudes a/(g tan alpha) [-]).
    scan_step, tolerance, ceiling : float
        Relative scan step [-], relative bracket width of every edge [-],
        largest amplitude examined a/(g tan alpha) [-].
    flags : list of str
        Places where a window narrower than the scan may hide, in words.
    runs : int
        Engine runs used.
    windows : pandas.DataFrame
        The same places as amplitude intervals, columns :data:`WINDOW_COLUMNS`
        (``reason``: ``"band narrower than the scan"``, ``"mode change without
        a safe band"`` or ``"unstable but safe at both ends"``).
    method : str
        Solver of every run (``"linear"``: the linearised model).
    """

    block: Block
    cor: float
    bands: pd.DataFrame
    scan_step: float
    tolerance: float
    ceiling: float
    flags: list = field(default_factory=list)
    runs: int = 0
    windows: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(columns=WINDOW_COLUMNS))
    method: str = "fast"

    def to_frame(self) -> pd.DataFrame:
        """The tidy band table (a copy)."""
        return self.bands.copy()

    def to_csv(self, path) -> None:
        """Write the band table, with a comment header saying how it was made (atomically:
        :func:`shaketable.core.files.write_text`)."""
        from shaketable.core.files import write_text

        header = (f"# overturning spectrum: block {self.block.describe()}, alpha "
                  f"{self.block.alpha:.8g} rad, p {self.block.p:.8g} rad/s, cor "
                  f"{self.cor:.8g}; scan step {self.scan_step:g}, edge tolerance "
                  f"{self.tolerance:g} relative, {self._ceilings()}; "
                  + ("" if self.method == "fast" else f"method {self.method}; ") +
                  "shaketable.studies.overturning_spectrum\n")
        # each flag's why is in its band's note (column note): here only where it is
        flags = "".join(f"# flag: {key}: {words.split(': ')[0]}\n" for key, _, words
                        in (flag.partition(": ") for flag in self.flags))
        if flags:
            flags = ("# flagged places (column flagged; each band's note says why):\n"
                     + flags)
        write_text(path, header + flags + self.bands.to_csv(index=False, float_format="%.9g"))

    def _ceilings(self) -> str:
        """``"ceiling 4.82843 at omega/p = 1, 6.47214 at 2"``: where each omega/p's scan
        stopped (the top of its last band), or ``"ceiling 10"`` when all share one."""
        columns = ("omega/p [-]", "to a/(g tan alpha) [-]")
        if not set(columns) <= set(self.bands.columns):   # no band table (nothing scanned)
            return f"ceiling {self.ceiling:g}"
        tops = self.bands.groupby(columns[0], sort=False)[columns[1]].max()
        if tops.empty or np.ptp(tops.to_numpy()) == 0.0:
            return f"ceiling {self.ceiling:g}"
        return "ceiling " + ", ".join(f"{top:g} at omega/p = {ratio:g}" if k == 0
                                      else f"{top:g} at {ratio:g}"
                                      for k, (ratio, top) in enumerate(tops.items()))

    def edges(self, pulse: str, ratio: float) -> list:
        """Band edges a/(g tan alpha) [-] for one pulse and omega/p, increasing."""
        rows = self.bands[(self.bands["pulse"] == pulse)
                          & np.isclose(self.bands["omega/p [-]"], ratio)]
        return [float(x) for x in rows["from a/(g tan alpha) [-]"].iloc[1:]]

    def minimum(self, pulse: str, ratio: float) -> float:
        """Smallest amplitude a/(g tan alpha) that overturns [-] (inf if none up to the ceiling)."""
        rows = self.bands[(self.bands["pulse"] == pulse)
                          & np.isclose(self.bands["omega/p [-]"], ratio)
                          & (self.bands["verdict"] == "overturns")]
        return float(rows["from a/(g tan alpha) [-]"].min()) if len(rows) else math.inf

    def plot(self, ax=None, **kwargs):
        """Figure in the style of Zhang & Makris (see :mod:`shaketable.plots.spectrum`;
        ``overlay=`` another spectrum, e.g. the linearised one, outlined on it)."""
        from shaketable.plots.spectrum import plot_spectrum

        return plot_spectrum(self, ax=ax, **kwargs)


def _edges(block: Block, cor: float, shapes: list, brackets: list, tolerance: float,
           samples_per_cycle: int, threads, method: str) -> tuple[list, int]:
    """Every bracket of a change of verdict narrowed to ``tolerance`` (relative).

    A bracket is [series index, lo, hi, class lo, class hi] in a/(g tan alpha); each round
    runs the geometric middles of all unfinished brackets in one batch and keeps the halves
    whose ends differ (both, when the middle differs from both ends). Returns the narrow
    brackets and the number of runs made.
    """
    edges: list = []
    runs = 0
    while brackets:
        active = [b for b in brackets if b[2] / b[1] - 1 > tolerance]
        edges += [b for b in brackets if b[2] / b[1] - 1 <= tolerance]
        if not active:
            break
        middles = [math.sqrt(b[1] * b[2]) for b in active]
        result = overturn_verdicts(block, cor, [shapes[b[0]] for b in active], middles,
                                   samples_per_cycle=samples_per_cycle, threads=threads,
                                   method=method)
        runs += len(active)
        brackets = []
        for b, x, c in zip(active, middles, _classes(result)):
            if c == b[3]:
                brackets.append([b[0], x, b[2], c, b[4]])
            elif c == b[4]:
                brackets.append([b[0], b[1], x, b[3], c])
            else:
                brackets.append([b[0], b[1], x, b[3], c])
                brackets.append([b[0], x, b[2], c, b[4]])
    return edges, runs


def check_scan(ratios, scan_step: float, tolerance: float, ceiling: float | None) -> None:
    """Refuse a scan that :func:`overturning_spectrum` cannot run (its parameters of the
    same names), before any work: a command calls it before making its output folder.

    Raises
    ------
    ValueError
        ``scan_step`` outside (0, 1), ``tolerance`` outside (0, scan_step), ``ceiling``
        not above 1, or more than ``MAX_SCAN_POINTS`` scan points per pulse and omega/p.
    """
    if not 0 < scan_step < 1:
        raise ValueError(f"scan_step must be in (0, 1), got {scan_step!r}")
    if not 0 < tolerance < scan_step:
        raise ValueError(f"tolerance must be in (0, scan_step), got {tolerance!r}")
    if ceiling is not None and (isinstance(ceiling, bool) or not isinstance(ceiling, (int, float))
                                or not 1.0 < ceiling < math.inf):
        raise ValueError(f"ceiling must be a number above 1 (the scan starts at a/(g tan alpha) "
                         f"= 1, where rocking starts), got {ceiling!r}")
    tallest = max([ceiling] if ceiling is not None else
                  [2 * math.sqrt(1 + float(ratio) ** 2) + 2 for ratio in ratios] or [2.0])
    scan_points = math.log(tallest) / math.log1p(scan_step)
    if scan_points > MAX_SCAN_POINTS:
        raise ValueError(f"scan_step {scan_step:g} up to a/(g tan alpha) = {tallest:g} makes "
                         f"{scan_points:.3g} scan points per pulse and omega/p; at most "
                         f"{MAX_SCAN_POINTS:,}: a larger scan_step or a lower ceiling")


def overturning_spectrum(block: Block, pulses=("half-sine",), ratios=(1, 2, 3, 4, 6, 8, 10), *,
                         cor="housner", ceiling: float | None = None, scan_step: float = 0.005,
                         tolerance: float = 1e-8, samples_per_cycle: int = 8192,
                         threads=None, method: str = "fast") -> OverturningSpectrum:
    """Every overturn/safe band in a/(g tan alpha) for pulses at several omega/p.

    Parameters
    ----------
    block : Block
        The block (alpha and p matter; :meth:`Block.from_slenderness`).
    pulses : sequence of str
        Pulse kinds (:data:`shaketable.ground.pulses.PULSES`).
    ratios : sequence of float
        omega/p [-].
    cor : float or "housner"
        Coefficient of restitution [-]; "housner" is 1 - 1.5 sin^2 alpha.
    ceiling : float, optional
        Largest a/(g tan alpha) examined [-] (default per omega/p:
        2 sqrt(1 + (omega/p)^2) + 2, twice Eq. 2-8 and more).
    scan_step : float
        Relative step of the scan [-].
    tolerance : float
        Relative width [-] below which a bracket is an edge (its midpoint).
    method : str
        ``"fast"`` (default), ``"predictor-corrector"`` (the exact Eq. 2-13) or
        ``"linear"`` (Housner's linearised Eq. 2-4, the model of the closed forms
        :func:`shaketable.core.theory.linear_pulse_bands`); amplitudes stay in
        a/(g tan alpha) for every method (the linearised literature's a/(g alpha)
        is that times tan(alpha)/alpha).

    Returns
    -------
    OverturningSpectrum
    """
    method = _method(method)
    if isinstance(pulses, str):
        pulses = [pulses]
    check_scan(ratios, scan_step, tolerance, ceiling)
    cor = _cor(block, cor)
    keys, shapes, grids, tops = [], [], [], []
    for kind in pulses:
        for ratio in ratios:
            shape = Pulse(kind, float(ratio) * block.p)
            top = ceiling if ceiling is not None else 2 * math.sqrt(1 + ratio ** 2) + 2
            count = int(math.ceil(math.log(top) / math.log1p(scan_step)))
            keys.append((shape.kind, float(ratio)))
            shapes.append(shape)
            grids.append(np.exp(np.linspace(0.0, math.log(top), count + 1)))
            tops.append(top)
    # scan, every (pulse, ratio) in one batch
    flat_shapes = [shape for shape, grid in zip(shapes, grids) for _ in grid]
    flat_x = np.concatenate(grids)
    verdicts = overturn_verdicts(block, cor, flat_shapes, flat_x,
                                 samples_per_cycle=samples_per_cycle, threads=threads,
                                 method=method)
    runs = len(flat_x)
    classes = _classes(verdicts)
    ratios_theta = verdicts["max_theta_ratio [-]"].to_numpy()
    windows: list = []     # (series index, lo, hi, reason, words)
    brackets = []          # [series index, lo, hi, class lo, class hi]
    start = 0
    for index, grid in enumerate(grids):
        cls = classes[start:start + grid.size]
        theta = ratios_theta[start:start + grid.size]
        for k in range(grid.size - 1):
            if cls[k] != cls[k + 1]:
                brackets.append([index, grid[k], grid[k + 1], cls[k], cls[k + 1]])
            elif cls[k] < 0 and theta[k] > 1 and theta[k + 1] > 1:
                # consecutive such intervals make one window
                if windows and windows[-1][0] == index and windows[-1][2] == grid[k] \
                        and windows[-1][3] == "unstable but safe at both ends":
                    lo = windows.pop()[1]
                else:
                    lo = grid[k]
                windows.append((index, lo, grid[k + 1], "unstable but safe at both ends",
                                f"safe but unstable (|theta| > alpha) at every scan point "
                                f"from {lo:.6g} to {grid[k + 1]:.6g}: an overturning window "
                                "narrower than the scan step cannot be excluded there"))
        start += grid.size
    edges, refining_runs = _edges(block, cor, shapes, brackets, tolerance,
                                  samples_per_cycle, threads, method)
    runs += refining_runs
    step = math.log1p(scan_step)
    rows = []
    for index, key in enumerate(keys):
        found = sorted((e for e in edges if e[0] == index), key=lambda e: e[1])
        points = [1.0] + [0.5 * (e[1] + e[2]) for e in found] + [tops[index]]
        first = classes[sum(g.size for g in grids[:index])]
        band_classes = [first] + [e[4] for e in found]
        for k, cls in enumerate(band_classes):
            notes = []
            if k > 0 and cls >= 0 and band_classes[k - 1] >= 0:
                edge = found[k - 1]
                notes.append(f"mode changes at {points[k]:.9g} with no safe band found: a "
                             f"safe window narrower than {tolerance:g} relative cannot be "
                             "excluded there")
                windows.append((index, edge[1], edge[2], "mode change without a safe band",
                                notes[-1]))
            inner = 0 < k < len(band_classes) - 1
            if inner and math.log(points[k + 1] / points[k]) < step:
                notes.append(f"band narrower than the scan step ({scan_step:g} relative): "
                             "found because the verdicts on its two sides differ; one as "
                             "narrow between scan points of the same verdict would not be "
                             "seen (scan finer)")
                windows.append((index, points[k], points[k + 1], "band narrower than the scan",
                                f"{'overturning' if cls >= 0 else 'safe'} band "
                                f"{points[k]:.9g}-{points[k + 1]:.9g}: {notes[-1]}"))
            for window in windows:
                if (window[0] == index and window[3] == "unstable but safe at both ends"
                        and points[k] <= window[1] < points[k + 1]):
                    notes.append(window[4])
            flagged = bool(notes)
            if k == len(band_classes) - 1:
                notes.append("up to the ceiling")
            rows.append({"pulse": key[0], "omega/p [-]": key[1],
                         "from a/(g tan alpha) [-]": points[k],
                         "to a/(g tan alpha) [-]": points[k + 1],
                         "verdict": "overturns" if cls >= 0 else "safe", "how": _how(cls),
                         "impacts": cls if cls >= 0 else -1, "flagged": flagged,
                         "note": "; ".join(notes)})
    windows.sort(key=lambda w: (w[0], w[1]))
    flags = [f"{keys[w[0]][0]} omega/p={keys[w[0]][1]:g}: {w[4]}" for w in windows]
    window_frame = pd.DataFrame([(keys[w[0]][0], keys[w[0]][1], float(w[1]), float(w[2]), w[3])
                                 for w in windows], columns=WINDOW_COLUMNS)
    return OverturningSpectrum(block, cor, pd.DataFrame(rows, columns=COLUMNS), scan_step,
                               tolerance, float(max(tops)), flags, runs, window_frame, method)


def threshold(block: Block, shape: Pulse, *, cor, low: float, high: float,
              tolerance: float = 1e-9, samples_per_cycle: int = 8192,
              method: str = "fast") -> float:
    """The one amplitude a/(g tan alpha) in [low, high] above which ``shape`` overturns [-].

    For pulses with a **single transition** (safe below, overturning above; the
    half-sine of Fig. 2.6 and Section 4.3 (4)). The assumption is checked, not
    assumed: the bracket is scanned on a 1 % geometric grid first, and a scan
    showing more than one transition (a banded pulse, e.g. a one-sine:
    :func:`overturning_spectrum` finds every edge) raises instead of returning
    one edge of a band. The switch is then bisected to ``tolerance`` relative.
    A safe window narrower than 1 % above the edge is not seen by the scan
    (:func:`overturning_spectrum` flags such places).

    ``method`` is that of :func:`overturning_spectrum` (``"linear"``: the
    linearised model, whose closed forms are
    :func:`shaketable.core.theory.linear_pulse_threshold`).

    Raises
    ------
    ValueError
        ``low`` already overturns, ``high`` does not, or the scan shows more
        than one transition.
    """
    grid = np.exp(np.linspace(math.log(low), math.log(high),
                              int(math.ceil(math.log(high / low) / math.log1p(0.01))) + 1))
    verdicts = overturn_verdicts(block, cor, [shape] * grid.size, grid,
                                 samples_per_cycle=samples_per_cycle,
                                 method=_method(method))["overturns"].to_numpy()
    if verdicts[0] or not verdicts[-1]:
        raise ValueError(f"the bracket [{low:.6g}, {high:.6g}] does not hold the threshold")
    changes = np.flatnonzero(verdicts[1:] != verdicts[:-1])
    if changes.size > 1:
        where = ", ".join(f"{grid[k]:.4g}-{grid[k + 1]:.4g}" for k in changes)
        raise ValueError(f"{shape.kind} at omega = {shape.omega:.6g} rad/s: {changes.size} "
                         f"overturn/safe transitions in [{low:.6g}, {high:.6g}] (near {where}), "
                         "not one threshold; overturning_spectrum gives every band edge")
    k = int(changes[0]) + 1
    lo, hi = grid[k - 1], grid[k]
    while hi / lo - 1 > tolerance:
        middle = math.sqrt(lo * hi)
        if overturn_verdicts(block, cor, [shape], [middle],
                             samples_per_cycle=samples_per_cycle,
                             method=method)["overturns"].iloc[0]:
            hi = middle
        else:
            lo = middle
    return 0.5 * (lo + hi)
