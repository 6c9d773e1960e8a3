"""The rocking model behind the package's one interface (:mod:`shaketable.models.base`)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from shaketable.core.geometry import AsymmetricBlock, Block
from shaketable.models.base import ModelResult


class RockingModel:
    """The rocking block, Eqs. (2-13)/(2-14) with impacts: a :class:`Block` or an
    :class:`AsymmetricBlock` without friction.

    One run is :func:`shaketable.simulate` (``models.api``) and gives a
    :class:`~shaketable.models.rocking.result.RockingResult` (an
    :class:`~shaketable.models.rocking.asymmetric_result.AsymmetricResult` for an
    asymmetric block); many runs at once, as a table, are
    :func:`~shaketable.models.rocking.batch.simulate_many`.
    """

    name: str = "rocking"
    #: The options that choose this model over another that takes the same input: none.
    selects: tuple[str, ...] = ()
    #: Its engine is compiled with numba (on first use, then cached).
    compiled: bool = True

    def accepts(self, subject: Any) -> bool:
        return isinstance(subject, (Block, AsymmetricBlock))

    def validate(self, subject: Any, options: Mapping[str, Any]) -> dict[str, Any]:
        """The options of ``shaketable.simulate`` without ``friction``, which this model
        does not take (ValueError)."""
        options = dict(options)
        if options.pop("friction", None) is not None:
            raise ValueError("friction is not offered by the rocking model (the planar model "
                             "takes it: model='planar')")
        options.pop("model", None)
        return options

    def run(self, subject: Any, motion: Any, **options: Any) -> ModelResult:
        from shaketable.models.api import simulate

        return simulate(subject, motion, **self.validate(subject, options))

    def run_many(self, subject: Any, motions: Iterable[Any], **options: Any) -> list[ModelResult]:
        return [self.run(subject, motion, **options) for motion in motions]


ROCKING_MODEL = RockingModel()
