"""A compiled stack run's events: written by the engine (:func:`record`, compiled) and read
back into Python (:class:`CompiledRun`: its status, statistics and recorded events, as the
Python engine's dicts)."""

from __future__ import annotations

from shaketable.models.stack.compiled_physics import kernel
from shaketable.models.stack.layout import (
    F_T_AIRBORNE,
    F_T_OVERTURN,
    I_EVALUATIONS,
    I_EVENTS,
    I_OVERTURNED,
    I_RECORDED,
    I_STATUS,
    I_STEPS,
    IMPACT,
    KINDS,
    REASONS,
    REST,
    STATUSES,
    UPLIFT,
)


@kernel
def record(run, time, kind, interface, before, after, has_patterns, reals, integers):
    """Count an event and keep it while there is room (``reals``: rate before, rate after,
    energy before, energy after; ``integers``: solutions, cascade, reason; NaN / -1 absent)."""
    ist, ev_f, ev_i, ev_pb, ev_pa = run[4], run[7], run[8], run[9], run[10]
    ist[I_EVENTS] += 1
    k = ist[I_RECORDED]
    if k >= ev_f.shape[0]:
        return
    ist[I_RECORDED] = k + 1
    ev_f[k, 0] = time
    for q in range(4):
        ev_f[k, 1 + q] = reals[q]
    ev_i[k, 0] = kind
    ev_i[k, 1] = interface
    ev_i[k, 2] = integers[0]
    ev_i[k, 3] = integers[1]
    ev_i[k, 4] = integers[2]
    ev_i[k, 5] = has_patterns
    for j in range(before.size):
        ev_pb[k, j] = before[j]
        ev_pa[k, j] = after[j]


class CompiledRun:
    """What :func:`integrate` returns as ``run``: the events (dicts, as the Python engine's),
    the status and the statistics of one compiled run."""

    def __init__(self, fs, ist, ev_f, ev_i, ev_pb, ev_pa) -> None:
        self.status = STATUSES[int(ist[I_STATUS])]
        self.t_overturn = float(fs[F_T_OVERTURN])
        self.overturned_block = int(ist[I_OVERTURNED])
        self.t_airborne = float(fs[F_T_AIRBORNE])
        self.n_events = int(ist[I_EVENTS])
        self.steps, self.evaluations = int(ist[I_STEPS]), int(ist[I_EVALUATIONS])
        count = int(ist[I_RECORDED])
        self._recorded = (ev_f[:count], ev_i[:count], ev_pb[:count], ev_pa[:count])

    @property
    def events(self) -> list[dict]:
        """The recorded events as dicts (their numbers as Python floats and ints, their
        patterns as tuples)."""
        return self.scaled_events(1.0)

    def scaled_events(self, scale: float) -> list[dict]:
        """The recorded events with their energies [J] times ``scale`` (the stack's mass
        scale; 1: as recorded), built column by column: one conversion per column, not one
        per number."""
        reals, integers, before, after = self._recorded
        energies = reals[:, 3:5] * scale if scale != 1.0 else reals[:, 3:5]
        columns = zip(reals[:, 0].tolist(), integers[:, 0].tolist(),
                      integers[:, 1].tolist(), map(tuple, before.tolist()),
                      map(tuple, after.tolist()), integers[:, 5].tolist(),
                      reals[:, 1].tolist(), reals[:, 2].tolist(), energies[:, 0].tolist(),
                      energies[:, 1].tolist(), integers[:, 2].tolist(),
                      integers[:, 3].tolist(), integers[:, 4].tolist())
        return [self.event(*row) for row in columns]

    @staticmethod
    def event(t, kind, interface, before, after, patterns, rate_before, rate_after,
              energy_before, energy_after, solutions, cascade, reason) -> dict:
        """One recorded event as a dict (the keys of the Python engine's, in its order)."""
        if patterns != 1:
            before = after = None
        if kind == IMPACT:
            return {"t": t, "kind": "impact", "interface": interface, "pattern_before": before,
                    "pattern_after": after, "rate_before": rate_before,
                    "rate_after": rate_after, "energy_before": energy_before,
                    "energy_after": energy_after, "solutions": solutions}
        if kind == UPLIFT:
            return {"t": t, "kind": "uplift", "interface": interface, "pattern_before": before,
                    "pattern_after": after, "solutions": solutions,
                    "reason": REASONS[reason]}
        if kind == REST:
            return {"t": t, "kind": "rest", "interface": interface, "pattern_before": before,
                    "pattern_after": after, "cascade": bool(cascade),
                    "energy_before": energy_before, "energy_after": energy_after}
        return {"t": t, "kind": KINDS[kind], "interface": interface, "pattern_before": before,
                "pattern_after": after}
