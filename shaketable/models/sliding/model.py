"""The sliding model behind the package's one interface (:mod:`shaketable.models.base`)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from shaketable.core.geometry import Block
from shaketable.models.base import ModelResult

#: The options of ``shaketable.simulate`` that the sliding block does not take, at the values
#: that mean "not given".
NOT_TAKEN = {"cor": None, "theta0": 0.0, "theta_dot0": 0.0, "duration": None, "method": "fast",
             "rtol": None, "subdivisions": 4, "output_dt": 0.005, "rest_tolerance": None,
             "max_recorded_impacts": 100_000, "top_force": 0.0}


class SlidingModel:
    """The block that only slides (Coulomb stick-slip, exact between samples): a
    :class:`Block` with ``friction=``, chosen by name (``model="sliding"``; a Block with
    friction is otherwise the planar model's).

    One run is :func:`~shaketable.models.sliding.engine.slide` and gives a
    :class:`~shaketable.models.sliding.result.SlidingResult`; many motions and frictions
    at once, as a table of peak slips, are
    :func:`~shaketable.models.sliding.engine.peak_slips`.
    """

    name: str = "sliding"
    selects: tuple[str, ...] = ("friction",)
    #: Its engine is compiled with numba (on first use, then cached).
    compiled: bool = True

    def accepts(self, subject: Any) -> bool:
        return isinstance(subject, Block)

    def validate(self, subject: Any, options: Mapping[str, Any]) -> dict[str, Any]:
        """The options of :func:`~shaketable.models.sliding.engine.slide` from those of
        ``shaketable.simulate``: ``friction`` required, the rocking options left at their
        defaults (ValueError naming one that is not)."""
        options = dict(options)
        options.pop("model", None)
        for key, default in NOT_TAKEN.items():
            if key in options and options.pop(key) != default:
                raise ValueError(f"{key} is not offered by the sliding model")
        if options.get("friction") is None:
            raise ValueError("the sliding model needs friction: give friction=Friction(mu_s, mu_d)")
        return options

    def run(self, subject: Any, motion: Any, **options: Any) -> ModelResult:
        from shaketable.models.sliding.engine import slide

        options = self.validate(subject, options)
        if motion is None:
            raise ValueError("the sliding model needs a motion (a block at rest does not slide)")
        return slide(motion, options.pop("friction"), block=subject, **options)

    def run_many(self, subject: Any, motions: Iterable[Any], **options: Any) -> list[ModelResult]:
        return [self.run(subject, motion, **options) for motion in motions]


SLIDING_MODEL = SlidingModel()
