"""The models by name, and the model whose input a user gave."""

from __future__ import annotations

from typing import Any

from shaketable.models.base import Model
from shaketable.models.stack.model import STACK_MODEL

#: Every model laid out in :mod:`shaketable.models`, by name.
MODELS: dict[str, Model] = {STACK_MODEL.name: STACK_MODEL}


def model_for(subject: Any) -> Model | None:
    """The model whose input ``subject`` is (a :class:`~shaketable.models.stack.Stack`:
    the stack model), or ``None``."""
    for model in MODELS.values():
        if model.accepts(subject):
            return model
    return None
