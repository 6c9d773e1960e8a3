"""The result of one run of the planar block: slip, rocking and flight in one model."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.core.motion import Motion
from shaketable.models.base import ModelResult
from shaketable.models.sliding.result import Friction

#: Mode names by code (the codes of :mod:`shaketable.models.planar.physics`).
MODES = ("rest", "slide", "rock", "slide-rock", "flight")

#: The verdict for the largest mode visited (same order as the codes).
VERDICTS = ("stayed", "slid", "rocked", "slide-rocked", "flew")

#: Event kinds by code (:data:`shaketable.models.planar.engine.EVENT_KINDS`).
EVENT_KINDS = ("mode change", "impact", "slip reverses", "cascade summed", "unstable",
               "overturned", "flat landing")

#: Why a run stopped, with what it means.
STATUS_MESSAGES = {
    "completed": "the run reached its end",
    "overturned": "|theta| reached pi/2",
    "painleve": ("Painleve's paradox: slipping on one corner, the effective mass "
                 "Ic + r_x (r_x + sigma mu_d r_y) is not positive (mu_d too large for the "
                 "block's h/b); the rigid-body Coulomb model has no solution here"),
    "inconsistent": ("a flat block must slide with mu_d > B/H but cannot tip: no mode of this "
                     "model holds it (docs/planar.md, 'Where the model stops')"),
    "chatter": ("more than 200 mode changes at one instant, or 100 000 in one sample "
                "interval: a sequence of events the model cannot sum (docs/planar.md, "
                "'Where the model stops')"),
    "stalled": ("the step size fell below 1e-14 s: the motion is not smooth enough here for "
                "the integrator (docs/planar.md, 'Where the model stops')"),
}


#: Where the planar model stops being valid (docs/planar.md, "Where the model stops"),
#: written with every planar summary.
MODEL_LIMITS = (
    "planar: no motion out of the plane, no twist; rigid block on a rigid table; constant "
    "Coulomb friction (mu_s, mu_d); no bouncing: an impact is plastic at the striking corner "
    "(the COR enters as a couple about it), so a squat block that bounces is not modelled; "
    "flat landings and impacts on both corners are plastic; near mu = B/H the verdict is a "
    "knife-edge (stay below 0.99 B/H for a robust 'slides'); no prestress rods")


@dataclass(frozen=True)
class PlanarResult(ModelResult):
    """Time history and scalar results of one run of the planar block.

    Coordinates are relative to the table (see :mod:`shaketable.models.planar.physics`):
    ``x`` the horizontal displacement of the centre of mass from its initial position
    [m], ``y`` its height above the table [m], ``theta`` the package's rotation [rad]
    (positive: pivot on the corner at -x). ``slip`` is the horizontal displacement of the
    base's midpoint, ``x + h sin(theta)`` [m].

    Attributes
    ----------
    block, motion, cor, friction
        The inputs (``cor`` a number or ``"housner"``).
    t : ndarray
        Output times [s]: the motion's samples up to the end of the run; a run that
        stopped early ends with the instant it stopped.
    x, y, theta, x_dot, y_dot, theta_dot, slip : ndarray
        The state at the output times [m, m, rad, m/s, m/s, rad/s, m].
    mode : ndarray of int
        Mode at each output time (the one entered at that instant), codes of :data:`MODES`.
    events : ndarray, shape (k, 6)
        Time [s], kind (:data:`EVENT_KINDS`), mode before, mode after, theta' [rad/s]
        (before an impact), slip [m]; the first ``max_recorded_events`` events.
    n_events : int
        All events counted.
    time_in_mode : dict
        Seconds spent in each mode [s].
    modes_visited : tuple of str
        Modes the block was in at any time.
    peak_slip, t_peak_slip, residual_slip : float
        Largest |slip| [m], when [s], slip at the end [m]: the base midpoint's
        displacement, which the rotation moves too (h sin(theta) - b (1 - cos(theta)) for
        a block rocking on a corner that does not slide; exactly b for a block that
        overturned without sliding). Kept with this meaning; ``peak_base_slip`` is the
        slide alone.
    peak_excursion : float
        Largest |X - X_rest| over time and over the four corners [m]: the clearance the
        block needs from its neighbours.
    max_abs_theta, t_max : float
        Largest |theta| [rad] and when [s].
    t_start, t_unstable, t_overturn, t_rest : float
        First departure from rest, first |theta| > alpha, overturning, last rest after a
        summed cascade [s] (NaN: never).
    unstable_direction, overturn_direction : int
        Sign of theta then (0: never).
    n_impacts, capped_impacts, cascades : int
        Corner impacts resolved; impacts whose couple ratio was lowered so as not to add
        kinetic energy; endless cascades summed in closed form.
    work_table, work_friction, impact_loss : float
        Per unit mass [J/kg = m^2/s^2]: work of the table's inertial force (-ug, -vg), of
        friction (<= 0) and the kinetic energy lost in impacts (>= 0).
    energy_start, energy_end : float
        Kinetic + potential energy per unit mass, g y [m^2/s^2].
    status : str
        A key of :data:`STATUS_MESSAGES`.
    statistics : dict
        Solver work: steps, rejected steps, right-hand-side evaluations.
    peak_base_slip, t_peak_base_slip : float
        How far the base slid on the table [m] and when [s]: the largest displacement of
        the bottom corner the block stands or turns on (x when flat), 0 for a block that
        rocks or overturns without sliding. Exact at every event and sample (a contact
        corner's slip turns where its slip speed is 0, an event); in a flight, at its ends.
    """

    block: Block | AsymmetricBlock
    motion: Motion
    cor: float | str
    friction: Friction
    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    x_dot: np.ndarray
    y_dot: np.ndarray
    theta_dot: np.ndarray
    slip: np.ndarray
    mode: np.ndarray
    events: np.ndarray
    n_events: int
    time_in_mode: dict
    modes_visited: tuple
    peak_slip: float
    t_peak_slip: float
    residual_slip: float
    peak_excursion: float
    max_abs_theta: float
    t_max: float
    t_start: float
    t_unstable: float
    unstable_direction: int
    t_overturn: float
    overturn_direction: int
    t_rest: float
    n_impacts: int
    capped_impacts: int
    cascades: int
    work_table: float
    work_friction: float
    impact_loss: float
    energy_start: float
    energy_end: float
    status: str
    statistics: dict = field(default_factory=dict)
    peak_base_slip: float = math.nan
    t_peak_base_slip: float = math.nan

    @property
    def overturned(self) -> bool:
        """True when |theta| reached pi/2."""
        return self.status == "overturned"

    @property
    def message(self) -> str:
        """What the status means."""
        return STATUS_MESSAGES[self.status]

    @property
    def max_theta_ratio(self) -> float:
        """max |theta| / alpha [-]; NaN for an overturned run (the report's "F"), as
        :attr:`shaketable.models.rocking.result.RockingResult.max_theta_ratio`."""
        if self.overturned:
            return math.nan
        return self.max_abs_theta / self.block.alpha

    @property
    def impact_times(self) -> np.ndarray:
        """Times of the recorded corner impacts [s]."""
        return self.events[self.events[:, 1] == EVENT_KINDS.index("impact"), 0]

    @property
    def energy_residual(self) -> float:
        """E_end - E_start - (W_table + W_friction - impact losses) [m^2/s^2]: zero up to
        the integration error."""
        return (self.energy_end - self.energy_start
                - (self.work_table + self.work_friction - self.impact_loss))

    def verdict(self) -> str:
        """The largest mode visited in words: stayed < slid < rocked < slide-rocked < flew,
        and overturned above all."""
        if self.overturned:
            return "overturned"
        largest = max(MODES.index(name) for name in self.modes_visited)
        return VERDICTS[largest]

    def events_frame(self):
        """The recorded events as a :class:`pandas.DataFrame`."""
        import pandas as pd

        e = self.events
        return pd.DataFrame({
            "time [s]": e[:, 0],
            "event": [EVENT_KINDS[int(k)] for k in e[:, 1]],
            "mode before": [MODES[int(k)] for k in e[:, 2]],
            "mode after": [MODES[int(k)] for k in e[:, 3]],
            "theta_dot [rad/s]": e[:, 4],
            "slip [m]": e[:, 5],
        })

    def to_frame(self):
        """Time history as a :class:`pandas.DataFrame` with units in the column names."""
        return planar_frame(self)

    def summary(self) -> dict:
        """Scalar results as a JSON-ready dict (NaN written as None): :func:`planar_summary`."""
        return planar_summary(self)

    def plot(self, fig=None, title: str | None = None):
        """The Calcomp layout with a slip panel and a mode band; see
        :func:`shaketable.plots.planar.planar_figure`."""
        from shaketable.plots.planar import planar_figure

        return planar_figure(self, fig=fig, title=title)


#: The rows of a planar run's summary, in order: (key, attribute of the result). A result
#: without the attribute leaves the row out: the SciPy reference
#: (:class:`~shaketable.models.planar.reference_result.PlanarReferenceResult`) computes no
#: corner excursion, start of rocking, event counts or solver statistics.
_SUMMARY_ROWS = (
    ("peak slip [m]", "peak_slip"), ("t_peak_slip [s]", "t_peak_slip"),
    ("peak base slip [m]", "peak_base_slip"), ("t_peak_base_slip [s]", "t_peak_base_slip"),
    ("residual slip [m]", "residual_slip"), ("peak corner excursion [m]", "peak_excursion"),
    ("t_start [s]", "t_start"), ("t_unstable [s]", "t_unstable"),
    ("unstable_direction", "unstable_direction"), ("t_overturn [s]", "t_overturn"),
    ("overturn_direction", "overturn_direction"), ("t_rest [s]", "t_rest"),
    ("n_impacts", "n_impacts"), ("capped_impacts", "capped_impacts"),
    ("cascades", "cascades"), ("n_events", "n_events"),
)


def planar_summary(result, model: str | None = None) -> dict:
    """The scalar results of a planar run (the compiled engine's or the reference's) as a
    JSON-ready dict (NaN written as None), with the same key for the same quantity.

    Parameters
    ----------
    result : PlanarResult or PlanarReferenceResult
    model : str, optional
        Written under ``model`` after the response mode (the reference names itself).

    Returns
    -------
    dict
        Block [m, rad, rad/s], COR, friction, motion, status and verdict, peaks [m, rad]
        and times [s], counts, the time in each mode [s], the work and loss terms and the
        energy residual [J/kg]; then the status message (a run that did not complete) and
        the solver statistics, where the result has them.
    """
    from shaketable.core.files import json_ready_dict

    block = result.block
    data: dict = {"response mode": "planar (rest, slide, rock, slide-rock, flight)"}
    if model is not None:
        data["model"] = model
    if isinstance(block, AsymmetricBlock):   # its centre's height and both pivots' distances
        data.update({"h [m]": block.h, "b_plus [m]": block.b_plus, "b_minus [m]": block.b_minus,
                     "alpha_plus [rad]": block.alpha_plus,
                     "alpha_minus [rad]": block.alpha_minus})
    else:
        data.update({"block_height [m]": block.height, "block_width [m]": block.width})
    data.update({
        "alpha [rad]": block.alpha, "p [rad/s]": block.p, "cor [-]": result.cor,
        "static friction mu_s [-]": result.friction.static,
        "dynamic friction mu_d [-]": result.friction.dynamic,
        "motion": None if result.motion is None else result.motion.name,
        "status": result.status, "verdict": result.verdict(),
        "overturned": result.overturned, "max_theta_ratio [-]": result.max_theta_ratio,
        "max_abs_theta [rad]": result.max_abs_theta, "t_max [s]": result.t_max,
        "model limits": MODEL_LIMITS,
    })
    data.update({key: getattr(result, name) for key, name in _SUMMARY_ROWS
                 if hasattr(result, name)})
    data.update({
        "modes visited": ", ".join(result.modes_visited),
        **{f"time {name} [s]": value for name, value in result.time_in_mode.items()},
        "work of the table [J/kg]": result.work_table,
        "work of friction [J/kg]": result.work_friction,
        "impact losses [J/kg]": result.impact_loss,
        "energy residual [J/kg]": result.energy_residual,
    })
    if result.status != "completed":
        data["status message"] = result.message
    data.update({f"solver {key}": value
                 for key, value in getattr(result, "statistics", {}).items()})
    return json_ready_dict(data)


def planar_frame(result):
    """The time history of a planar result (the compiled engine's or the reference's) as a
    :class:`pandas.DataFrame`: ground acceleration [g], x, y [m], theta [rad], their rates,
    the slip [m], theta/alpha [-] and the mode's name; one set of columns for both results,
    which the planar figure (:func:`shaketable.plots.planar.planar_figure`) reads."""
    import pandas as pd

    return pd.DataFrame({
        "time [s]": result.t,
        **result.motion.columns_in_g(result.t),
        "x [m]": result.x,
        "y [m]": result.y,
        "theta [rad]": result.theta,
        "x_dot [m/s]": result.x_dot,
        "y_dot [m/s]": result.y_dot,
        "theta_dot [rad/s]": result.theta_dot,
        "slip [m]": result.slip,
        "theta/alpha [-]": result.theta / result.block.alpha,
        "mode": [MODES[int(k)] for k in result.mode],
    })


def base_slip(x, theta, block) -> np.ndarray:
    """How far the base has slid [m] at each sample: the displacement of the bottom corner
    the block stands or turns on (on theta's side; x when flat),
    x + h sin(theta) + sign(theta) b (1 - cos(theta)); 0 for a block that rocks without
    sliding. The quantity whose peak is ``peak_base_slip`` (docs/planar.md, "Using it").

    Parameters
    ----------
    x, theta : ndarray
        Horizontal displacement of the centre of mass [m] and rotation [rad].
    block : Block
    """
    x = np.asarray(x, dtype=float)
    theta = np.asarray(theta, dtype=float)
    slip = x + block.h * np.sin(theta)
    # an AsymmetricBlock's pivots are b_plus (theta > 0) and b_minus from the centre
    b = np.where(theta > 0.0, block.b_plus, block.b_minus) \
        if isinstance(block, AsymmetricBlock) else block.b
    return slip + np.sign(theta) * b * (1.0 - np.cos(theta))
