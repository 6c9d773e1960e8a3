"""The interface every model offers, and the base class of its results.

A model is an object with a ``name``, a test that says whether an input is its own
(:meth:`Model.accepts`), a check of its options (:meth:`Model.validate`), one run
(:meth:`Model.run`) and many runs (:meth:`Model.run_many`). Its result derives from
:class:`ModelResult`, which gives every result the same four views: ``to_frame()``
(the time history), ``events_frame()`` (one row per event), ``summary()`` (one row of
scalars) and ``plot()`` (a figure, drawn by :mod:`shaketable.plots`).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

from shaketable.core.equality import fields_equal

if TYPE_CHECKING:   # pandas is loaded by the views that build a frame, not by a run
    import pandas as pd
    from matplotlib.figure import Figure


@runtime_checkable
class Model(Protocol):
    """What a model offers the package's front door and its batch."""

    name: str

    def accepts(self, subject: Any) -> bool:
        """Whether ``subject`` (what the user simulates) is this model's input."""
        ...

    def validate(self, subject: Any, options: Mapping[str, Any]) -> dict[str, Any]:
        """Check ``subject`` and ``options``; the options to run with (ValueError naming
        the parameter otherwise)."""
        ...

    def run(self, subject: Any, motion: Any, **options: Any) -> "ModelResult":
        """One run."""
        ...

    def run_many(self, subject: Any, motions: Iterable[Any], **options: Any) -> list["ModelResult"]:
        """Many runs of one subject, one per motion."""
        ...


class ModelResult:
    """Base of the models' results: the views every result offers.

    A subclass is a frozen dataclass; it implements :meth:`to_frame`,
    :meth:`events_frame`, :meth:`summary` and :meth:`_figure` (the ``.plot()`` delegate).
    Equality compares the fields by value (arrays included), so a result equals its
    pickled-and-loaded copy.
    """

    __eq__ = fields_equal

    def to_frame(self) -> pd.DataFrame:
        """The time history, one row per output time, SI units in the column names."""
        raise NotImplementedError

    def events_frame(self) -> pd.DataFrame:
        """One row per event (time [s], kind, and what the model records of it)."""
        raise NotImplementedError

    def summary(self) -> dict[str, Any]:
        """The scalar results, one entry each."""
        raise NotImplementedError

    def plot(self, *args: Any, **options: Any) -> "Figure":
        """The result's figure (see the model's plotting function for the options)."""
        return self._figure(*args, **options)

    def _figure(self, *args: Any, **options: Any) -> "Figure":
        raise NotImplementedError
