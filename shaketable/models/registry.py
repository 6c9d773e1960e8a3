"""The models by name, and the model whose input a user gave."""

from __future__ import annotations

from typing import Any

from shaketable.models.base import Model
from shaketable.models.planar.model import PLANAR_MODEL
from shaketable.models.rocking.model import ROCKING_MODEL
from shaketable.models.sliding.model import SLIDING_MODEL
from shaketable.models.stack.model import STACK_MODEL

#: Every model laid out in :mod:`shaketable.models`, by name.
MODELS: dict[str, Model] = {model.name: model for model in (
    ROCKING_MODEL, PLANAR_MODEL, SLIDING_MODEL, STACK_MODEL)}


def model_for(subject: Any, options: dict[str, Any] | None = None) -> Model | None:
    """The model whose input ``subject`` is, given the run's ``options``; ``None`` if none.

    Among the models that accept ``subject``, those whose selecting options
    (``model.selects``, e.g. the planar model's ``friction``) are all given (not None);
    of these, the one selected by the most options, the first in :data:`MODELS` on a tie:
    a :class:`~shaketable.core.geometry.Block` is the rocking model's, a Block with
    ``friction`` the planar model's (the sliding model, which takes the same, is chosen
    by name only), a :class:`~shaketable.models.stack.Stack` the stack model's.
    """
    options = options or {}
    chosen, most = None, -1
    for model in MODELS.values():
        selects = getattr(model, "selects", ())
        if model.accepts(subject) and len(selects) > most \
                and all(options.get(key) is not None for key in selects):
            chosen, most = model, len(selects)
    return chosen


def model_named(name: str, subject: Any) -> Model:
    """The model ``name`` of :data:`MODELS`, checked to accept ``subject`` (ValueError)."""
    if name not in MODELS:
        raise ValueError(f"model must be one of {sorted(MODELS)}, got {name!r}")
    model = MODELS[name]
    if not model.accepts(subject):
        raise ValueError(f"model {name!r} does not take a {type(subject).__name__}")
    return model
