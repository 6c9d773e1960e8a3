"""The stack's event-driven integration: DOP853 (SciPy) between events, events located.

Between two input samples the table's acceleration is linear, so each input interval is
integrated on its own (``solve_ivp``, DOP853) and its right-hand side is smooth. Inside an
interval a pattern runs until an event: an open interface landing (``s_j phi_j = 0``: the
impact law, then the pattern chosen afresh), a flat interface's corner force reaching
zero (uplift: the pattern chosen afresh), an interface's rotation reaching pi/2 (the
block above it overturned: the run stops). The rest pattern has no motion to integrate:
its corner forces are linear in time inside an interval and their zero is found exactly.

Choosing a pattern (acceleration-level complementarity)
-------------------------------------------------------
At an uplift the closing force is zero and the flat and the opened patterns have the same
accelerations, so the choice is made just after the event, at ``t + delta``
(``delta = 1e-8 / p_max``) with the state carried along the current pattern: a candidate
is consistent when every flat corner's normal force is >= -tol (``tol = 1e-12`` times the
weight of the lightest block) and every interface it opens accelerates open (``s_j phi_j'' > 0``).
The uplift events fire at a corner force of -tol, so that a force touching zero and
recovering (grazing) starts nothing. The consistent candidate with the fewest open
interfaces is kept; how many were consistent is recorded with the event.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from shaketable.core.constants import G
from shaketable.models.stack.impact import cor_impact, plastic_impact
from shaketable.models.stack.physics import (
    Chain,
    accelerations,
    candidate_levels,
    energy,
    interface_forces,
    state_forces,
    table_power,
)
from shaketable.numerics.cascade import cascade_rest_time

#: Relative force tolerance of the rest and flat contacts (times the lightest block's weight).
FORCE_TOLERANCE = 1e-12
#: Look-ahead of the pattern choice, times 1 / p_max [s].
LOOKAHEAD = 1e-8
#: Up to this many blocks every candidate pattern is tried (and the consistent ones
#: counted); above it the search stops at the first number of open interfaces that has one.
FULL_ENUMERATION = 3
#: Rates below FLOOR alpha_min p_max and rotations below FLOOR alpha_min after an impact
#: are rest (the noise level of a landing).
FLOOR = 1e-10
#: Events in a row at one instant before the run is declared stalled.
MAX_EVENTS_AT_ONE_INSTANT = 200
#: Events in one input interval before the run is declared endless (impacts without end:
#: contacts chattering, each flight shorter than the last, that neither the cascades'
#: closed forms nor the no-progress count catches); a run has thousands at most.
MAX_EVENTS_PER_INTERVAL = 100_000


class StackStalled(RuntimeError):
    """The stack's integration cannot go on (no consistent pattern, no progress, a failed
    step); the message says which and where."""


class StackChatter(StackStalled):
    """Events without end: :data:`MAX_EVENTS_AT_ONE_INSTANT` in a row without progress, or
    more than :data:`MAX_EVENTS_PER_INTERVAL` in one input interval (contacts chattering in
    a way the engines do not resolve). Which run does this depends on the tolerance's
    steps: :func:`shaketable.models.stack.model.integrate_retrying` runs it again at a
    tighter tolerance."""


class Ground:
    """The table's accelerations inside one input interval (linear) [m/s^2]."""

    def __init__(self, t0, t1, u0, u1, v0, v1) -> None:
        self.t0, self.span = t0, t1 - t0
        self.u0, self.du, self.v0, self.dv = u0, u1 - u0, v0, v1 - v0

    def __call__(self, t):
        x = (t - self.t0) / self.span
        return self.u0 + self.du * x, self.v0 + self.dv * x


def pattern_of(phi, phi_dot):
    """The pattern a state implies: the sign of phi, or of phi' where phi is zero."""
    pattern = []
    for angle, rate in zip(phi, phi_dot):
        value = angle if angle != 0.0 else rate
        pattern.append(0 if value == 0.0 else (1 if value > 0 else -1))
    return tuple(pattern)


class Run:
    """One run's state, its records and the event handling (see the module's docstring)."""

    def __init__(self, stack, motion, law: str, cor: float, theta0, theta_dot0, rtol: float,
                 rest_tolerance: float, max_recorded_events: int) -> None:
        self.chain = Chain.of(stack)
        self.n = self.chain.n
        self.law, self.cor, self.rtol = law, cor, rtol
        self.rest_tolerance = rest_tolerance
        self.max_recorded = max_recorded_events
        self.delta = LOOKAHEAD / stack.p_max
        self.tol_force = FORCE_TOLERANCE * G * float(stack.m.min())
        scale = stack.alpha_min
        self.alpha, self.alpha_p = scale, scale * stack.p_max
        self.work = 0.0   # the table's work on the blocks since the start [J]
        self.atol = np.concatenate([np.full(self.n, rtol * scale),
                                    np.full(self.n, rtol * scale * stack.p_max),
                                    [rtol * float(G * stack.m.sum())
                                     * float(np.hypot(stack.b, stack.h).max())]])
        self.t = motion.t
        self.ug = motion.horizontal
        self.vg = motion.vertical_or_zero
        self.phi = np.diff(np.asarray(theta0, dtype=float), prepend=0.0)
        self.phi_dot = np.diff(np.asarray(theta_dot0, dtype=float), prepend=0.0)
        self.pattern = pattern_of(self.phi, self.phi_dot)
        self.events: list[dict] = []
        self.n_events = 0
        self.status = "completed"
        self.t_overturn = math.nan
        self.overturned_block = -1
        self.t_airborne = math.nan
        self.t_tension = math.nan
        self.rest_until = -math.inf
        self.steps = self.evaluations = 0
        self.stalled = 0
        self.interval_events = 0
        self.energy_reference = float(G * stack.m.sum()) * float(np.hypot(stack.b, stack.h).max())

    # ----------------------------------------------------------------- records
    def record(self, time, kind, interface=-1, before=None, after=None, **values) -> None:
        self.n_events += 1
        if len(self.events) < self.max_recorded:
            self.events.append(dict(t=time, kind=kind, interface=interface,
                                    pattern_before=before, pattern_after=after, **values))

    # ----------------------------------------------------------------- choice
    def choose(self, time, ground, reason: str, interface: int = -1, end=math.inf) -> float:
        """Choose the pattern at ``time`` among the candidates (module docstring); the time
        the run goes on from.

        When the pattern changes the run goes on from the look-ahead ``time + delta`` (at
        most ``end``), with the state carried there along the old pattern (an error of
        order delta^3 in the newly opened interfaces, whose phi'' is of order delta there):
        the new pattern then starts with its opening acceleration strictly positive.

        An open interface at ``phi = 0`` that does not separate (``s phi' <= FLOOR alpha p``:
        left there by landings at the noise level) is closed first, its rate of rounding
        size dropped, and chosen with the flat ones: its landing event could not fire if it
        turned the other way, nor its overturn.
        """
        stuck = [j for j in range(self.n) if self.pattern[j] != 0 and self.phi[j] == 0.0
                 and self.pattern[j] * self.phi_dot[j] <= FLOOR * self.alpha_p]
        if stuck:
            pattern = list(self.pattern)
            for j in stuck:
                pattern[j] = 0
                self.phi_dot[j] = 0.0
            self.pattern = tuple(pattern)
        free = [j for j in range(self.n) if self.pattern[j] == 0]
        if not free:
            return time
        acceleration, _ = accelerations(self.chain, self.phi, self.phi_dot, self.pattern,
                                        *ground(time))
        delta = min(self.delta, max(end - time, 0.0))
        phi = self.phi + self.phi_dot * delta + 0.5 * acceleration * delta ** 2
        phi_dot = self.phi_dot + acceleration * delta
        ug, vg = ground(time + delta)
        consistent = []
        for level in candidate_levels(self.pattern, free):
            for candidate in level:
                phi_ddot, forces = state_forces(self.chain, phi, phi_dot, candidate, ug, vg)
                good = all(candidate[j] * phi_ddot[j] > 0.0 for j in free if candidate[j] != 0)
                good = good and all(forces[j, 2] >= -self.tol_force
                                    and forces[j, 3] >= -self.tol_force
                                    for j in free if candidate[j] == 0)
                if good:
                    consistent.append(candidate)
            if consistent and self.n > FULL_ENUMERATION:
                break   # the fewest open interfaces: the levels above are not searched
        if not consistent:
            raise StackStalled(f"stack model: no consistent contact pattern at t = {float(time)!r} s "
                               f"(from {self.pattern}); the input is outside the model")
        best = min(consistent, key=lambda c: sum(s != 0 for s in c))
        if best == self.pattern:
            return time
        self.record(time, "uplift", interface, self.pattern, best, solutions=len(consistent),
                    reason=reason)
        self.work += delta * table_power(self.chain, self.phi, self.phi_dot, self.pattern,
                                         *ground(time))
        self.pattern, self.phi, self.phi_dot = best, phi, phi_dot
        return time + delta

    # ----------------------------------------------------------------- impact
    def impact(self, time, ground, interface: int, end: float) -> float:
        before = self.pattern
        energy_before = sum(energy(self.chain, self.phi, self.phi_dot, before))
        rate_before = self.phi_dot[interface]
        rates_before = self.phi_dot.copy()
        self.phi[interface] = 0.0
        if abs(rate_before) <= FLOOR * self.alpha_p and np.abs(rates_before).max() > \
                FLOOR * self.alpha_p:
            # a landing at the noise level while the stack moves: the interface closes (a
            # plastic landing held flat), whatever the law
            phi_dot, pattern = self.closure(time, ground, rates_before, before, interface)
            self.phi_dot, self.pattern = phi_dot, pattern
            self.record(time, "rest", interface, before, pattern, cascade=False,
                        energy_before=energy_before,
                        energy_after=sum(energy(self.chain, self.phi, phi_dot, pattern)))
            return self.choose(time, ground, "after a noise-level landing", interface, end)
        if self.law == "plastic":
            phi_dot, pattern, solutions, _ = plastic_impact(self.chain, self.phi, self.phi_dot,
                                                            before, interface)
            noise = self.noise_flights(time, ground, phi_dot, pattern, interface)
            if noise:
                # the impact opens other interfaces with flights below the resolution: they
                # are held flat (the landing's own rebound is the cascade's, below)
                phi_dot, pattern = self.closure(time, ground, rates_before, before, interface,
                                                held=noise, skip=interface)
        else:
            phi_dot, pattern = cor_impact(self.chain, self.phi, self.phi_dot, before, interface,
                                          self.cor)
            solutions = 1
        self.phi_dot, self.pattern = phi_dot, pattern
        energy_after = sum(energy(self.chain, self.phi, self.phi_dot, pattern))
        self.record(time, "impact", interface, before, pattern, rate_before=rate_before,
                    rate_after=phi_dot[interface], energy_before=energy_before,
                    energy_after=energy_after, solutions=solutions)
        # a landing at the noise level (a force that barely crossed zero, the end of a
        # chatter of several interfaces): the stack is at rest
        if (np.abs(phi_dot).max() <= FLOOR * self.alpha_p and np.abs(self.phi).max()
                <= FLOOR * self.alpha):
            self.record(time, "rest", interface, pattern, (0,) * self.n, cascade=True,
                        energy_before=energy_after,
                        energy_after=sum(energy(self.chain, 0.0 * self.phi, 0.0 * phi_dot,
                                                (0,) * self.n)))
            self.phi, self.phi_dot, self.pattern = np.zeros(self.n), np.zeros(self.n), (0,) * self.n
            return self.choose(time, ground, "after rest", interface, end)
        # an endless cascade of landings of this interface, summed in closed form: the
        # flights shrink by the ratio of this impact and last 2|phi'| / deceleration
        if pattern[interface] != 0 and rate_before != 0.0:
            ratio = abs(phi_dot[interface] / rate_before)
            phi_ddot, _ = accelerations(self.chain, self.phi, self.phi_dot, pattern,
                                        *ground(time))
            deceleration = -pattern[interface] * phi_ddot[interface]
            remaining = cascade_rest_time(phi_dot[interface], deceleration, ratio)
            # a rebound pushed back whose flight would rise less than the integrator's
            # absolute tolerance (rtol alpha_min) is noise: it ends here too (early by the
            # series' length, which can exceed rest_tolerance: docs/stack.md, Cascades)
            if deceleration > 0.0 and phi_dot[interface] ** 2 <= 2.0 * deceleration * self.atol[0]:
                remaining = 0.0
            if remaining <= self.rest_tolerance and sum(s != 0 for s in pattern) == 1:
                # the only moving interface: the stack rests at the cascade's end
                self.record(time + remaining, "rest", interface, pattern, (0,) * self.n,
                            cascade=True, energy_before=energy_after,
                            energy_after=sum(energy(self.chain, self.phi, 0.0 * self.phi_dot,
                                                    (0,) * self.n)))
                self.phi_dot = np.zeros(self.n)
                self.pattern = (0,) * self.n
                self.rest_until = time + remaining
                return time
            if remaining <= self.rest_tolerance:
                # the others move on: this interface closes now (a plastic landing held
                # flat), at most rest_tolerance early (or the series' length: above)
                phi_dot, closed = self.closure(time, ground, rates_before, before, interface)
                energy_closed = sum(energy(self.chain, self.phi, phi_dot, closed))
                self.record(time, "rest", interface, pattern, closed, cascade=True,
                            energy_before=energy_after, energy_after=energy_closed)
                self.phi_dot, self.pattern = phi_dot, closed
        if all(s == 0 for s in self.pattern):
            self.phi_dot = np.zeros(self.n)
        return self.choose(time, ground, "after impact", interface, end)

    def noise_flights(self, time, ground, phi_dot, pattern, skip: int = -1) -> list:
        """The interfaces other than ``skip`` open at zero gap whose flight would rise less
        than the integrator's absolute tolerance (rtol alpha_min): noise, below what the
        integration resolves."""
        candidates = [k for k in range(self.n) if k != skip and pattern[k] != 0
                      and self.phi[k] == 0.0]
        if not candidates:
            return []
        phi_ddot, _ = accelerations(self.chain, self.phi, phi_dot, pattern, *ground(time))
        return [k for k in candidates if -pattern[k] * phi_ddot[k] > 0.0
                and phi_dot[k] ** 2 <= -2.0 * pattern[k] * phi_ddot[k] * self.atol[0]]

    def closure(self, time, ground, rates_before, before, interface, held=None,
                skip: int = -1):
        """``(phi', pattern)`` after the landing of ``interface`` held flat (the plastic law
        with that interface closed, from the rates ``rates_before`` and pattern ``before``
        of the landing), with every interface it would open at zero gap with a flight
        rising less than the integrator's absolute tolerance held flat too (``held``: the
        interfaces held from the start, by default ``interface``; ``skip``: one never
        held).

        Such a flight is noise, as the landing interface's own rebound is: left open, it
        lands at once, its closure opens the first one again at a smaller rate, and so on
        (a cascade over two or more interfaces whose flights shrink geometrically). The
        limit of those alternating plastic landings, each an energy projection of the
        velocities, is the projection with all of them held: the law with them closed.
        """
        held = [interface] if held is None else list(held)
        while True:
            phi_dot, pattern, _, _ = plastic_impact(self.chain, self.phi, rates_before, before,
                                                    interface, closed=tuple(held))
            noise = [k for k in self.noise_flights(time, ground, phi_dot, pattern, skip)
                     if k not in held]
            if not noise:
                return phi_dot, pattern
            held += noise

    # ----------------------------------------------------------------- rest
    def rest_uplift(self, t, t_end, ground):
        """The first time in [t, t_end] a rest corner force reaches -tol, or None."""
        zero = np.zeros(self.n)
        _, start = state_forces(self.chain, zero, zero, self.pattern, *ground(t))
        _, end = state_forces(self.chain, zero, zero, self.pattern, *ground(t_end))
        first = None
        for j in range(self.n):
            for corner in (2, 3):
                a, b = start[j, corner] + self.tol_force, end[j, corner] + self.tol_force
                if b >= 0.0:
                    continue
                time = t if a <= 0.0 else t + (t_end - t) * a / (a - b)
                if first is None or time < first[0]:
                    first = (time, j)
        return first

    # ----------------------------------------------------------------- one interval
    def segment(self, t, t_end, ground):
        """Integrate the current (moving) pattern from ``t`` to the first event or ``t_end``."""
        chain, pattern, n = self.chain, self.pattern, self.n
        open_ = [j for j in range(n) if pattern[j] != 0]
        flat = [j for j in range(n) if pattern[j] == 0]
        for j in open_:
            # an interface already on the wrong side of its pivot (two landings within the
            # event location's rounding, the later one passed by ~1e-7 rad) or leaving phi = 0
            # the wrong way: it lands now (its events could not fire from there)
            if pattern[j] * self.phi[j] < 0.0 or (self.phi[j] == 0.0
                                                   and pattern[j] * self.phi_dot[j] < 0.0):
                self.phi[j] = 0.0
                return t, ("impact", j)
        cache: dict = {}

        def evaluate(time, y):
            key = (time, y.tobytes())
            if key not in cache:
                if len(cache) > 64:
                    cache.clear()
                ug, vg = ground(time)
                phi_ddot, (theta, theta_dot, centroid, jacobian, centripetal) = accelerations(
                    chain, y[:n], y[n:2 * n], pattern, ug, vg)
                forces = interface_forces(chain, pattern, ug, vg, theta, np.cumsum(phi_ddot),
                                          centroid, jacobian, centripetal) if flat else None
                # the power of the table's inertial forces -m u'', -m v'' (the work W)
                velocity = np.einsum("iak,k->ia", jacobian, theta_dot)
                power = -float((chain.m * (ug * velocity[:, 0] + vg * velocity[:, 1])).sum())
                cache[key] = (phi_ddot, forces, power)
            return cache[key]

        def rhs(time, y):
            phi_ddot, _, power = evaluate(time, y)
            return np.concatenate([y[n:2 * n], phi_ddot, [power]])

        events, meaning = [], []
        y0 = np.concatenate([self.phi, self.phi_dot, [self.work]])
        for j in open_:
            s = pattern[j]
            if self.phi[j] == 0.0 and self.phi_dot[j] == 0.0:
                # leaving phi = 0 from rest (an uplift: s phi'' > 0): s phi / elapsed^2
                # (-> s phi'' / 2 at the start) so that a flight shorter than a step is not
                # "found" at its start, where s phi and s phi' are zero
                opening = 0.5 * s * evaluate(t, y0)[0][j]
                if opening <= 0.0:
                    return t, ("impact", j)   # it cannot open: it lands now, at rate zero
                landing = (lambda time, y, j=j, s=s, opening=opening: opening if time <= t
                           else s * y[j] / (time - t) ** 2)
            elif self.phi[j] == 0.0:
                # leaving phi = 0: s phi / elapsed (-> s phi' at the start), likewise
                landing = (lambda time, y, j=j, s=s: s * y[n + j] if time <= t
                           else s * y[j] / (time - t))
            else:
                landing = (lambda time, y, j=j, s=s: s * y[j])
            landing.terminal, landing.direction = True, -1
            falling = (lambda time, y, j=j, s=s: 0.5 * math.pi - s * y[j])
            falling.terminal, falling.direction = True, -1
            events += [landing, falling]
            meaning += [("impact", j), ("overturn", j)]
        for j in flat:
            for corner in (2, 3):
                lift = (lambda time, y, j=j, c=corner: evaluate(time, y)[1][j, c] + self.tol_force)
                lift.terminal, lift.direction = True, -1
                events.append(lift)
                meaning.append(("lift", j))
        turning = len(events)
        for j in open_:
            peak = (lambda time, y, j=j: y[n + j])
            peak.terminal, peak.direction = False, 0
            events.append(peak)
            meaning.append(("turn", j))
        solution = solve_ivp(rhs, (t, t_end), y0, method="DOP853", rtol=self.rtol, atol=self.atol,
                             events=events)
        if any(pattern[meaning[index][1]] * y[meaning[index][1]] < 0.0
               for index in range(turning, len(meaning)) for y in solution.y_events[index]):
            # a turning point on the wrong side of a landing: the same steps again, with
            # their dense output, to find the landing before it (passed_landing)
            solution = solve_ivp(rhs, (t, t_end), y0, method="DOP853", rtol=self.rtol,
                                 atol=self.atol, events=events, dense_output=True)
        if solution.status == -1:
            raise StackStalled(f"stack model: DOP853 failed at t = {float(solution.t[-1])!r} s: "
                               f"{solution.message}")
        self.steps += len(solution.t) - 1
        self.evaluations += solution.nfev
        fired = [(times[0], index) for index, times in enumerate(solution.t_events[:turning])
                 if len(times)]
        passed = None if solution.sol is None else self.passed_landing(solution, t, pattern,
                                                                        meaning, turning)
        if passed is not None and (not fired or passed[0] < min(fired)[0]):
            time, j = passed
            y = solution.sol(time)
            self.phi, self.phi_dot, self.work = y[:n].copy(), y[n:2 * n].copy(), float(y[-1])
            self.phi[j] = 0.0
            return time, ("impact", j)
        if solution.status == 1:
            time, index = min(fired)
            y = solution.y_events[index][0]
            self.phi, self.phi_dot, self.work = y[:n].copy(), y[n:2 * n].copy(), float(y[-1])
            return time, meaning[index]
        self.phi, self.phi_dot = solution.y[:n, -1].copy(), solution.y[n:2 * n, -1].copy()
        self.work = float(solution.y[-1, -1])
        return t_end, None

    def passed_landing(self, solution, t, pattern, meaning, turning):
        """A landing a step passed without seeing it, as ``(time, interface)``, else None.

        The landing events test the sign of s phi at step ends only: a dip below zero that
        begins and ends inside one step is invisible to them, but its turning point is
        not (phi' = 0 on the wrong side). The landing is then the zero of s phi before that
        turning point on the step's dense output (Brent's method), as the single-block
        reference solver does.
        """
        found = None
        for index in range(turning, len(meaning)):
            j = meaning[index][1]
            s = pattern[j]
            earlier = t
            for tau, y in zip(solution.t_events[index], solution.y_events[index]):
                if s * y[j] >= 0.0:
                    earlier = tau
                    continue
                steps = solution.t[solution.t < tau]
                low = max(float(steps[-1]) if steps.size else t, earlier)
                side = (lambda x, j=j, s=s: s * float(solution.sol(x)[j]))
                if low <= t and self.phi[j] == 0.0 or side(low) <= 0.0:
                    break
                time = brentq(side, low, tau, xtol=1e-300, rtol=4 * np.finfo(float).eps)
                if found is None or time < found[0]:
                    found = (time, j)
                break
        return found

    def interval(self, k: int) -> bool:
        """Advance over the input interval k; False when the run stops."""
        t0, t1 = float(self.t[k]), float(self.t[k + 1])
        ground = Ground(t0, t1, self.ug[k], self.ug[k + 1], self.vg[k], self.vg[k + 1])
        support0, support1 = G + self.vg[k], G + self.vg[k + 1]
        if support0 <= 0.0 or support1 <= 0.0:
            self.status = "airborne"
            self.t_airborne = t0 if support0 <= 0.0 else t0 + (t1 - t0) * support0 / (support0 - support1)
            self.record(self.t_airborne, "airborne")
            return False
        t = t0
        self.interval_events = self.n_events
        while t < t1:
            if self.rest_until > t:
                if self.rest_until >= t1:
                    return True
                t = self.rest_until
            if self.rest_until > -math.inf and t >= self.rest_until:
                self.rest_until = -math.inf
                t = self.choose(t, ground, "after rest", end=t1)
            if all(s == 0 for s in self.pattern):
                found = self.rest_uplift(t, t1, ground)
                if found is None:
                    return True
                t_new, interface = found
                self.progress(t, t_new)
                t = self.choose(t_new, ground, "uplift", interface, t1)
                continue
            t_new, what = self.segment(t, t1, ground)
            self.progress(t, t_new)
            t = t_new
            if what is None:
                continue
            kind, interface = what
            if kind == "impact":
                t = self.impact(t, ground, interface, t1)
            elif kind == "overturn":
                self.status = "overturned"
                self.t_overturn = t
                self.overturned_block = interface
                self.record(t, "overturn", interface, self.pattern, self.pattern)
                return False
            else:
                t = self.choose(t, ground, "uplift", interface, t1)
        return True

    def progress(self, t, t_new) -> None:
        self.stalled = self.stalled + 1 if t_new <= t else 0
        if self.stalled > MAX_EVENTS_AT_ONE_INSTANT:
            raise StackChatter(f"stack model: {MAX_EVENTS_AT_ONE_INSTANT} events in a row at "
                               f"t = {float(t)!r} s without progress")
        if self.n_events - self.interval_events > MAX_EVENTS_PER_INTERVAL:
            raise StackChatter(f"stack model: more than {MAX_EVENTS_PER_INTERVAL:,} events in "
                               f"one input interval, the last at t = {float(t)!r} s: impacts "
                               "without end (contacts chattering, each flight shorter than "
                               "the last)")

    def sample(self, k):
        """theta, theta', theta'' of every block, the pattern and the contact forces at
        t[k]."""
        ug, vg = self.ug[k], self.vg[k]
        phi_ddot, forces = state_forces(self.chain, self.phi, self.phi_dot, self.pattern, ug, vg)
        return (np.cumsum(self.phi), np.cumsum(self.phi_dot), np.cumsum(phi_ddot),
                np.array(self.pattern), forces, self.work)


def integrate(stack, motion, *, law: str, cor: float, theta0, theta_dot0, rtol: float,
              rest_tolerance: float, max_recorded_events: int) -> dict:
    """Run the stack over ``motion``: the sampled histories and the events (a dict)."""
    run = Run(stack, motion, law, cor, theta0, theta_dot0, rtol, rest_tolerance,
              max_recorded_events)
    count = motion.t.size
    n = run.n
    theta, rate, acceleration = np.zeros((count, n)), np.zeros((count, n)), np.zeros((count, n))
    patterns = np.zeros((count, n), dtype=np.int8)
    forces = np.zeros((count, n, 4))
    work = np.zeros(count)
    first = Ground(float(motion.t[0]), float(motion.t[1]), run.ug[0], run.ug[1], run.vg[0],
                   run.vg[1])
    run.choose(float(motion.t[0]), first, "start", end=float(motion.t[0]))
    filled = 0
    theta[0], rate[0], acceleration[0], patterns[0], forces[0], work[0] = run.sample(0)
    filled = 1
    for k in range(count - 1):
        going = run.interval(k)
        if not going:
            break
        theta[k + 1], rate[k + 1], acceleration[k + 1], patterns[k + 1], forces[k + 1], \
            work[k + 1] = run.sample(k + 1)
        filled = k + 2
    return dict(run=run, filled=filled, theta=theta[:filled], rate=rate[:filled],
                acceleration=acceleration[:filled], patterns=patterns[:filled],
                forces=forces[:filled], work=work[:filled])
