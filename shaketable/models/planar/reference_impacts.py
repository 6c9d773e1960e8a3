"""The impacts of the planar block's SciPy reference (:mod:`shaketable.models.planar.reference`):
a corner impact, the mode it leaves, the summed cascade of impacts and the flat landing.

A base class of the reference's event loop (its run state lives there: ``state``,
``mode``, ``side``, ``sigma``, ``geometry``, ``impact_loss``, ...); the physics of the
impulse is :func:`~shaketable.models.planar.contact.impact_map` and
:func:`~shaketable.models.planar.contact.two_corner_impact`.
"""

from __future__ import annotations

import math

import numpy as np

from shaketable.models.planar.contact import impact_map, kinetic_energy, two_corner_impact
from shaketable.models.planar.shenton import REST, ROCK, SLIDE, SLIDE_ROCK
from shaketable.models.rocking.physics import cascade_rest_time


class ImpactTransitions:
    """The reference's transitions at an impact (methods of its event loop)."""

    def rho_of(self, corner):
        """The couple ratio of an impact of ``corner``: cor / c_H of that pivot (an
        asymmetric block's own), 1 for Housner's law."""
        geometry = self.geometry
        if self.cor == "housner" or geometry.c_plus == geometry.c_minus:
            return self.rho
        return self.cor / geometry.c_of(corner)

    def cascade_of(self, corner):
        """theta'+ / theta'- of a sticking rock-to-rock impact onto ``corner``."""
        if self.cor == "housner":
            return self.geometry.c_of(corner)
        return self.cascade_cor

    def impact(self, t, corner):
        """A corner impact at t (docs/planar.md, "Impacts"); at theta = 0 an impact that
        turns the block back onto the other corner, which is on the table, is followed by
        the two-corner problem."""
        before = self.mode
        pre = self.state.copy()
        energy_before = kinetic_energy(self.geometry, pre)
        self.impacts.append((t, pre[5]))
        velocities, _, sigma, capped = impact_map(self.geometry, pre, corner, self.rho_of(corner),
                                                   self.mu_s, self.mu_d)
        self.capped += capped
        self.state[3:6] = velocities
        self.side = corner
        mode = ROCK if sigma == 0 else SLIDE_ROCK
        if self.state[2] == 0.0 and corner * self.state[5] < 0.0:
            velocities, mode, side, sigma = two_corner_impact(self.geometry, self.state,
                                                              self.mu_s, self.mu_d)
            self.state[3:6] = velocities
            self.side = side or corner
        self.enter_after_impact(t, mode, sigma, "impact", before)
        if self.mode in (REST, SLIDE):
            self.t_rest = t if self.mode == REST else -math.inf   # -inf: rests when it stops
        self.impact_loss += energy_before - kinetic_energy(self.geometry, self.state)
        if self.state[2] == 0.0 and self.mode in (ROCK, SLIDE_ROCK) and pre[5] != 0.0:
            sticking = sigma == 0 and self.mode == ROCK and self.side == corner
            self.cascade(t, self.cascade_of(corner) if sticking else abs(self.state[5] / pre[5]))

    def enter_after_impact(self, t, mode, sigma, kind, before):
        """Enter the mode an impact left (flat: REST, which records t_rest, or SLIDE)."""
        if mode in (ROCK, SLIDE_ROCK):
            if sigma != 0:
                self.sigma = sigma
            self.enter_contact(t, mode, self.side, self.sigma, kind, before)
            return
        self.state[1:3] = [self.geometry.h, 0.0]
        if mode == REST:
            self.t_rest = t
            self.rest_until = t
        self.set_mode(t, mode, sigma=sigma if mode == SLIDE else None, kind=kind)

    def cascade(self, t, ratio):
        """The endless cascade of impacts of a decaying block, summed (as the rocking engine).

        ``ratio``: |theta'+ / theta'-| of each impact of the cascade (the cor of a
        sticking rock -> rock impact, exactly as the rocking engine; the ratio of
        this impact for a slipping one, e.g. frictionless). The cascade of a
        slipping corner ends flat at once, sliding at the corner's slip speed (REST if 0).
        """
        omega = self.state[5]
        deceleration = -self.side * self.solution(t, np.r_[self.state[:2], 0.0, 0.0, 0.0,
                                                           0.0])[2]
        if self.mode == SLIDE_ROCK and deceleration <= 0.0:
            # slide-rock tips away from theta = 0: the slip stops first and the block
            # returns to the table rocking (the pattern of a slipping cascade), so the
            # rocking deceleration (agreed with branch planar, 18:40)
            ug, vg = self.ground(t)
            deceleration = -self.tipping(self.side, ug, vg)
        remaining = cascade_rest_time(omega, deceleration, ratio)
        if (remaining == math.inf and ratio >= 1.0 and deceleration > 0.0
                and abs(omega) <= max(self.velocity_floor,
                                      0.5 * deceleration * self.rest_tolerance)):
            remaining = 0.0   # no decay, and impacts closer than the rest tolerance
        if omega == 0.0 or remaining <= self.rest_tolerance or (
                abs(omega) <= self.velocity_floor and remaining < math.inf):
            # a slipping corner's cascade ends sliding flat at the corner's slip speed
            x_dot = self.corner_slip_velocity(self.state) if self.mode == SLIDE_ROCK else 0.0
            self.impact_loss += kinetic_energy(self.geometry, self.state) - 0.5 * x_dot ** 2
            self.state[3:6] = [x_dot, 0.0, 0.0]
            if x_dot == 0.0:
                self.set_mode(t, REST, kind="cascade")
                self.rest_until = t + remaining
                self.t_rest = self.rest_until
            else:
                self.set_mode(t, SLIDE, sigma=1 if x_dot > 0 else -1, kind="cascade")
                self.t_rest = -math.inf

    def flat_landing(self, t):
        """A flat landing (theta = theta' = 0): the two-corner problem."""
        before = self.mode
        energy_before = kinetic_energy(self.geometry, self.state)
        velocities, mode, side, sigma = two_corner_impact(self.geometry, self.state,
                                                          self.mu_s, self.mu_d)
        self.state[3:6] = velocities
        if side:
            self.side = side
        self.enter_after_impact(t, mode, sigma, "flat landing", before)
        self.impact_loss += energy_before - kinetic_energy(self.geometry, self.state)
