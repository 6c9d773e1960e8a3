"""The result of one stack run (:class:`StackResult`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from shaketable.core.motion import Motion
from shaketable.models.base import ModelResult
from shaketable.models.stack.geometry import Stack

#: The largest friction coefficient F/N a contact is taken to offer [-]: the model does not
#: slide, and a run whose contacts need more (dry stone, steel or concrete give 0.3 to 0.8;
#: 1.0 leaves a margin) is outside its no-slip assumption from that time on.
PLAUSIBLE_FRICTION = 1.0


def pattern_name(pattern) -> str:
    """A contact pattern in words (``(1, 0)`` of two blocks: ``"stack as one body (+)"``)."""
    pattern = tuple(int(s) for s in pattern)
    sign = lambda s: "+" if s > 0 else "-"   # noqa: E731
    if all(s == 0 for s in pattern):
        return "rest"
    if len(pattern) == 1:
        return f"rocking ({sign(pattern[0])})"
    if len(pattern) == 2:
        base, top = pattern
        if top == 0:
            return f"stack as one body ({sign(base)})"
        if base == 0:
            return f"top alone ({sign(top)})"
        if base == top:
            return f"both, same way ({sign(base)})"
        return f"both, opposite ways ({sign(base)}{sign(top)})"
    return "open " + " ".join(f"{j}{sign(s)}" for j, s in enumerate(pattern) if s != 0)


def _first_row(mask: np.ndarray) -> int:
    """The first index along the first axis where ``mask`` has a True value (-1: none):
    one pass over the flattened mask (``any`` along the short trailing axes is slow)."""
    flat = mask.reshape(-1)
    if not flat.size:
        return -1
    first = int(np.argmax(flat))
    return first // (flat.size // mask.shape[0]) if flat[first] else -1


def block_name(i: int, n: int) -> str:
    """Block ``i`` of a stack of ``n`` in words: numbered from 0 at the bottom, "block 0
    (bottom)", "block 1 (top)", "block 1" between (a block alone: "block 0")."""
    if n > 1 and i == 0:
        return "block 0 (bottom)"
    if n > 1 and i == n - 1:
        return f"block {i} (top)"
    return f"block {i}"


def end_state_text(n: int, t_end: float, past_alpha: tuple[int, ...]) -> str:
    """:meth:`StackResult.end_state` of a run still moving at ``t_end`` [s] with the blocks
    ``past_alpha`` beyond their alpha."""
    words = f"still moving at the end of the run (t = {t_end:.2f} s)"
    if past_alpha:
        words += ("; " + ", ".join(block_name(i, n) for i in past_alpha)
                  + " past α (|θ| > α, beyond static stability)")
    return words


#: A column whose every block's peak |θ| stays below this share of its own alpha [-] only
#: touched its uplift threshold (a contact opened by a rotation of rounding size, as an
#: unscaled record just reaching the threshold gives): the verdict says so, not "rocked".
TOUCHED_BELOW = 1e-6


def verdict_text(n: int, status: str, overturned_block: int, t_overturn: float,
                 t_airborne: float, peaks: np.ndarray, alphas: np.ndarray, still_moving: bool,
                 t_end: float, past_alpha: tuple[int, ...]) -> str:
    """:meth:`StackResult.verdict` from a run's numbers: its status, the overturn or airborne
    time [s], each block's peak |θ| [rad] and alpha [rad], whether it was still moving at
    its last output time ``t_end`` [s], and the blocks past their alpha there."""
    if status == "overturned":
        return f"{block_name(overturned_block, n)} overturned at {t_overturn:.2f} s"
    if status == "airborne":
        return (f"a block would leave its support at {t_airborne:.2f} s (outside the "
                "model: the run stops there)")
    if not peaks.any():
        return "stayed at rest"
    values = ", ".join(f"{peak:.3g}" for peak in peaks)
    if np.all(np.asarray(peaks) < TOUCHED_BELOW * np.asarray(alphas)):
        words = (f"touched its uplift threshold (max |θ| {values} rad, bottom to top: under "
                 f"{TOUCHED_BELOW:g} α, no rocking to speak of)")
    else:
        words = f"rocked: max |θ| = {values} rad (bottom to top)"
    return words + ("; " + end_state_text(n, t_end, past_alpha) if still_moving else "")


@dataclass(frozen=True, eq=False)
class StackResult(ModelResult):
    """Time history, events and scalar results of one stack run.

    Attributes
    ----------
    stack : Stack
    motion : Motion
        The table's motion (``Motion.at_rest`` for free rocking).
    impact : str
        ``"plastic"`` or ``"cor"`` (with ``cor``).
    cor : float
        The constant COR of ``impact="cor"`` [-]; NaN with the plastic law.
    t : ndarray, shape (k,)
        Output times [s] (the motion's samples up to the end of the run).
    theta, theta_dot, theta_ddot : ndarray, shape (k, n)
        Each block's absolute rotation [rad], rate [rad/s] and acceleration [rad/s^2]
        (positive: counter-clockwise, the package's sign).
    patterns : ndarray of int8, shape (k, n)
        Each interface's state at the output times: 0 flat, +1/-1 pivoting on the upper
        block's -x/+x corner (interface j is below block j).
    forces : ndarray, shape (k, n, 4)
        Each interface's normal N and tangential F force on the blocks above [N] (along
        the lower surface), and the normal forces at the upper block's -x and +x corners [N].
    work : ndarray, shape (k,)
        Work of the table's inertial forces (-m u'', -m v'') on the blocks since the start
        [J] (integrated with the motion): kinetic plus potential energy change by it
        between impacts.
    events : tuple of dict
        Uplifts, impacts, rests, overturn, airborne, in time order.
    status : str
        ``"completed"``, ``"overturned"`` or ``"airborne"``.
    t_overturn : float
        When an interface's rotation reached pi/2 [s]; NaN if none.
    overturned_block : int
        The block above that interface (-1 if none).
    t_airborne : float
        When g + v'' reached 0 [s] (the run stops); NaN if never.
    n_events : int
        Events counted (all; ``events`` keeps the first ``max_recorded_events``).
    statistics : dict
        Solver work: steps, right-hand-side evaluations.
    """

    stack: Stack
    motion: Motion
    impact: str
    cor: float
    t: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    theta_ddot: np.ndarray
    patterns: np.ndarray
    forces: np.ndarray
    work: np.ndarray
    events: tuple
    status: str
    t_overturn: float
    overturned_block: int
    t_airborne: float
    n_events: int
    statistics: dict = field(default_factory=dict, compare=False)

    # ------------------------------------------------------------------ derived
    @property
    def n_blocks(self) -> int:
        return self.stack.n

    @property
    def friction_demand(self) -> np.ndarray:
        """|F| / N of every interface at the output times [-] (inf where N <= 0)."""
        normal, tangential = self.forces[:, :, 0], np.abs(self.forces[:, :, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(normal > 0.0, tangential / normal, np.inf)

    def block_name(self, i: int) -> str:
        """How the results, the figure and ``docs/stack.md`` name block ``i``: numbered from 0
        at the bottom, "block 0 (bottom)", "block 1 (top)", "block 1" between."""
        return block_name(i, self.n_blocks)

    def t_friction_exceeded(self, mu: float) -> float:
        """First output time some interface needs more friction than ``mu`` [s] (NaN if
        never): the no-sliding assumption fails there."""
        if not (isinstance(mu, (int, float)) and mu >= 0 and math.isfinite(mu)):
            raise ValueError(f"mu must be a finite friction coefficient >= 0, got {mu!r}")
        row = _first_row(self.friction_demand > mu)
        return float(self.t[row]) if row >= 0 else math.nan

    @property
    def t_tension(self) -> float:
        """First output time a contact carries a tensile (negative) normal force [s] (the
        no-flight assumption fails there); NaN if never."""
        tolerance = 1e-9 * self.stack.weight
        row = _first_row(self.forces[:, :, 2:] < -tolerance)
        return float(self.t[row]) if row >= 0 else math.nan

    @property
    def top_corner_excursion(self) -> np.ndarray:
        """Horizontal displacement of the top block's two top corners from rest [m],
        shape (k, 2) (-x corner, +x corner), at the output times (from the corner's place
        at rest, ``X_top +- b_top``, ``X_top`` the top block's centre,
        :attr:`Stack.centres`)."""
        from shaketable.models.stack.physics import Chain, kinematics, rotation

        chain = Chain.of(self.stack)
        top = self.stack.n - 1
        rest = float(self.stack.centres[-1])
        out = np.empty((self.t.size, 2))
        for k in range(self.t.size):
            centroid, _, _ = kinematics(chain, self.theta[k], self.theta_dot[k], self.patterns[k])
            r = rotation(self.theta[k, top])
            for c, side in enumerate((-1.0, 1.0)):
                corner = centroid[top] + r @ np.array([side * chain.b[top], chain.h[top]])
                out[k, c] = corner[0] - side * chain.b[top] - rest
        return out

    @property
    def peak_excursion(self) -> float:
        """Peak |horizontal displacement| of the top block's top corners [m] (at the output
        times): the clearance the stack needs."""
        return float(np.abs(self.top_corner_excursion).max()) if self.t.size else 0.0

    @property
    def still_moving(self) -> bool:
        """Whether the run ended (``status == "completed"``) with some block not at rest
        (a rotation or rate not zero at the last output time): as the single block says,
        "still moving at the end of the run"."""
        if self.status != "completed" or not self.t.size:
            return False
        return bool(np.any(self.theta[-1]) or np.any(self.theta_dot[-1]))

    @property
    def past_alpha_at_end(self) -> tuple[int, ...]:
        """The blocks whose |θ| at the end of a completed run exceeds their own alpha (past
        their static stability: gravity alone no longer pulls them back) [index]."""
        if self.status != "completed" or not self.t.size:
            return ()
        alphas = np.array([block.alpha for block in self.stack.blocks])
        return tuple(int(i) for i in np.flatnonzero(np.abs(self.theta[-1]) > alphas))

    @property
    def t_past_alpha(self) -> float:
        """First output time some block's |θ| exceeds its own alpha [s] (past its static
        stability: the column is falling or about to), NaN if never. The peak friction
        demand and excursion before it are the ones a standing column needs
        (:meth:`peak_before_past_alpha`)."""
        if not self.t.size:
            return math.nan
        alphas = np.array([block.alpha for block in self.stack.blocks])
        row = _first_row(np.abs(self.theta) > alphas)
        return float(self.t[row]) if row >= 0 else math.nan

    def peak_before_past_alpha(self, excursion: np.ndarray | None = None
                               ) -> tuple[float, float]:
        """(peak F/N over the contacts [-], peak top-corner excursion [m]) over the output
        times before :attr:`t_past_alpha` (the whole run when no block passes its alpha):
        what the column needs while it still stands, not while it falls. ``excursion``:
        :attr:`top_corner_excursion` when the caller has it already (it is computed sample
        by sample)."""
        end = self.t.size if math.isnan(self.t_past_alpha) else int(
            np.searchsorted(self.t, self.t_past_alpha))
        if end == 0:
            return 0.0, 0.0
        demand = self.friction_demand[:end]
        finite = demand[np.isfinite(demand)]
        if excursion is None:
            excursion = self.top_corner_excursion
        return ((float(finite.max()) if finite.size else math.nan),
                float(np.abs(excursion[:end]).max()))

    def end_state(self) -> str:
        """How the run ends when the stack is still moving, in the single block's words:
        "still moving at the end of the run (t = 0.60 s); block 0 (bottom), block 1 (top)
        past α (|θ| > α, beyond static stability)"; "" when it ended at rest, overturned
        or stopped early."""
        if not self.still_moving:
            return ""
        return end_state_text(self.n_blocks, float(self.t[-1]), self.past_alpha_at_end)

    def verdict(self) -> str:
        """The run in words, as the other models' results say it: "block 0 (bottom) overturned
        at 3.99 s" (blocks numbered from 0 at the bottom, :meth:`block_name`), "rocked:
        max |θ| = 0.012, 0.030 rad (bottom to top)" (followed by :meth:`end_state` when
        the run ends with the stack still moving; "touched its uplift threshold" when every
        block stayed under :data:`TOUCHED_BELOW` of its alpha), "stayed at rest", or
        the time a block would leave its support (outside the model: the run stops there)."""
        peaks = np.abs(self.theta).max(axis=0) if self.t.size else np.zeros(self.n_blocks)
        return verdict_text(self.n_blocks, self.status, self.overturned_block, self.t_overturn,
                            self.t_airborne, peaks,
                            np.array([block.alpha for block in self.stack.blocks]),
                            self.still_moving,
                            float(self.t[-1]) if self.t.size else math.nan,
                            self.past_alpha_at_end)

    # ------------------------------------------------------------------ views
    @property
    def energy(self) -> np.ndarray:
        """Kinetic (table frame) plus potential energy above the table [J] at the output
        times."""
        from shaketable.models.stack.physics import Chain, energy

        chain = Chain.of(self.stack)
        phi = np.diff(self.theta, axis=1, prepend=0.0)
        rate = np.diff(self.theta_dot, axis=1, prepend=0.0)
        return self.stack.mass_scale * np.array(
            [sum(energy(chain, phi[k], rate[k], self.patterns[k])) for k in range(self.t.size)])

    def to_frame(self) -> pd.DataFrame:
        columns: dict[str, Any] = {"t [s]": self.t}
        u, v = self.motion.at(self.t)
        columns["ug [m/s^2]"], columns["vg [m/s^2]"] = u, v
        for i in range(self.n_blocks):
            columns[f"theta_{i} [rad]"] = self.theta[:, i]
            columns[f"theta_dot_{i} [rad/s]"] = self.theta_dot[:, i]
            columns[f"theta_ddot_{i} [rad/s^2]"] = self.theta_ddot[:, i]
        for j in range(self.n_blocks):
            columns[f"state_{j}"] = self.patterns[:, j]
            columns[f"N_{j} [N]"] = self.forces[:, j, 0]
            columns[f"F_{j} [N]"] = self.forces[:, j, 1]
            columns[f"F/N_{j} [-]"] = self.friction_demand[:, j]
        columns["pattern"] = [pattern_name(p) for p in self.patterns]
        return pd.DataFrame(columns)

    def events_frame(self) -> pd.DataFrame:
        rows = []
        for event in self.events:
            row = dict(event)
            for key in ("pattern_before", "pattern_after"):
                if row.get(key) is not None:
                    row[key] = pattern_name(row[key])
            rows.append(row)
        frame = pd.DataFrame(rows)
        for column in ("t", "kind", "interface", "pattern_before", "pattern_after"):
            if column not in frame:
                frame[column] = pd.Series(dtype=object)
        return frame.rename(columns={"t": "t [s]", "rate_before": "phi_dot_before [rad/s]",
                                     "rate_after": "phi_dot_after [rad/s]",
                                     "energy_before": "energy_before [J]",
                                     "energy_after": "energy_after [J]"})

    def summary(self) -> dict[str, Any]:
        """The run's numbers as plain Python values (float, int, str, lists of float).

        ``"no-slip assumption"`` says whether some contact needed a friction
        coefficient above :data:`PLAUSIBLE_FRICTION` (no real contact gives more),
        and ``"t_friction_exceeded [s]"`` is the first such time
        (:meth:`t_friction_exceeded`); NaN if never. ``"t_past_alpha [s]"`` is the first
        time a block passes its alpha, and the two ``"... before past alpha"`` values are the
        peak F/N and top-corner excursion before it (:meth:`peak_before_past_alpha`).
        """
        kinds = [event["kind"] for event in self.events]
        first_uplift = next((e["t"] for e in self.events if e["kind"] == "uplift"), math.nan)
        finite = np.isfinite(self.friction_demand)
        slip = self.t_friction_exceeded(PLAUSIBLE_FRICTION)
        excursion = self.top_corner_excursion   # once: it is computed sample by sample
        standing = self.peak_before_past_alpha(excursion)
        return {"blocks": int(self.n_blocks), "impact law": str(self.impact),
                "masses [kg]": [float(mass) for mass in self.stack.mass],
                "masses": self.stack.describe_masses(),
                "status": str(self.status),
                "still moving at the end": self.still_moving,
                "past alpha at the end": [self.block_name(i) for i in self.past_alpha_at_end],
                "t_start [s]": float(first_uplift),
                "t_overturn [s]": float(self.t_overturn),
                "overturned block": int(self.overturned_block),
                "t_airborne [s]": float(self.t_airborne),
                "impacts": kinds.count("impact"), "events": int(self.n_events),
                # uplifts and impacts whose complementarity had not exactly one solution
                "events not unique": sum(1 for e in self.events
                                         if e.get("solutions") not in (None, 1)),
                "max |theta| [rad]": [float(x) for x in np.abs(self.theta).max(axis=0)],
                "peak top-corner excursion [m]": float(np.abs(excursion).max())
                if self.t.size else 0.0,
                "max F/N [-]": float(np.nanmax(np.where(finite, self.friction_demand, np.nan)))
                if finite.any() else math.nan,
                "no-slip assumption": (f"holds (F/N <= {PLAUSIBLE_FRICTION:g} throughout)"
                                       if math.isnan(slip) else
                                       f"fails from t = {slip:.3f} s (F/N > "
                                       f"{PLAUSIBLE_FRICTION:g}: the blocks would slide)"),
                "t_friction_exceeded [s]": float(slip),
                "t_tension [s]": float(self.t_tension),
                # what the column needs while it stands (before a block passes its alpha)
                "t_past_alpha [s]": float(self.t_past_alpha),
                "max F/N before past alpha [-]": standing[0],
                "peak top-corner excursion before past alpha [m]": standing[1]}

    def _figure(self, **options: Any):
        from shaketable.plots.stack import stack_calcomp  # matplotlib on use

        return stack_calcomp(self, **options)
