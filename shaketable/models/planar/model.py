"""The planar model behind the package's one interface (:mod:`shaketable.models.base`)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from shaketable.core.geometry import Block
from shaketable.models.base import ModelResult


class PlanarModel:
    """The planar block with friction (rest, slide, rock, slide-rock, flight): a
    :class:`Block` with ``friction=`` a :class:`~shaketable.models.sliding.result.Friction`.

    One run is :func:`shaketable.simulate` with ``friction`` (:func:`~shaketable.models.planar.run.simulate_planar`)
    and gives a :class:`~shaketable.models.planar.result.PlanarResult`; many runs at once,
    as a table, are :func:`~shaketable.models.planar.batch.simulate_many_planar`.
    """

    name: str = "planar"
    #: A Block with these options is this model's input, not the rocking model's.
    selects: tuple[str, ...] = ("friction",)
    #: Its engine is compiled with numba (on first use, then cached).
    compiled: bool = True

    def accepts(self, subject: Any) -> bool:
        return isinstance(subject, Block)

    def validate(self, subject: Any, options: Mapping[str, Any]) -> dict[str, Any]:
        """The options of ``shaketable.simulate``; ``friction`` is required (ValueError)."""
        options = dict(options)
        if options.get("friction") is None:
            raise ValueError("the planar model needs friction: give friction=Friction(mu_s, mu_d)")
        options.pop("model", None)
        return options

    def run(self, subject: Any, motion: Any, **options: Any) -> ModelResult:
        from shaketable.models.api import simulate

        return simulate(subject, motion, **self.validate(subject, options))

    def run_many(self, subject: Any, motions: Iterable[Any], **options: Any) -> list[ModelResult]:
        return [self.run(subject, motion, **options) for motion in motions]


PLANAR_MODEL = PlanarModel()
