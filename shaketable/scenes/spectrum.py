"""The ``[study] kind = "overturning-spectrum"`` of a scene: its keys, read and checked.

A scene of this kind runs :func:`shaketable.studies.overturning_spectrum.overturning_spectrum`
(every overturn/safe band edge in a/(g tan alpha)) with the options of
``shaketable spectrum``::

    [study]
    kind = "overturning-spectrum"
    pulse = "one-sine"            # or a list: half-sine, one-sine, one-cosine, type-A, type-B,
                                  # type-C1, type-C2, ..., ricker
    alpha = "0.25 rad"            # the block: alpha and p (p^2 = 3 g / (4 R)) ...
    p = "2 rad/s"
    # block = "16x4ft"            # ... or its size (not both)
    cor = "housner"               # a number in [0, 1] or "housner" (1 - 1.5 sin^2 alpha)
    omega_over_p = [2, 3, 4]      # a list, or a range "1:10:0.5" (start:stop:step)
    # ceiling = 12.0              # largest a/(g tan alpha) examined (default per omega/p)
    # scan_step = 0.005           # relative scan step; tolerance = 1e-8 (edge width)
    # method = "fast"             # or "linear" (Housner's linearised Eq. 2-4), or
                                  # "predictor-corrector"

    [[study.reference]]           # optional: published edges to compare with
    pulse = "one-sine"
    omega_over_p = 4
    edges = [1.78856, 5.00928, 5.32302]   # a/(g tan alpha), increasing
    tolerance = 5e-6              # absolute: half a unit of the last digit given
    source = "Zhang & Makris (2001), J. Eng. Mech. 127(5):473-483"

This module reads no study (the scene parser stays light); ``shaketable spectrum``
shares its :func:`parse_ratios` and :func:`block_from` with it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaketable.core.constants import G
from shaketable.core.geometry import Block
from shaketable.core.units import parse
from shaketable.core.validation import unknown_keys

__all__ = ["MAX_RATIOS", "SPECTRUM_KEYS", "REFERENCE_KEYS", "SpectrumReference",
           "SpectrumSettings", "block_from", "parse_ratios", "spectrum_settings"]

#: Most values of omega/p one spectrum may ask for (each costs a scan and bisections).
MAX_RATIOS = 1000

#: Keys of an ``overturning-spectrum`` ``[study]`` (besides ``kind``).
SPECTRUM_KEYS = {"pulse", "block", "alpha", "p", "cor", "omega_over_p", "ceiling", "scan_step",
                 "tolerance", "reference", "method"}

#: Keys of each ``[[study.reference]]``.
REFERENCE_KEYS = {"pulse", "omega_over_p", "edges", "tolerance", "source"}


@dataclass(frozen=True)
class SpectrumReference:
    """Published band edges of one pulse at one omega/p, to compare with.

    Attributes
    ----------
    pulse : str
    omega_over_p : float
        omega/p [-].
    edges : tuple of float
        Every band edge a/(g tan alpha) [-], increasing.
    tolerance : float
        Largest |reproduced - published| that agrees [-] (absolute).
    source : str
        Where the values are published.
    """

    pulse: str
    omega_over_p: float
    edges: tuple
    tolerance: float
    source: str = ""


@dataclass(frozen=True)
class SpectrumSettings:
    """The inputs of an overturning-spectrum study (validated, SI units).

    Attributes
    ----------
    pulses : tuple of str
        Pulse kinds (:data:`shaketable.ground.pulses.PULSES`).
    block : Block
    cor : float or str
        Coefficient of restitution [-] or ``"housner"``.
    ratios : tuple of float
        omega/p [-].
    ceiling : float or None
        Largest a/(g tan alpha) examined [-] (None: the default per omega/p).
    scan_step, tolerance : float
        Relative scan step and relative edge width [-].
    references : tuple of SpectrumReference
    method : str
        Solver of the runs: ``"fast"``, ``"linear"`` or ``"predictor-corrector"``.
    """

    pulses: tuple
    block: Block
    cor: float | str
    ratios: tuple
    ceiling: float | None = None
    scan_step: float = 0.005
    tolerance: float = 1e-8
    references: tuple = ()
    method: str = "fast"


def parse_ratios(text, where: str = "--ratios") -> list:
    """omega/p values: ``"1,2,3"``, a list of numbers, or a range ``"1:10:0.5"``
    (start:stop:step, stop included). ``where`` names the option or key in messages."""
    if isinstance(text, list):
        if not text or not all(not isinstance(x, bool) and isinstance(x, (int, float))
                               and math.isfinite(x) and x > 0 for x in text):
            raise ValueError(f"{where}: omega/p values must be positive numbers, got {text!r}")
        if len(text) > MAX_RATIOS:
            raise ValueError(f"{where}: at most {MAX_RATIOS} values of omega/p in one spectrum")
        return [float(x) for x in text]
    text = str(text).strip()
    if ":" in text:
        try:
            parts = [float(x) for x in text.split(":")]
        except ValueError:
            raise ValueError(f"{where} {text!r}: a range is start:stop:step, three numbers") \
                from None
        if len(parts) != 3 or not all(math.isfinite(x) for x in parts) or parts[2] <= 0 \
                or parts[1] < parts[0] or parts[0] <= 0:
            raise ValueError(f"{where} {text!r}: a range is start:stop:step with "
                             f"0 < start <= stop and step > 0")
        count = int(round((parts[1] - parts[0]) / parts[2]))
        if count > MAX_RATIOS:
            raise ValueError(f"{where} {text!r} asks for {count + 1} values of omega/p; at "
                             f"most {MAX_RATIOS} in one spectrum")
        return [parts[0] + k * parts[2] for k in range(count + 1)]
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"{where} {text!r}: give numbers separated by commas, or "
                         "start:stop:step") from None
    if len(values) > MAX_RATIOS:
        raise ValueError(f"{where}: at most {MAX_RATIOS} values of omega/p in one spectrum")
    if not values or min(values) <= 0 or not all(math.isfinite(x) for x in values):
        raise ValueError(f"{where} {text!r}: omega/p values must be positive")
    return values


def block_from(alpha: float, p: float) -> Block:
    """The block of angle ``alpha`` [rad] and frequency parameter ``p`` [rad/s]
    (p^2 = 3 g / (4 R), Eq. 2-13)."""
    if not 0 < p < math.inf:
        raise ValueError(f"p must be positive [rad/s], got {p!r}")
    return Block.from_slenderness(3 * G / (4 * p * p), alpha)


def _number(value, where, key, low=0.0, high=math.inf, open_low=True):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(
            value) or value < low or (open_low and value == low) or value > high:
        raise ValueError(f"{where}: study.{key} must be a number in {'(' if open_low else '['}"
                         f"{low:g}, {high:g}], got {value!r}")
    return float(value)


def _pulses(value, where, key):
    from shaketable.ground.pulses import Pulse

    names = value if isinstance(value, list) else [value]
    if not names or not all(isinstance(name, str) for name in names):
        raise ValueError(f"{where}: {key} must be a pulse name or a list of them, got {value!r}")
    try:
        return tuple(Pulse(name, 1.0).kind for name in names)
    except ValueError as error:
        raise ValueError(f"{where}: {key}: {error}") from None


def spectrum_settings(spec: dict, where: str) -> SpectrumSettings:
    """Check the ``[study]`` table of an ``overturning-spectrum`` scene (ValueError naming
    the file and the key)."""
    for key in ("pulse", "cor", "omega_over_p"):
        if key not in spec:
            raise ValueError(f"{where}: study.{key} is missing (an overturning spectrum needs "
                             "pulse, cor, omega_over_p and the block)")
    pulses = _pulses(spec["pulse"], where, "study.pulse")
    if "block" in spec:
        if "alpha" in spec or "p" in spec:
            raise ValueError(f"{where}: give study.block or study.alpha and study.p, not both")
        try:
            block = Block.parse(spec["block"])
        except (ValueError, TypeError) as error:
            raise ValueError(f"{where}: study.block: {error}") from None
    elif "alpha" in spec and "p" in spec:
        alpha = parse(spec["alpha"], "angle", where=f"{where}: study.alpha")
        if not 0 < alpha < math.pi / 2:
            raise ValueError(f"{where}: study.alpha must be in (0, 90 deg), got {spec['alpha']!r}")
        p_text = spec["p"]
        if not isinstance(p_text, str) or not p_text.strip().lower().endswith("rad/s"):
            raise ValueError(f"{where}: study.p must be a frequency parameter with its unit, "
                             f"e.g. '2 rad/s', got {p_text!r}")
        try:
            p = float(p_text.strip()[:-len("rad/s")])
        except ValueError:
            raise ValueError(f"{where}: study.p: {p_text!r} is not a number in rad/s") from None
        if not 0 < p < math.inf:
            raise ValueError(f"{where}: study.p must be positive, got {p_text!r}")
        block = block_from(alpha, p)
    else:
        raise ValueError(f"{where}: the block is missing: give study.block (e.g. '16x4ft') or "
                         "study.alpha and study.p (e.g. '0.25 rad' and '2 rad/s')")
    cor = spec["cor"]
    if isinstance(cor, str):
        if cor.lower() != "housner":
            raise ValueError(f"{where}: study.cor must be a number in [0, 1] or 'housner', got "
                             f"{cor!r}")
        cor = "housner"
    else:
        cor = _number(cor, where, "cor", 0.0, 1.0, open_low=False)
    ratios = tuple(parse_ratios(spec["omega_over_p"], f"{where}: study.omega_over_p"))
    ceiling = None
    if "ceiling" in spec:
        ceiling = _number(spec["ceiling"], where, "ceiling (a/(g tan alpha))", 1.0)
    scan_step = _number(spec.get("scan_step", 0.005), where, "scan_step", 0.0, 0.999)
    tolerance = _number(spec.get("tolerance", 1e-8), where, "tolerance", 0.0, scan_step)
    method = spec.get("method", "fast")
    if method not in ("fast", "linear", "predictor-corrector"):
        raise ValueError(f"{where}: study.method must be 'fast', 'linear' or "
                         f"'predictor-corrector', got {method!r}")
    references = []
    given = spec.get("reference", [])
    if not isinstance(given, list) or not all(isinstance(item, dict) for item in given):
        raise ValueError(f"{where}: study.reference must be [[study.reference]] tables, got "
                         f"{given!r}")
    for k, item in enumerate(given):
        key = f"study.reference[{k}]"
        unknown = unknown_keys(item, REFERENCE_KEYS)
        if unknown:
            raise ValueError(f"{where}: unknown key {key}.{unknown[0]}; expected one of "
                             f"{', '.join(sorted(REFERENCE_KEYS))}")
        missing = sorted({"pulse", "omega_over_p", "edges", "tolerance"} - set(item))
        if missing:
            raise ValueError(f"{where}: {key}.{missing[0]} is missing")
        pulse = _pulses(item["pulse"], where, f"{key}.pulse")[0]
        ratio = _number(item["omega_over_p"], where, f"reference[{k}].omega_over_p")
        if pulse not in pulses or not any(math.isclose(ratio, r) for r in ratios):
            raise ValueError(f"{where}: {key} compares {pulse} at omega/p = {ratio:g}, which "
                             "the study does not compute (see study.pulse, study.omega_over_p)")
        edges = item["edges"]
        if not isinstance(edges, list) or not edges or any(
                isinstance(x, bool) or not isinstance(x, (int, float)) for x in edges) or \
                list(edges) != sorted(edges):
            raise ValueError(f"{where}: {key}.edges must be increasing numbers "
                             f"(a/(g tan alpha)), got {edges!r}")
        references.append(SpectrumReference(
            pulse, ratio, tuple(float(x) for x in edges),
            _number(item["tolerance"], where, f"reference[{k}].tolerance"),
            str(item.get("source", ""))))
    return SpectrumSettings(pulses, block, cor, ratios, ceiling, scan_step, tolerance,
                            tuple(references), method)
