"""Independent SciPy reference of the planar rigid block: rest, slide, rock, slide-rock, flight.

The model is the one of ``docs/planar.md``; this module is a second,
independent implementation of it, used to validate the compiled engine. It
shares with the rest of the package only the closed-form cascade sum
(:func:`shaketable.models.rocking.physics.cascade_rest_time`) and the mode codes of
:mod:`shaketable.models.planar.shenton`.

Formulation
-----------
Newton-Euler in the table frame, per unit mass, in the full coordinates
q = (x, y, theta) of the centre and the rotation, in every mode:

    M q'' = f + W(theta) lambda,   M = diag(1, 1, Ic),  f = (-ug, -(g + vg), 0),

with W the generalised direction of each contact force (a force (Fx, Fy) at
the corner r = (r_x, r_y) from the centre acts as (Fx, Fy, r_x Fy - r_y Fx)).
In each mode the unknown accelerations and contact forces are found together
from a small linear system (``numpy.linalg.solve``), the constraints written
on accelerations (a corner fixed: X'' = x'' - r_y theta'' - r_x theta'^2 = 0,
Y'' = y'' + r_x theta'' - r_y theta'^2 = 0):

* ROCK: unknowns (x'', y'', theta'', F, N), both corner constraints (5 x 5);
* SLIDE_ROCK: unknowns (x'', y'', theta'', N), F = -sigma mu_d N, Y'' = 0 (4 x 4);
  Painleve's case (a normal "effective mass" <= 0) stops the run;
* SLIDE: y'' = theta'' = 0, N = g + vg, F = -sigma mu_d N;
* FLIGHT: q'' = f; REST: nothing moves (the rest conditions are linear in time
  between samples and their first violation is a root of a linear function).

The six-component state (x, y, theta, x', y', theta') plus two quadratures
(friction work and the work of the table's inertial forces) is integrated by
SciPy's DOP853 at ``rtol`` (default 1e-12), one ``solve_ivp`` call per input
interval (accelerations linear between samples, Section 2.8 of the report)
and per mode, every transition and impact of the spec located by SciPy's event
location and the integration restarted there. The constraints hold on
accelerations only; at every restart the positions and velocities are
projected back onto them (theta and theta' are not changed by the projection:
in ROCK and SLIDE_ROCK theta'' depends on theta, theta' and the input only).
A turning point of theta on the wrong side of theta = 0 means an impact was
passed inside a step; it is found on the dense output (Brent's method), as
:mod:`shaketable.models.rocking.reference` does for the rocking model.

Choices where the spec is silent (documented here, reported to the lead)
-------------------------------------------------------------------------
* A slipping corner reaching zero slip velocity whose ROCK forces need more
  than mu_s N slips on toward -sign(F_rock) (the ROCK -> SLIDE_ROCK rule);
  this is the spec's "slip reverses" when F_rock opposes the old slip, and
  keeps the slip direction in the marginal case mu_d = mu_s just after a slip
  started (a sign the spec does not fix).
* Impacts (``planar_contact.impact_map``): the couple C = (rho - 1) H_k' with
  H_k' the angular momentum about the striking corner in the frame of its
  incoming slip (``planar_contact.frame_momentum``); a slipping impact slips
  the way its corner goes (sigma = -sign of the sticking P_x, else the other
  sigma, else it sticks). The cap applies on both sides of rho = 1: rho is moved
  toward 1 until the normal impulse pushes and the kinetic energy grows in
  neither the table's frame nor the slip frame, and the branch is decided
  again at the new rho.
* An impact at theta = 0 that leaves the block turning onto the corner that
  was on the table (side * theta'+ < 0), and a flat landing, are resolved by
  the plastic two-corner problem (``planar_contact.two_corner_impact``).
* The cascade sum (``cascade_rest_time``) is applied after every impact at
  theta = 0: after a sticking impact that leaves the block in ROCK with the
  numeric cor (c_H for ``"housner"``), exactly as the rocking engine; after a
  slipping one with that impact's ratio |theta'+ / theta'-| and the
  deceleration of SLIDE_ROCK at theta = theta' = 0 (ROCK's where SLIDE_ROCK tips
  away from 0), the block then sliding flat at the corner's slip speed (REST if 0). The kinetic energy the cascade
  absorbs is counted as impact loss.
* "The block tips" (Eq. 2-1) is decided by the sign of ROCK's theta'' at
  theta = theta' = 0 from the same linear solve as the ROCK mode, and a flat
  block whose chosen corner does not tip (a marginal start such as mu_s = B/H)
  stays flat (SLIDE or REST), so that rounding cannot start a mode that turns
  the block the wrong way.
* x is the centre's displacement from its position at rest; a block started
  tilted (theta0 != 0) stands on its corner s = sign(theta0) at that corner's
  rest position X_s = -s b (so x(0) = -s b - r_x(theta0)); ``x_dot0`` is the
  initial slip velocity of the base (flat) or of the pivot corner.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning
   response of rigid bodies to earthquake motions", Lawrence Berkeley
   Laboratory, University of California, Berkeley.
.. [2] H. W. Shenton III, "Criteria for initiation of slide, rock, and
   slide-rock rigid-body modes", J. Eng. Mech. 122(7), 1996.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from shaketable.core.constants import G
from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.core.motion import Motion
from shaketable.models.planar.contact import (
    PlanarGeometry,
    kinetic_energy,
    mode_solution,
    rock_solution,
    slide_rock_effective_mass,
    slide_rock_solution,
)
from shaketable.models.planar.reference_impacts import ImpactTransitions
from shaketable.models.planar.reference_result import PlanarReferenceResult
from shaketable.models.planar.shenton import FLIGHT, MODE_NAMES, REST, ROCK, SLIDE, SLIDE_ROCK
from shaketable.models.sliding.result import Friction

#: Consecutive segments that may end where they began before the solver gives up.
MAX_STALLED_SEGMENTS = 100

#: Impacts at one instant (each turning the block onto the corner that struck before).
MAX_IMMEDIATE_IMPACTS = 1000

#: Segments (solve_ivp calls) allowed inside one input interval.
MAX_SEGMENTS_PER_INTERVAL = 100_000


class PlanarReferenceError(RuntimeError):
    """SciPy's integrator gave up, or the event loop stopped advancing in time."""


# ----------------------------------------------------------------- the solver

def _check(block, motion, cor, friction, rtol, duration, output_dt):
    if not isinstance(block, (Block, AsymmetricBlock)):
        raise ValueError(f"block must be a shaketable Block or AsymmetricBlock, got "
                         f"{type(block).__name__}")
    if isinstance(block, Block) and block.rods is not None:
        raise ValueError("rods: the planar (sliding) model refuses a block with prestress rods "
                         "(a rod hinged to the ground ties the block to the table)")
    if motion is None:
        if duration is None:
            raise ValueError("duration [s] is required for free motion (motion=None)")
        motion = Motion.at_rest(duration, dt=output_dt)
    elif not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable Motion or None, got "
                         f"{type(motion).__name__}")
    if motion.pitched:
        raise ValueError("motion: the planar model takes horizontal and vertical table "
                         "acceleration only (no table rotation)")
    if isinstance(cor, str):
        if cor != "housner":
            raise ValueError(f"cor must be a number in [0, 1] or 'housner', got {cor!r}")
    elif isinstance(cor, bool) or not isinstance(cor, (int, float)) or not 0 <= cor <= 1:
        raise ValueError(f"cor must be a number in [0, 1] or 'housner', got {cor!r}")
    if not isinstance(cor, str) and 0.0 in (PlanarGeometry(block).c_plus,
                                            PlanarGeometry(block).c_minus):
        raise ValueError(f"cor: a numeric cor ({cor!r}) needs Housner's ratio c_H = 1 - 1.5 "
                         "sin^2(alpha) != 0 (rho = cor / c_H); this block has B/H = sqrt(2), "
                         "c_H = 0: use cor='housner'")
    if not isinstance(friction, Friction):
        raise ValueError(f"friction must be a Friction, got {type(friction).__name__}")
    if not (isinstance(rtol, float) and 1e-14 <= rtol <= 1e-3):
        raise ValueError(f"rtol must be a float in [1e-14, 1e-3], got {rtol!r}")
    return motion


def simulate_reference(block: Block, motion: Motion | None = None, *, cor, friction: Friction,
                       theta0: float = 0.0, theta_dot0: float = 0.0, x_dot0: float = 0.0,
                       duration: float | None = None, rtol: float = 1e-12,
                       output_dt: float = 0.005,
                       rest_tolerance: float | None = None) -> PlanarReferenceResult:
    """Planar block (rest, slide, rock, slide-rock, flight) by SciPy DOP853 with events.

    Parameters
    ----------
    block : Block
        The block (no prestress rods).
    motion : Motion, optional
        Horizontal (+x) and vertical (up) table accelerations [m/s^2], linear
        between samples. ``None``: a table at rest for ``duration``.
    cor : float or "housner"
        Coefficient of restitution [-] (Section 2.7 (5)), rho = cor / c_H; or
        Housner's law (rho = 1).
    friction : Friction
        mu_s and mu_d [-].
    theta0, theta_dot0 : float
        Initial rotation [rad] and rate [rad/s].
    x_dot0 : float
        Initial slip velocity [m/s] of the base (flat start) or pivot corner.
    duration : float, optional
        Length of a free run [s] (``motion=None``).
    rtol : float
        DOP853 relative tolerance [-]; absolute tolerances are rtol/100 times
        alpha (theta), alpha R (x, y) and their rates times p.
    output_dt : float
        Output interval of a free run [s].
    rest_tolerance : float, optional
        A cascade of impacts lasting less than this is summed [s]; default
        1e-6 / p (the rocking engine's).

    Returns
    -------
    PlanarReferenceResult

    Raises
    ------
    ValueError
        Bad input (naming the parameter), a block with rods.
    PlanarReferenceError
        SciPy failed or the event loop stalled.
    """
    motion = _check(block, motion, cor, friction, rtol, duration, output_dt)
    for name, value, unit in (("theta0", theta0, "rad"), ("theta_dot0", theta_dot0, "rad/s"),
                              ("x_dot0", x_dot0, "m/s")):
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value):
            raise ValueError(f"{name} must be a finite number [{unit}], got {value!r}")
    if not abs(theta0) < 0.5 * math.pi:
        raise ValueError(f"theta0 must be within (-pi/2, pi/2) [rad], got {theta0!r}")
    return _Run(block, motion, cor, friction, rtol, rest_tolerance).run(
        float(theta0), float(theta_dot0), float(x_dot0))


class _Stop(Exception):
    def __init__(self, status, message):
        super().__init__(message)
        self.status, self.message = status, message


class _Run(ImpactTransitions):
    """The event loop of one run (mutable state; see the module docstring)."""

    def __init__(self, block, motion, cor, friction, rtol, rest_tolerance):
        self.block, self.motion, self.cor, self.friction = block, motion, cor, friction
        self.geometry = geometry = PlanarGeometry(block)
        self.mu_s, self.mu_d = friction.static, friction.dynamic
        self.rho = 1.0 if cor == "housner" else cor / geometry.c_housner
        self.cascade_cor = geometry.c_housner if cor == "housner" else float(cor)
        self.rtol = rtol
        p, alpha = block.p, block.alpha
        size = max(block.R_of(1.0), block.R_of(-1.0)) if isinstance(block, AsymmetricBlock) \
            else block.R
        self.atol = 1e-2 * rtol * np.array([alpha * size, alpha * size, alpha,
                                            alpha * size * p, alpha * size * p, alpha * p,
                                            G * size * alpha, G * size * alpha])
        self.velocity_floor = 1e3 * self.atol[5]
        self.rest_tolerance = 1e-6 / p if rest_tolerance is None else rest_tolerance
        self.events: list = []
        self.fresh: set = set()
        self.impacts: list = []
        self.capped = 0
        self.impact_loss = 0.0
        self.max_abs_theta, self.t_max = 0.0, float(motion.t[0])
        self.peak_slip, self.t_peak_slip = 0.0, float(motion.t[0])
        self.peak_base_slip, self.t_peak_base_slip = 0.0, float(motion.t[0])
        self.t_unstable = math.nan
        self.t_rest = math.nan
        self.time_in_mode = dict.fromkeys(MODE_NAMES, 0.0)

    # ------------------------------------------------------------ bookkeeping
    def record(self, t, kind, before, after):
        self.events.append((t, kind, before, after))
        # the next segment starts on the zero of these event functions
        self.fresh = {"stick", "landing+1", "landing-1"} | (
            {"impact"} if self.state[2] == 0.0 else set())

    def note(self, t, state):
        """Track max |theta| and |slip| at a point of the trajectory."""
        theta = state[2]
        if abs(theta) > self.max_abs_theta:
            self.max_abs_theta, self.t_max = abs(theta), t
        slip = state[0] + self.geometry.h * math.sin(theta)
        if abs(slip) > self.peak_slip:
            self.peak_slip, self.t_peak_slip = abs(slip), t
        # the base's own slide: the corner it stands or turns on (x when flat)
        b = self.geometry.b_of(1 if theta > 0.0 else -1)
        base = slip + math.copysign(b * (1.0 - math.cos(theta)), theta)
        if abs(base) > self.peak_base_slip:
            self.peak_base_slip, self.t_peak_base_slip = abs(base), t

    def ground(self, time):
        u0, u1, v0, v1, t0, t1 = self.interval
        fraction = (time - t0) / (t1 - t0)
        return u0 + (u1 - u0) * fraction, v0 + (v1 - v0) * fraction

    def solution(self, time, state, mode=None):
        ug, vg = self.ground(time)
        return mode_solution(self.geometry, self.mode if mode is None else mode, self.side,
                             self.sigma, state[2], state[5], ug, vg, self.mu_d)

    def project(self):
        """Put positions and velocities back on the active constraints."""
        state, geometry = self.state, self.geometry
        if self.mode in (ROCK, SLIDE_ROCK):
            r_x, r_y = geometry.arm(self.side, state[2])
            state[1], state[4] = -r_y, -r_x * state[5]
            if self.mode == ROCK:
                state[0], state[3] = self.pivot - r_x, r_y * state[5]
        elif self.mode in (REST, SLIDE):
            state[1], state[2], state[4], state[5] = geometry.h, 0.0, 0.0, 0.0
            if self.mode == REST:
                state[3] = 0.0

    def corner_slip_velocity(self, state):
        r_x, r_y = self.geometry.arm(self.side, state[2])
        return state[3] - r_y * state[5]

    def energy(self):
        return kinetic_energy(self.geometry, self.state) + G * (self.state[1] - self.geometry.h)

    # ----------------------------------------------------------- mode choice
    def set_mode(self, t, mode, side=None, sigma=None, kind=None):
        before = self.mode
        self.mode = mode
        if side is not None:
            self.side = side
        if sigma is not None:
            self.sigma = sigma
        if mode == ROCK:
            r_x, _ = self.geometry.arm(self.side, self.state[2])
            self.pivot = self.state[0] + r_x
        self.project()
        if kind is not None:
            self.record(t, kind, before, mode)

    def enter_contact(self, t, mode, side, sigma, kind, before):
        """Enter ROCK or SLIDE_ROCK (from mode ``before``), redirected to SLIDE_ROCK,
        FLIGHT, or (flat, theta = theta' = 0, not tipping) SLIDE or REST when its contact
        forces are inconsistent; record the event."""
        for _ in range(4):
            self.set_mode(t, mode, side, sigma)
            if mode == SLIDE_ROCK and slide_rock_effective_mass(
                    self.geometry, side, sigma, self.state[2], self.mu_d) <= 0.0:
                raise _Stop("painleve", f"Painleve's paradox at t = {t!r} s: slide-rock about "
                            f"corner {side:+d} with mu_d = {self.mu_d} has no consistent "
                            "normal force")
            _, _, thdd, force, normal = self.solution(t, self.state)
            if normal <= 0.0:
                # a sticking corner that would have to pull flies only if its free vertical
                # acceleration -(g + vg) - r_y theta'^2 is >= 0; otherwise it slips
                _, vg = self.ground(t)
                _, r_y = self.geometry.arm(side, self.state[2])
                if mode == ROCK and G + vg + r_y * self.state[5] ** 2 > 0.0:
                    mode, sigma = SLIDE_ROCK, (-1 if force > 0 else 1)
                    continue
                mode = FLIGHT
                break
            if self.state[2] == 0.0 and self.state[5] == 0.0 and side * thdd <= 0.0:
                # a flat block at rest on both corners that does not tip onto this one
                # (a marginal start, e.g. mu_s = B/H): it stays flat, sliding if it slips
                if mode == SLIDE_ROCK and self.mu_d > self.geometry.b_of(-sigma) / self.geometry.h:
                    raise _Stop("inconsistent", f"no consistent mode at t = {t!r} s: "
                                "slide-rock does not tip and mu_d > B/H forbids a flat slide")
                mode = SLIDE if mode == SLIDE_ROCK else REST
                break
            if mode == ROCK and abs(force) > self.mu_s * normal:
                mode, sigma = SLIDE_ROCK, (-1 if force > 0 else 1)
                continue
            break
        self.set_mode(t, mode, side, sigma)
        self.record(t, kind, before, mode)

    def start_rules(self, t):
        """Spec "Leaving REST": the mode of a flat block with x' = 0 at time t."""
        ug, vg = self.ground(t)
        normal = G + vg
        geometry = self.geometry
        if normal <= 0.0:
            return FLIGHT, self.side, self.sigma
        if self.tipping(1, ug, vg) > 0.0 or self.tipping(-1, ug, vg) > 0.0:
            side = 1 if ug > 0 else -1
            sigma = -side
            _, _, _, force, rock_normal = rock_solution(geometry, side, 0.0, 0.0, ug, vg)
            if rock_normal > 0.0 and abs(force) <= self.mu_s * rock_normal:
                return ROCK, side, sigma
            if slide_rock_effective_mass(geometry, side, sigma, 0.0, self.mu_d) > 0.0:
                xdd, _, thdd, _, sr_normal = slide_rock_solution(geometry, side, sigma, 0.0,
                                                                 0.0, ug, vg, self.mu_d)
                r_x, r_y = geometry.arm(side, 0.0)
                if sr_normal > 0.0 and side * thdd > 0.0 and sigma * (xdd - r_y * thdd) > 0.0:
                    return SLIDE_ROCK, side, sigma
        if abs(ug) > self.mu_s * normal \
                and self.mu_d <= geometry.b_of(1 if ug > 0 else -1) / geometry.h:
            return SLIDE, self.side, (-1 if ug > 0 else 1)
        raise _Stop("inconsistent", f"no consistent mode for the flat block at t = {t!r} s "
                    f"(ug = {ug!r}, vg = {vg!r} m/s^2)")

    def rest_holds(self, t):
        ug, vg = self.ground(t)
        normal = G + vg
        return (normal > 0.0 and abs(ug) <= self.mu_s * normal
                and self.tipping(1, ug, vg) <= 0.0 and self.tipping(-1, ug, vg) <= 0.0)

    def tipping(self, side, ug, vg):
        """side * theta'' of ROCK about ``side`` at theta = theta' = 0 [rad/s^2].

        Positive iff side ug h > b (g + vg) (Eq. 2-1), here from the same Newton-Euler
        solve as the ROCK mode itself, so that "the block tips" and "ROCK turns the
        block onto that corner" never disagree by rounding.
        """
        return side * rock_solution(self.geometry, side, 0.0, 0.0, ug, vg)[2]

    def leave_flat(self, t, kind):
        """A flat block at rest at t whose rest conditions fail: apply the start rules."""
        mode, side, sigma = self.start_rules(t)
        self.state[3] = 0.0
        if mode in (ROCK, SLIDE_ROCK):
            before = self.mode
            self.set_mode(t, REST)
            self.enter_contact(t, mode, side, sigma, kind, before)
        else:
            self.set_mode(t, mode, side, sigma, kind)

    # -------------------------------------------------------------- REST
    def rest_until_failure(self, t, t_end):
        """First time in [t, t_end] at which the rest conditions fail, else None."""
        u0, u1, v0, v1, t0, t1 = self.interval
        mu_s = self.mu_s
        # each condition g(time) > 0 means "rest fails"; g is linear in time (to rounding)
        conditions = [lambda u, v: -(G + v),
                      lambda u, v: u - mu_s * (G + v), lambda u, v: -u - mu_s * (G + v),
                      lambda u, v: self.tipping(1, u, v), lambda u, v: self.tipping(-1, u, v)]
        best = None
        for index, condition in enumerate(conditions):
            def value(time, condition=condition):
                return condition(*self.ground(time))
            start, end = value(t), value(t_end)
            failing = (lambda g: g >= 0.0) if index == 0 else (lambda g: g > 0.0)
            if failing(start):
                candidate = t
            elif failing(end):
                candidate = t + (t_end - t) * (-start) / (end - start)
                low, high = max(t, min(candidate, t_end)), t_end
                if not failing(value(low)):
                    for _ in range(200):  # the first float at which it fails
                        middle = 0.5 * (low + high)
                        if middle <= low or middle >= high:
                            break
                        if failing(value(middle)):
                            high = middle
                        else:
                            low = middle
                    candidate = high
                else:
                    candidate = low
            else:
                continue
            if best is None or candidate < best:
                best = candidate
        return best

    # ------------------------------------------------------------- a segment
    def event_functions(self, t_segment):
        """(functions, names) of the events of the current mode.

        An event function that is zero at the segment's start (theta = 0 after an
        impact, a slip velocity 0 after a start of slip, the corner that just lifted
        off) is divided by the elapsed time (its limit, the rate, at the start), so
        that the start itself is not taken for its root (the rocking reference's rule).
        """
        mode, side, sigma, geometry = self.mode, self.side, self.sigma, self.geometry
        fresh, self.fresh = self.fresh, set()
        functions, names = [], []

        def add(function, name, terminal, direction, rate=None, order=1):
            if name in fresh and rate is not None:
                raw = function

                def function(t, z):
                    elapsed = t - t_segment
                    if elapsed > 0.0:
                        return raw(t, z) / elapsed ** order
                    value = raw(t, z)
                    return value if value != 0.0 else rate(t, z)
            function.terminal, function.direction = terminal, direction
            functions.append(function)
            names.append(name)

        def corner_slip_acceleration(t, z):
            xdd, _, thdd, _, _ = self.solution(t, z)
            r_x, r_y = geometry.arm(side, z[2])
            return xdd - r_y * thdd - r_x * z[5] ** 2

        if mode in (ROCK, SLIDE_ROCK):
            if self.state[5] == 0.0:
                # a block that starts to turn from theta = theta' = 0: theta ~ theta'' t^2 / 2
                add(lambda t, z: side * z[2], "impact", True, -1,
                    lambda t, z: 0.5 * side * self.solution(t, z)[2], order=2)
            else:
                add(lambda t, z: side * z[2], "impact", True, -1, lambda t, z: side * z[5])
            add(lambda t, z: self.solution(t, z)[4], "lift-off", True, -1)
            if mode == ROCK:
                add(lambda t, z: self.mu_s * self.solution(t, z)[4]
                    - abs(self.solution(t, z)[3]), "slip", True, -1)
            else:
                add(lambda t, z: sigma * self.corner_slip_velocity(z), "stick", True, -1,
                    lambda t, z: sigma * corner_slip_acceleration(t, z))
            add(lambda t, z: 0.5 * math.pi - side * z[2], "overturn", True, -1)
            add(lambda t, z: z[5], "peak", False, 0)
        elif mode == SLIDE:
            add(lambda t, z: sigma * z[3], "stick", True, -1,
                lambda t, z: sigma * self.solution(t, z)[0])
            add(lambda t, z: G + self.ground(t)[1], "lift-off", True, -1)
        elif mode == FLIGHT:
            for corner in (1, -1):
                add(lambda t, z, c=corner: z[1] + geometry.arm(c, z[2])[1],
                    f"landing{corner:+d}", True, -1, lambda t, z: 1.0)
            add(lambda t, z: 0.5 * math.pi - abs(z[2]), "overturn", True, -1)
        if mode in (ROCK, SLIDE_ROCK, FLIGHT):
            add(lambda t, z: geometry.alpha_of(1 if z[2] > 0.0 else -1) - abs(z[2]), "unstable",
                False, -1)
        add(lambda t, z: z[3] + geometry.h * math.cos(z[2]) * z[5], "slip turn", False, 0)
        return functions, names

    def rhs(self, t, z):
        ug, vg = self.ground(t)
        xdd, ydd, thdd, force, _ = mode_solution(self.geometry, self.mode, self.side,
                                                 self.sigma, z[2], z[5], ug, vg, self.mu_d)
        if self.mode == SLIDE:
            friction_power = force * z[3]
        elif self.mode == SLIDE_ROCK:
            friction_power = force * self.corner_slip_velocity(z)
        else:
            friction_power = 0.0
        return [z[3], z[4], z[5], xdd, ydd, thdd, friction_power, -ug * z[3] - vg * z[4]]

    def passed_impact(self, solution, names, t_segment):
        """An impact a step passed without seeing it (a turning point with side*theta < 0)."""
        side = self.side
        peaks = solution.t_events[names.index("peak")]
        states = solution.y_events[names.index("peak")]
        t_last = float(solution.t[-1])
        for time, z in zip(peaks, states):
            if time >= t_last and solution.status == 1:
                break
            if side * z[2] >= 0.0:
                continue
            steps = solution.t[solution.t < time]
            low = float(steps[-1]) if steps.size else t_segment
            theta_of = lambda s: side * float(solution.sol(s)[2])  # noqa: E731
            if theta_of(low) <= 0.0:
                low = float(np.nextafter(low, time))
                if theta_of(low) <= 0.0:
                    return low
            return brentq(theta_of, low, float(time), xtol=1e-15,
                          rtol=4 * np.finfo(float).eps, maxiter=200)
        return None

    def integrate_segment(self, t, t_end):
        """Integrate the current mode from t to t_end or its first terminal event.

        Returns (time reached, name of the terminal event or None).
        """
        functions, names = self.event_functions(t)
        z0 = np.r_[self.state, self.work]
        solution = solve_ivp(self.rhs, (t, t_end), z0, method="DOP853", rtol=self.rtol,
                             atol=self.atol, events=functions, dense_output=True)
        if solution.status == -1:
            raise PlanarReferenceError(f"planar reference (DOP853, rtol {self.rtol:g}) failed at "
                                       f"t = {solution.t[-1]!r} s: {solution.message}")
        end, terminal = float(solution.t[-1]), None
        if solution.status == 1:
            for index, name in enumerate(names):
                if functions[index].terminal and len(solution.t_events[index]) \
                        and solution.t_events[index][-1] == end:
                    terminal = name
                    break
        if "peak" in names:
            passed = self.passed_impact(solution, names, t)
            if passed is not None and passed <= end:
                end, terminal = passed, "impact"
        for index, name in enumerate(names):
            if name == "unstable" and len(solution.t_events[index]) \
                    and solution.t_events[index][0] <= end and math.isnan(self.t_unstable):
                self.t_unstable = float(solution.t_events[index][0])
            if name in ("peak", "slip turn"):
                for time, z in zip(solution.t_events[index], solution.y_events[index]):
                    if time <= end:
                        self.note(float(time), z)
        final = solution.sol(end) if end != float(solution.t[-1]) else solution.y[:, -1]
        self.time_in_mode[MODE_NAMES[self.mode]] += end - t
        self.state, self.work = np.array(final[:6], dtype=float), np.array(final[6:], dtype=float)
        if terminal == "impact":
            self.state[2] = 0.0
        self.project()
        self.note(end, self.state)
        return end, terminal

    # ------------------------------------------------------------ transitions
    def after_event(self, t, terminal):
        """Apply the transition of a terminal event."""
        mode = self.mode
        if terminal == "overturn":
            self.record(t, "overturn", mode, mode)
            raise _Stop("overturned", "")
        if terminal == "lift-off":
            self.set_mode(t, FLIGHT, kind="lift-off")
        elif terminal == "impact":
            self.impact(t, -self.side)
            # impact() resolves a block turned back onto the corner on the table with the
            # two-corner problem; the bound is a safeguard
            for _ in range(MAX_IMMEDIATE_IMPACTS):
                if not (self.mode in (ROCK, SLIDE_ROCK) and self.state[2] == 0.0
                        and self.side * self.state[5] < 0.0):
                    break
                self.impact(t, -self.side)
            else:
                raise _Stop("inconsistent", f"more than {MAX_IMMEDIATE_IMPACTS} impacts at "
                            f"t = {t!r} s, each turning the block onto the other corner")
        elif terminal == "slip":
            _, _, _, force, _ = self.solution(t, self.state)
            self.enter_contact(t, SLIDE_ROCK, self.side, -1 if force > 0 else 1, "slip", mode)
        elif terminal == "stick" and mode == SLIDE:
            self.state[3] = 0.0
            if self.rest_holds(t):
                self.set_mode(t, REST, kind="stick")
                if self.t_rest == -math.inf:   # a slide an impact left ends the rocking
                    self.t_rest = t
            else:
                self.leave_flat(t, "reverse")
        elif terminal == "stick":  # SLIDE_ROCK: the corner stops slipping
            r_x, r_y = self.geometry.arm(self.side, self.state[2])
            self.state[3] = r_y * self.state[5]
            _, _, _, force, normal = self.solution(t, self.state, ROCK)
            if abs(force) <= self.mu_s * normal:
                self.enter_contact(t, ROCK, self.side, self.sigma, "stick", mode)
            else:
                self.enter_contact(t, SLIDE_ROCK, self.side, -1 if force > 0 else 1, "reverse",
                                   mode)
        elif terminal is not None and terminal.startswith("landing"):
            if self.state[2] == 0.0 and self.state[5] == 0.0:
                self.flat_landing(t)
            else:
                self.impact(t, int(terminal[len("landing"):]))

    # ------------------------------------------------------------------ run
    def run(self, theta0, theta_dot0, x_dot0):
        motion, geometry = self.motion, self.geometry
        t_grid = motion.t
        ug_all, vg_all = motion.horizontal, motion.vertical_or_zero
        n = t_grid.size
        self.state = np.zeros(6)
        self.work = np.zeros(2)
        self.side, self.sigma, self.pivot = 1, 1, 0.0
        self.rest_until = -math.inf
        self.mode = REST
        self.interval = (ug_all[0], ug_all[min(1, n - 1)], vg_all[0], vg_all[min(1, n - 1)],
                         t_grid[0], t_grid[min(1, n - 1)])
        r_x, r_y = geometry.arm(1, 0.0)
        self.state[:] = [0.0, geometry.h, 0.0, 0.0, 0.0, 0.0]
        t = float(t_grid[0])
        status, message = "completed", ""
        if theta0 != 0.0 or theta_dot0 != 0.0:
            side = 1 if theta0 > 0 or (theta0 == 0 and theta_dot0 > 0) else -1
            r_x, r_y = geometry.arm(side, theta0)
            # tilted about its corner standing at its rest position X_s = -s b
            self.pivot = -side * geometry.b_of(side)
            self.state[:] = [self.pivot - r_x, -r_y, theta0, r_y * theta_dot0 + x_dot0,
                             -r_x * theta_dot0, theta_dot0]
            self.side = side
            mode = SLIDE_ROCK if x_dot0 != 0.0 else ROCK
            self.sigma = 1 if x_dot0 > 0 else -1
            self.mode = mode
        elif x_dot0 != 0.0:
            self.state[3] = x_dot0
            self.mode, self.sigma = SLIDE, (1 if x_dot0 > 0 else -1)
        energy_start = self.energy()
        if abs(theta0) >= geometry.alpha_of(1 if theta0 > 0 else -1):
            self.t_unstable = t
        self.note(t, self.state)
        out = np.zeros((n, 6))
        modes = np.zeros(n, dtype=int)
        out[0], modes[0] = self.state, self.mode
        filled = 1
        started = False
        try:
            for k in range(n - 1):
                t0, t1 = float(t_grid[k]), float(t_grid[k + 1])
                self.interval = (ug_all[k], ug_all[k + 1], vg_all[k], vg_all[k + 1], t0, t1)
                if not started:
                    started = True
                    if self.mode in (ROCK, SLIDE_ROCK):
                        initial = self.mode
                        self.enter_contact(t, initial, self.side, self.sigma, "start", initial)
                        if self.mode == initial:
                            self.events.pop()  # the initial state is no transition
                stalled = segments = 0
                while t < t1:
                    segments += 1
                    if segments > MAX_SEGMENTS_PER_INTERVAL:
                        raise PlanarReferenceError(
                            f"planar reference: more than {MAX_SEGMENTS_PER_INTERVAL} segments "
                            f"in the input interval [{t0!r}, {t1!r}] s")
                    if self.mode == REST:
                        begin = max(t, self.rest_until)
                        if begin >= t1:
                            self.time_in_mode["rest"] += t1 - t
                            t = t1
                            break
                        failure = self.rest_until_failure(begin, t1)
                        if failure is None:
                            self.time_in_mode["rest"] += t1 - t
                            t = t1
                            break
                        self.time_in_mode["rest"] += failure - t
                        t = failure
                        self.leave_flat(t, "start")
                        continue
                    end, terminal = self.integrate_segment(t, t1)
                    stalled = stalled + 1 if end <= t else 0
                    if stalled > MAX_STALLED_SEGMENTS:
                        raise PlanarReferenceError(
                            f"planar reference made no progress at t = {t!r} s "
                            f"({MAX_STALLED_SEGMENTS} segments ended where they began)")
                    t = end
                    self.after_event(t, terminal)
                out[k + 1], modes[k + 1] = self.state, self.mode
                filled = k + 2
        except _Stop as stop:
            status, message = stop.status, stop.message
            if status != "overturned":
                self.record(t, status, self.mode, self.mode)
        t_overturn = t if status == "overturned" else math.nan
        events = self.events
        slip_end = self.state[0] + geometry.h * math.sin(self.state[2])
        return PlanarReferenceResult(
            block=self.block, motion=motion, cor=self.cor, friction=self.friction,
            t=np.array(t_grid[:filled], dtype=float), x=out[:filled, 0], y=out[:filled, 1],
            theta=out[:filled, 2], x_dot=out[:filled, 3], y_dot=out[:filled, 4],
            theta_dot=out[:filled, 5], mode=modes[:filled],
            event_times=np.array([e[0] for e in events], dtype=float),
            event_kinds=tuple(e[1] for e in events),
            event_mode_before=np.array([e[2] for e in events], dtype=int),
            event_mode_after=np.array([e[3] for e in events], dtype=int),
            impact_times=np.array([i[0] for i in self.impacts], dtype=float),
            impact_velocities=np.array([i[1] for i in self.impacts], dtype=float),
            peak_slip=float(self.peak_slip), t_peak_slip=float(self.t_peak_slip),
            peak_base_slip=float(self.peak_base_slip),
            t_peak_base_slip=float(self.t_peak_base_slip),
            residual_slip=float(slip_end), max_abs_theta=float(self.max_abs_theta),
            t_max=float(self.t_max), t_unstable=float(self.t_unstable),
            t_overturn=float(t_overturn),
            t_rest=float(self.t_rest) if self.t_rest != -math.inf else math.nan,
            friction_work=float(self.work[0]),
            input_work=float(self.work[1]), impact_loss=float(self.impact_loss),
            energy_start=float(energy_start), energy_end=float(self.energy()),
            capped_impacts=int(self.capped), status=status, message=message,
            time_in_mode=dict(self.time_in_mode))
