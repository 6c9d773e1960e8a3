"""The ``[study] kind = "mode-map"`` of a scene: its keys, read and checked.

A scene of this kind runs :func:`shaketable.studies.mode_map.mode_map` (the planar
block's mode over a grid of B/H and friction) with the sliding limit of the
report's shielding blocks::

    [study]
    kind = "mode-map"
    record = "pacoima-dam-s16e"        # a bundled record (with its vertical)
    pga = ["0.25 g", "0.5 g", "record"] # levels to scale the record to; "record": as recorded
    aspect_ratios = [0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5]   # B/H [-]
    frictions = "0.05:0.8:0.05"        # mu_s = mu_d: a list or start:stop:step (stop included)
    height = "16 ft"
    cor = 0.95

This module reads no study (the scene parser stays light).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaketable.core.constants import FOOT
from shaketable.core.units import parse

#: Keys of a ``mode-map`` ``[study]`` (besides ``kind``).
MODE_MAP_KEYS = {"record", "pga", "aspect_ratios", "frictions", "height", "cor"}

#: Most cells one map may ask for (each is a run of the planar model).
MAX_CELLS = 20_000


@dataclass(frozen=True)
class ModeMapSettings:
    """The validated inputs of a mode-map study (SI units).

    Attributes
    ----------
    record : str
        Bundled record name.
    pga_levels : tuple of float or None
        Peak horizontal accelerations [m/s^2]; ``None``: the record as recorded.
    aspect_ratios : tuple of float
        B/H [-].
    frictions : tuple of float
        mu_s = mu_d [-].
    height : float
        Height of the blocks [m].
    cor : float
        Coefficient of restitution [-].
    """

    record: str = "pacoima-dam-s16e"
    pga_levels: tuple = (None,)
    aspect_ratios: tuple = (0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5)
    frictions: tuple = tuple(float(x) for x in np.round(np.arange(0.05, 0.801, 0.05), 3))
    height: float = 16 * FOOT
    cor: float = 0.95


def grid_numbers(value, where: str, key: str, low: float, high: float) -> tuple:
    """A list of numbers, or ``"start:stop:step"`` (stop included), each in (low, high]
    (ValueError naming ``where`` and ``study.key``)."""
    if isinstance(value, str) and value.count(":") == 2:
        try:
            start, stop, step = (float(part) for part in value.split(":"))
        except ValueError:
            raise ValueError(f"{where}: study.{key}: {value!r} is not start:stop:step") from None
        if not step > 0 or stop < start:
            raise ValueError(f"{where}: study.{key}: {value!r} needs a positive step and "
                             "stop >= start")
        count = int(math.floor((stop - start) / step + 1e-9)) + 1
        values = [round(start + k * step, 12) for k in range(count)]
    elif isinstance(value, list) and value:
        values = value
    else:
        raise ValueError(f"{where}: study.{key} must be a list of numbers or 'start:stop:step', "
                         f"got {value!r}")
    for number in values:
        if isinstance(number, bool) or not isinstance(number, (int, float)) or \
                not low < number <= high:
            raise ValueError(f"{where}: study.{key}: every value must be a number in "
                             f"({low:g}, {high:g}], got {number!r}")
    return tuple(float(number) for number in values)


def mode_map_settings(spec: dict, where: str) -> ModeMapSettings:
    """Check the ``[study]`` table of a ``mode-map`` scene (ValueError naming the file and key)."""
    from shaketable.ground.records import available

    defaults = ModeMapSettings()
    record = spec.get("record", defaults.record)
    if record not in available():
        raise ValueError(f"{where}: study.record must be a bundled record "
                         f"({', '.join(available())}), got {record!r}")
    levels = spec.get("pga", ["record"])
    if not isinstance(levels, list) or not levels:
        raise ValueError(f"{where}: study.pga must be a list such as ['0.5 g', 'record'], got "
                         f"{levels!r}")
    pga_levels: list[float | None] = []
    for level in levels:
        if level == "record":
            pga_levels.append(None)
            continue
        value = parse(level, "acceleration", where=f"{where}: study.pga")
        if not value > 0:
            raise ValueError(f"{where}: study.pga: every level must be positive, got {level!r}")
        pga_levels.append(value)
    aspect_ratios = grid_numbers(spec.get("aspect_ratios", list(defaults.aspect_ratios)), where,
                             "aspect_ratios", 0.0, 10.0)
    frictions = grid_numbers(spec.get("frictions", list(defaults.frictions)), where, "frictions",
                         0.0, 10.0)
    cells = len(pga_levels) * len(aspect_ratios) * len(frictions)
    if cells > MAX_CELLS:
        raise ValueError(f"{where}: study: {cells} cells asked for, at most {MAX_CELLS}")
    height = defaults.height
    if "height" in spec:
        height = parse(spec["height"], "length", where=f"{where}: study.height")
        if not height > 0:
            raise ValueError(f"{where}: study.height must be positive, got {spec['height']!r}")
    cor = spec.get("cor", defaults.cor)
    if isinstance(cor, bool) or not isinstance(cor, (int, float)) or not 0 <= cor <= 1:
        raise ValueError(f"{where}: study.cor must be a number in [0, 1], got {cor!r}")
    return ModeMapSettings(record, tuple(pga_levels), aspect_ratios, frictions, float(height),
                           float(cor))
