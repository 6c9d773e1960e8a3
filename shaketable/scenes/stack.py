"""A column of blocks as the command line and scenes give it, and a scene's ``[stack]``.

``stack_from_text`` reads the blocks (``"30x6in,30x6in"``, bottom first), their masses or
densities and per-block angles, for ``shaketable simulate --stack`` and for a scene; a scene
with a ``[stack]`` section (instead of ``[block]`` and ``[rocking]``) is a
:class:`StackScene`, run by :func:`run_stack_scene` with the stack model
(:mod:`shaketable.models.stack`, ``docs/stack.md``)::

    name = "stack-kick"
    [stack]
    blocks = ["1x0.3m", "1x0.3m", "0.8x0.2m"]    # bottom first, each HEIGHTxWIDTH<unit>
    masses = ["1 t", "1 t", "0.5 t"]            # or densities = ["2400 kg/m3", ...]; default:
                                                # 2400 kg/m^3 over 1 m of depth (concrete)
    offsets = ["2 in", "-1 in"]                  # optional: blocks 1.. from the centre of the
                                                # one below (+x positive); default centred
    theta0 = ["0 rad", "0 rad", "0.1 rad"]      # per block (or one value for all); "alpha":
                                                # a multiple of that block's own alpha
    theta_dot0 = ["0 rad/s", ...]                # optional, per block
    cor = 0.9                                    # optional: the constant-COR law; default
                                                # the plastic multi-contact law
    duration = "2 s"                             # free rocking ([motion] kind = "free"), or
                                                # the length of a record's window
    mu = 0.6                                     # optional: the friction the contacts offer,
                                                # against the friction they need
    [motion]   as in any scene
    [outputs]  figure, csv, time_range
"""

from __future__ import annotations

import json
import math
import os
import re
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from shaketable.core.constants import MAX_FRICTION
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.core.units import format_length, parse, parse_angle_or_ratio
from shaketable.core.validation import unknown_keys
from shaketable.models.stack import (
    PLAUSIBLE_FRICTION,
    Stack,
    StackFrictionWarning,
    StackResult,
    StackRetryWarning,
    StackTensionWarning,
    simulate_stack,
)
from shaketable.models.stack.geometry import block_words as _block_words
from shaketable.models.stack.geometry import overhang_message
from shaketable.scenes.parse import Scene, SceneError, scene_from_dict

#: Keys of a scene's ``[stack]`` section.
STACK_KEYS = {"blocks", "masses", "densities", "offsets", "theta0", "theta_dot0", "cor",
              "duration", "mu", "rtol"}

#: Top-level keys of a stack scene.
STACK_SCENE_KEYS = {"name", "source", "description", "stack", "motion", "outputs"}


# ----------------------------------------------------------------------------- input
def _items(value, where: str) -> list:
    """A list given as a list, or as text separated by commas."""
    if isinstance(value, str):
        return [part.strip() for part in value.split(",")]
    if isinstance(value, (list, tuple)):
        return list(value)
    raise ValueError(f"{where}: expected a list (bottom first) or text separated by commas, "
                     f"got {value!r}")


def typed_mass_unit(masses) -> str:
    """``"t"`` when every mass was typed in tonnes (``["10 t", "5 t"]``, ``"10t,5t"``),
    else ``"kg"``: the unit the answer gives the masses in."""
    if masses is None or not isinstance(masses, (str, list, tuple)):
        return "kg"
    items = _items(masses, "masses")
    typed = [re.fullmatch(r"\s*[-+0-9.eE]+\s*t\s*", str(item)) for item in items]
    return "t" if items and all(typed) else "kg"


def mass_line(stack: Stack, unit: str = "kg") -> str:
    """:meth:`Stack.describe_masses`, the given masses in tonnes when typed so."""
    if unit != "t" or stack.masses is None:
        return stack.describe_masses()
    return ("masses: " + ", ".join(f"{mass / 1000.0:.4g}" for mass in stack.mass)
            + " t (given, bottom first)")


def stack_from_text(blocks, masses=None, densities=None, *, where: str = "--stack",
                    masses_where: str = "--masses",
                    densities_where: str = "--densities") -> Stack:
    """The :class:`~shaketable.models.stack.Stack` of sizes, bottom first.

    Parameters
    ----------
    blocks : str or list of str
        ``"30x6in,30x6in"`` or ``["30x6in", "30x6in"]``: each block ``HEIGHTxWIDTH<unit>``,
        height first (:meth:`shaketable.Block.parse`), from the bottom up.
    masses : str or list of str, optional
        Each block's mass with its unit (``"400kg"``, ``"1t"``, ``"900lb"``).
    densities : str or list of str, optional
        Each block's density with its unit (``"2400kg/m3"``): the masses are in proportion
        to density times B H over 1 m of depth. Neither: 2400 kg/m^3 (concrete) over 1 m
        of depth for all (``Stack.describe_masses``).
    where, masses_where, densities_where : str
        How an error names the three inputs (an option or a scene key).

    Raises
    ------
    ValueError
        Naming the input and the block (counted from 0 at the bottom): a size without a
        unit, a non-positive size or mass, an overhanging block, a count that does not
        match, no block at all.
    """
    sizes = [size for size in _items(blocks, where) if str(size).strip()]
    if not sizes:
        raise ValueError(f"{where}: give at least one block, e.g. 30x6in,30x6in (bottom first)")
    count = len(sizes)
    parsed = []
    for index, size in enumerate(sizes):
        try:
            parsed.append(Block.parse(str(size)))
        except ValueError as error:
            raise ValueError(f"{where}: {_block_words(index, count)}: {error}") from None
    overhang = overhang_message(parsed)
    if overhang is not None:
        raise ValueError(f"{where}: {overhang}")
    if masses is not None and densities is not None:
        raise ValueError(f"give {masses_where} or {densities_where}, not both")
    values = None
    for given, kind, name in ((masses, "mass", masses_where),
                              (densities, "density", densities_where)):
        if given is None:
            continue
        items = _items(given, name)
        if len(items) != count:
            raise ValueError(f"{name}: {len(items)} value(s) for {count} block(s); give one "
                             f"per block, bottom first")
        values = []
        for index, (item, block) in enumerate(zip(items, parsed)):
            value = parse(item, kind, where=f"{name}: {_block_words(index, count)}")
            if not (value > 0 and math.isfinite(value)):
                raise ValueError(f"{name}: {_block_words(index, count)}: the {kind} must be "
                                 f"positive, got {item!r}")
            values.append(value if kind == "mass" else value * block.width * block.height)
    try:
        return Stack(tuple(parsed), masses=None if values is None else tuple(values))
    except ValueError as error:
        raise ValueError(f"{where}: " + _named_blocks(str(error), count)) from None


def with_offsets(stack: Stack, offsets, where: str) -> Stack:
    """``stack`` with the offsets given as lengths with their units (``["2 in", "-1 in"]``,
    or text separated by commas): one per block above the bottom one, each from the centre
    of the block below [m] (:class:`Stack`'s ``offsets``); errors name ``where`` and the
    block."""
    items = _items(offsets, where)
    count = stack.n
    if len(items) != count - 1:
        raise ValueError(f"{where}: {len(items)} value(s) for {count} block(s); give {count - 1}, "
                         "one per block above the bottom one (each from the centre of the "
                         "block below), bottom first")
    values = [parse(item, "length", where=f"{where}: {_block_words(index + 1, count)}")
              for index, item in enumerate(items)]
    unit = stack.blocks[0].length_unit
    for index, value in enumerate(values, start=1):
        lower, upper = stack.blocks[index - 1], stack.blocks[index]
        if abs(value) + upper.b > lower.b * (1.0 + 1e-12):   # Stack's own check, in words
            raise ValueError(
                f"{where}: {_block_words(index, count)} ({upper.describe()}) offset "
                f"{format_length(value, unit)} would overhang {_block_words(index - 1, count)} "
                f"({lower.describe()}): its offset may be at most "
                f"{format_length(lower.b - upper.b, unit)} either way (an overhanging block "
                "is not offered by the stack model)")
    try:
        return Stack(stack.blocks, masses=stack.masses, offsets=tuple(values))
    except ValueError as error:
        message = re.sub(r"Stack\.offsets\[\d+\] ", "", str(error))
        raise ValueError(f"{where}: {message}") from None


def _named_blocks(message: str, count: int) -> str:
    """``Stack.blocks[1].width ...`` of the model's message as ``block 1 (top) width ...``."""
    return re.sub(r"Stack\.(?:blocks|masses)\[(\d+)\]\.?",
                  lambda match: _block_words(int(match[1]), count) + " ", message)


def per_block_angles(values, stack: Stack, *, where: str, rates: bool = False) -> np.ndarray:
    """Initial rotations [rad] (or rates [rad/s] with ``rates``) of each block, bottom first.

    One value is every block's (equal blocks: the stack tilted as one body); else one per
    block. An angle is written in rad, deg or as a multiple of that block's own alpha
    (``"0.5 alpha"``); a rate in rad/s.
    """
    items = _items(values, where)
    if len(items) == 1:
        items = items * stack.n
    if len(items) != stack.n:
        raise ValueError(f"{where}: {len(items)} values for {stack.n} blocks; give one value "
                         "(every block's) or one per block, bottom first")
    out = []
    for index, (item, block) in enumerate(zip(items, stack.blocks)):
        name = f"{where}: {_block_words(index, stack.n)}"
        if rates:
            out.append(parse(str(item).replace("rad/s", "rad"), "angle", where=name))
        else:
            out.append(parse_angle_or_ratio(item, block.alpha, where=name))
    return np.array(out)


def friction_coefficient(value, where: str) -> float | None:
    """``mu``: the friction coefficient the contacts offer [-] in [0, 1.5] (None: not
    given; :data:`~shaketable.core.constants.MAX_FRICTION`, assess's bound too)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            0 <= value < math.inf):
        raise ValueError(f"{where} must be a friction coefficient >= 0 (a number), "
                         f"got {value!r}")
    if value > MAX_FRICTION:
        raise ValueError(f"{where} must be at most {MAX_FRICTION:g} (a friction coefficient "
                         f"[-], as assess takes it; no real contact offers more than about "
                         f"1), got {value!r}")
    return float(value)


# ----------------------------------------------------------------------------- answer
def stack_answer(result: StackResult, mu: float | None = None,
                 mass_unit: str = "kg") -> list[str]:
    """The answer lines of a stack run (after its verdict): each block's peak rotation
    against its own alpha, the first uplift, the top corner's excursion (the clearance the
    stack needs), the friction the contacts need against ``mu`` and any pulling force;
    given masses in ``mass_unit`` (``"t"`` when typed in tonnes, :func:`typed_mass_unit`)."""
    stack = result.stack
    unit = stack.blocks[0].length_unit
    lines = []
    for i, block in enumerate(stack.blocks):
        theta = np.abs(result.theta[:, i]) if result.t.size else np.zeros(1)
        k = int(np.argmax(theta))
        if result.status == "overturned" and i >= result.overturned_block:
            fell = ("overturned" if i == result.overturned_block else
                    f"fell with block {result.overturned_block}")
            lines.append(f"{result.block_name(i)} {block.describe()}: F ({fell} at "
                         f"{result.t_overturn:.2f} s)")
            continue
        lines.append(f"{result.block_name(i)} {block.describe()}: max |θ| {theta[k]:.3g} rad "
                     f"= {theta[k] / block.alpha:.3g} α (α = {block.alpha:.4g} rad)"
                     + (f" at t = {result.t[k]:.2f} s" if theta[k] > 0 else "")
                     + _first_moved(result, i))
    if result.still_moving:
        lines.append("came to rest: no, " + result.end_state())
    lines.append(mass_line(stack, mass_unit))   # in t when typed in t
    uplift = next((event for event in result.events if event["kind"] == "uplift"), None)
    impacts = sum(1 for event in result.events if event["kind"] == "impact")
    if uplift is None:
        lines.append(_no_uplift_line(result, impacts))
    else:
        from shaketable.scenes.stack_patterns import pattern_signs, pattern_words

        lines.append(f"first uplift at t = {uplift['t']:.3f} s: "
                     f"{pattern_words(uplift['pattern_after'])}; {impacts} impact(s)")
        if pattern_signs(uplift["pattern_after"]):
            lines.append(pattern_signs(uplift["pattern_after"]))
    falling = result.t_past_alpha
    excursion = result.top_corner_excursion   # once: it is computed sample by sample
    demand_standing, excursion_standing = result.peak_before_past_alpha(excursion)
    peak_excursion = float(np.abs(excursion).max()) if result.t.size else 0.0
    standing = (f"; {{}} before a block passed its α (t < {falling:.2f} s: what the column "
                "needs while it stands)") if not math.isnan(falling) else ""
    lines.append(f"top corner's peak excursion (the clearance the stack needs) "
                 f"{format_length(peak_excursion, unit)}"
                 + standing.format(format_length(excursion_standing, unit)))
    demand = result.friction_demand
    finite = np.where(np.isfinite(demand), demand, -1.0)
    if finite.size and finite.max() >= 0:
        k, j = (int(index) for index in np.unravel_index(int(np.argmax(finite)), finite.shape))
        where = "the base" if j == 0 else f"interface {j - 1}|{j}"
        line = f"needed friction: peak F/N {finite[k, j]:.3g} at {where}, t = {result.t[k]:.2f} s"
        line += standing.format(f"{demand_standing:.3g}")
        limit = PLAUSIBLE_FRICTION if mu is None else mu
        slip = result.t_friction_exceeded(limit)
        label = f"mu {limit:g}" if mu is not None else f"{limit:g} (no real contact offers more)"
        line += ("; within " + label if math.isnan(slip) else
                 f"; exceeds {label} from t = {slip:.2f} s: the blocks would slide there, "
                 "outside the model")
        lines.append(line)
    if not math.isnan(result.t_tension):
        lines.append(f"a contact pulls from t = {result.t_tension:.2f} s (a block would lift "
                     "off: outside the model)")
    return lines


def _no_uplift_line(result: StackResult, impacts: int) -> str:
    """The uplift line of a run with no uplift event: the stack stood, or only the blocks
    released tilted rocked, or an impact opened an interface that was flat (a landing's
    kick: "block 0 (bottom) lifted by the impact at t = 0.265 s")."""
    if not np.any(result.theta):
        return "uplift: none (the stack stood on the table)"
    for event in result.events:
        before, after = event.get("pattern_before"), event.get("pattern_after")
        if before is None or after is None:
            continue
        opened = [j for j, (was, now) in enumerate(zip(before, after)) if was == 0 and now != 0]
        if opened:
            names = " and ".join(result.block_name(j) for j in opened)
            return (f"no uplift of its own after the release: {names} lifted by the "
                    f"{event['kind']} at t = {event['t']:.3f} s; {impacts} impact(s)")
    return f"no uplift after the release (only the blocks released tilted moved); {impacts} impact(s)"


def _first_moved(result: StackResult, i: int) -> str:
    """``"; at rest until t = 0.265 s"`` for a block that started at rest and was set
    moving later (an interface at or below it opened: an uplift or a landing's kick)."""
    if result.t.size == 0 or result.theta[0, i] != 0.0 or result.theta_dot[0, i] != 0.0:
        return ""
    for index, event in enumerate(result.events):
        after = event.get("pattern_after")
        if after is not None and any(after[: i + 1]):
            first = index == 0 and event["kind"] == "uplift"   # the stack's own start: said
            return ("" if event["t"] <= result.t[0] or first else      # by the uplift line
                    f"; at rest until t = {event['t']:.3f} s ({event['kind']})")
    return ""


#: The stack model's warnings a command or a report says as text: its assumptions (tension,
#: friction) and a run made again at a tighter tolerance.
SAID_WARNINGS = (StackTensionWarning, StackFrictionWarning, StackRetryWarning)


def run_quietly(stack: Stack, motion, **options) -> tuple[StackResult, list[str]]:
    """:func:`~shaketable.models.stack.simulate_stack` with its warnings
    (:data:`SAID_WARNINGS`: tension, friction, a retry at a tighter tolerance) caught and
    returned as text, for a command or a report to say."""
    with warnings.catch_warnings(record=True) as caught:
        for category in SAID_WARNINGS:
            warnings.simplefilter("always", category)
        result = simulate_stack(stack, motion, **options)
    said = [str(item.message) for item in caught if issubclass(item.category, SAID_WARNINGS)]
    for item in caught:   # anything else is passed on
        if not issubclass(item.category, SAID_WARNINGS):
            warnings.warn_explicit(item.message, item.category, item.filename, item.lineno)
    return result, said


def fall_note(warned) -> tuple[str, list[str]]:
    """The assumption warnings of a stack run for the console: those raised only once the
    column was already falling (a block past its alpha: the fall is the model's answer,
    its motion is not) as one short note line, and the others, whole.

    Returns
    -------
    (str, list of str)
        ``"note: ..."`` ("" when no warning came after the fall) and the warnings to say
        as they are.
    """
    import re

    after = [line for line in warned if "the column was already falling" in line]
    before = [line for line in warned if line not in after]
    if not after:
        return "", before
    times = [float(found[1]) for line in after
             if (found := re.search(r"passed its alpha at t = ([0-9.]+) s", line))]
    when = f" (t = {min(times):.2f} s)" if times else ""
    what = " and ".join(word for word, key in (("lift-off", "tensile"), ("sliding", "friction"))
                        if any(key in line for line in after))
    return (f"note: the {what or 'assumptions'} came after the column began to fall{when}: "
            "the fall is the model's answer, not its motion (summary.json: warnings)", before)


def describe_law(result: StackResult) -> str:
    return "plastic impacts" if result.impact == "plastic" else f"COR {result.cor:g}"


# ----------------------------------------------------------------------------- scenes
@dataclass(frozen=True)
class StackScene:
    """A validated scene with a ``[stack]``: a column of blocks on the scene's table motion.

    Attributes
    ----------
    name, source, description : str
    stack : Stack
    base : Scene
        The scene's motion and outputs (``[motion]``, ``[outputs]``), read as any scene
        reads them (:func:`shaketable.scenes.run.build_motion` builds the motion from it).
    theta0, theta_dot0 : ndarray
        Each block's initial rotation [rad] and rate [rad/s], bottom first.
    cor : float or None
        The constant COR [-] (``impact="cor"``); None: the plastic law.
    duration : float or None
        Free rocking's length, or a record's window [s].
    mu : float or None
        The friction coefficient the contacts offer [-] (compared with what they need).
    rtol : float or None
    path : str
    """

    name: str
    source: str
    description: str
    stack: Stack
    base: Scene
    theta0: np.ndarray
    theta_dot0: np.ndarray
    cor: float | None = None
    duration: float | None = None
    mu: float | None = None
    rtol: float | None = None
    path: str = ""
    outputs: dict = field(default_factory=dict)
    mass_unit: str = "kg"


def stack_scene_from_dict(data: dict, where: str) -> StackScene:
    """A scene with ``[stack]`` (the parser :mod:`shaketable.scenes` registers for it).

    Raises
    ------
    SceneError
        Naming the file, the key and the block.
    """
    unknown = unknown_keys(data, STACK_SCENE_KEYS)
    if unknown:
        raise SceneError(f"{where}: unknown key {unknown[0]!r} in [top level of a stack "
                         f"scene]; expected one of {', '.join(sorted(STACK_SCENE_KEYS))} "
                         "([block] and [rocking] are for one block)")
    spec = data["stack"]
    if not isinstance(spec, dict):
        raise SceneError(f"{where}: [stack] must be a table, got {spec!r}")
    unknown = unknown_keys(spec, STACK_KEYS)
    if unknown:
        raise SceneError(f"{where}: unknown key {unknown[0]!r} in [stack]; expected one of "
                         f"{', '.join(sorted(STACK_KEYS))}")
    if "blocks" not in spec:
        raise SceneError(f"{where}: stack.blocks is missing: the sizes from the bottom up, "
                         "e.g. [\"30x6in\", \"30x6in\"]")
    try:
        stack = stack_from_text(spec["blocks"], spec.get("masses"), spec.get("densities"),
                                where=f"{where}: stack.blocks",
                                masses_where=f"{where}: stack.masses",
                                densities_where=f"{where}: stack.densities")
        if "offsets" in spec:
            stack = with_offsets(stack, spec["offsets"], f"{where}: stack.offsets")
        theta0 = per_block_angles(spec.get("theta0", "0 rad"), stack,
                                  where=f"{where}: stack.theta0")
        theta_dot0 = per_block_angles(spec.get("theta_dot0", "0 rad/s"), stack,
                                      where=f"{where}: stack.theta_dot0", rates=True)
        duration = (parse(spec["duration"], "time", where=f"{where}: stack.duration")
                    if "duration" in spec else None)
        mu = friction_coefficient(spec.get("mu"), f"{where}: stack.mu")
    except ValueError as error:
        message = str(error)
        raise SceneError(message if message.startswith(where) else f"{where}: {message}") \
            from None
    cor = spec.get("cor")
    if cor is not None and (isinstance(cor, bool) or not isinstance(cor, (int, float))
                            or not 0 <= cor <= 1):
        raise SceneError(f"{where}: stack.cor must be a number in [0, 1] (the constant-COR "
                         f"law; leave it out for the plastic law), got {cor!r}")
    rtol = spec.get("rtol")
    if rtol is not None and (isinstance(rtol, bool) or not isinstance(rtol, float)):
        raise SceneError(f"{where}: stack.rtol must be a number such as 1e-10, got {rtol!r}")
    # the motion, the outputs and the name, read as any scene reads them
    stand_in = {key: data[key] for key in ("name", "source", "description", "motion",
                                           "outputs") if key in data}
    stand_in["block"] = {"size": spec["blocks"][0] if isinstance(spec["blocks"], list)
                         else str(spec["blocks"]).split(",")[0]}
    stand_in["rocking"] = {"cor": 1.0, "duration": spec.get("duration", "1 s")}
    base = scene_from_dict(stand_in, where)
    assert isinstance(base, Scene)
    if base.motion["kind"] == "free" and duration is None:
        raise SceneError(f"{where}: stack.duration is needed for free rocking, e.g. '2 s'")
    if base.motion["kind"] == "impulses":
        raise SceneError(f"{where}: motion.kind 'impulses' is not offered for a stack")
    return StackScene(name=base.name, source=base.source, description=base.description,
                      stack=stack, base=base, theta0=theta0, theta_dot0=theta_dot0,
                      cor=None if cor is None else float(cor), duration=duration, mu=mu,
                      rtol=rtol, path=where, outputs=base.outputs,
                      mass_unit=typed_mass_unit(spec.get("masses")))


@dataclass(frozen=True, eq=False)
class StackSceneResult:
    """The run of a :class:`StackScene` and what it warned."""

    scene: StackScene
    run: StackResult
    warnings: tuple = ()

    def lines(self) -> list[str]:
        """The console's answer: the verdict, then :func:`stack_answer`."""
        scene = self.scene
        lines = [f"{scene.name}: {scene.stack.describe()}, {describe_law(self.run)}: "
                 f"{self.run.verdict()}"]
        lines += ["  " + line for line in stack_answer(self.run, scene.mu, scene.mass_unit)]
        return lines

    def summary(self) -> dict:
        from shaketable.core.files import json_ready_dict
        from shaketable.models.stops import stop_summary

        summary = {"scene": self.scene.name, "source": self.scene.source,
                   "description": self.scene.description,
                   "stack": self.scene.stack.describe(), "verdict": self.run.verdict(),
                   **stop_summary(self.run), "warnings": list(self.warnings)}
        if self.scene.mu is not None:   # the keys `simulate --stack --mu` writes
            summary["mu [-]"] = self.scene.mu
            summary["t_friction_exceeded(mu) [s]"] = self.run.t_friction_exceeded(
                self.scene.mu)
        return json_ready_dict(summary)

    def write(self, out: str | os.PathLike[str]) -> list[Path]:
        """history.csv, events.csv, summary.json and calcomp.png (and .svg), as the scene's
        ``[outputs]`` asks."""
        from shaketable.core.files import prepare_output_folder, write_csv, write_text

        out = prepare_output_folder(out, "out")
        written = []
        if self.scene.outputs.get("csv", True):
            written += [write_csv(out / "history.csv", self.run.to_frame()),
                        write_csv(out / "events.csv", self.run.events_frame())]
        written.append(write_text(out / "summary.json",
                                  json.dumps(self.summary(), indent=2)))
        if self.scene.outputs.get("figure", True):
            from shaketable.plots.base import save

            title = (f"{self.scene.source} (scene {self.scene.name})" if self.scene.source
                     else f"scene {self.scene.name}")
            for suffix in ("png", "svg") if self.scene.outputs.get("svg", False) else ("png",):
                written.append(out / f"calcomp.{suffix}")
                save(self.run.plot(title=title,
                                   time_range=self.scene.outputs.get("time_range")),
                     written[-1])
        return written


def stack_motion(scene: StackScene):
    """The table motion of a stack scene [m/s^2] (None: free rocking), cut to
    ``stack.duration`` when a motion is given with one."""
    from shaketable.models.rocking.run import extended
    from shaketable.scenes.run import build_motion

    motion = build_motion(scene.base)
    if motion is not None and not isinstance(motion, Motion):   # refused when parsed
        raise SceneError(f"{scene.path}: motion.kind 'impulses' is not offered for a stack")
    if motion is not None and scene.duration is not None:
        motion = extended(motion, scene.duration)
    return motion


def run_stack_scene(scene: StackScene) -> StackSceneResult:
    """Run a stack scene with the stack model."""
    motion = stack_motion(scene)
    options: dict[str, Any] = {"theta0": scene.theta0, "theta_dot0": scene.theta_dot0}
    if scene.cor is not None:
        options.update(impact="cor", cor=scene.cor)
    if scene.rtol is not None:
        options["rtol"] = scene.rtol
    if motion is None:
        options["duration"] = scene.duration
    try:
        run, said = run_quietly(scene.stack, motion, **options)
    except ValueError as error:
        raise SceneError(f"{scene.path}: [stack]: {error}") from None
    return StackSceneResult(scene=scene, run=run, warnings=tuple(said))


def with_outputs(scene: StackScene, **outputs) -> StackScene:
    """The scene with some outputs switched on (``--svg``, ``--parquet`` of ``run``)."""
    return replace(scene, outputs=dict(scene.outputs, **outputs))


def stack_scene_section(scene: StackScene, folder: Path) -> str:
    """A stack scene's section of ``reproduce``'s report: it runs into ``folder``."""
    result = run_stack_scene(scene)
    result.write(folder)
    lines = [f"## {scene.source or scene.name} — `{scene.name}`", "", scene.description, "",
             f"![{scene.name}]({scene.name}/calcomp.png)", "",
             f"* {scene.stack.describe()}, {describe_law(result.run)}: {result.run.verdict()}"]
    lines += [f"  * {line}" for line in stack_answer(result.run, scene.mu)]
    lines += [f"  * warning: {line}" for line in result.warnings]
    return "\n".join(lines) + "\n"


#: The stacks section of ``reproduce``: the block of Figs. 4.16-4.17 (8 x 2 ft: two high is
#: 16 ft, three high 24 ft, the report's "as much as 20 feet high"); the columns of Tables
#: 4.1-4.3 whose records the columns run (the report's Section 4 records: Pacoima Dam S16E
#: and S74W with their verticals, the substitutes for Olive View, A-1 and B-1 horizontal
#: only, as :mod:`shaketable.studies.report_tables` loads them) over their first 10 s, then
#: 5 s at rest (a column still falling at the cut falls within it); a slender top block for
#: the second branch of the uplift threshold; one pulse frequency, its minimum the lowest
#: edge of ``spectrum --stack``; the stack engine's rtol for the record runs.
STACKS_SECTION: dict[str, Any] = {"block": "8x2ft", "slender_top": "6x1ft",
                                  "records": ("pacoima S16E", "pacoima S74W", "olive view",
                                              "A-1", "B-1"),
                                  "window": 10.0, "rest": 5.0, "ratios": (3.0,),
                                  "iterations": 5,
                                  "rtol": 1e-7}


def stacks_section(folder: Path, lines: list) -> str:
    """``reproduce``'s stacks section (:mod:`shaketable.studies.stacks`): tables, figure,
    Markdown, written into ``folder``."""
    from shaketable.core.files import write_csv
    from shaketable.plots.base import save
    from shaketable.studies.report_tables import SUBSTITUTE_SEED, column_motion
    from shaketable.studies.stacks import retried_runs, stacks_study

    settings = STACKS_SECTION
    block = Block.parse(settings["block"])
    study = stacks_study(block, {name: column_motion(name) for name in settings["records"]},
                         Block.parse(settings["slender_top"]), settings["window"],
                         ratios=settings["ratios"], iterations=settings["iterations"],
                         rtol=settings["rtol"], rest=settings["rest"])
    write_csv(folder / "records.csv", study.records)
    write_csv(folder / "uplift.csv", study.uplift)
    write_csv(folder / "pulses.csv", study.pulses)
    save(study.plot(), folder / "figure.png")
    name = folder.name
    uplift = study.uplift
    worst = float(np.nanmax(np.abs(uplift["relative difference [-]"])))
    agree = int((uplift["pattern entered"] == uplift["pattern of the closed form"]).sum())
    pulses = study.pulses
    width = float(((pulses["falls [g]"] - pulses["stands [g]"]) / pulses["minimum [g]"]).max())

    def table(frame, digits=4):
        shown = frame.copy()
        for column in shown.columns:
            if shown[column].dtype.kind == "f":
                shown[column] = shown[column].map(lambda x: "—" if not math.isfinite(x)
                                                  else f"{x:.{digits}g}")
        return "\n".join(["| " + " | ".join(map(str, shown.columns)) + " |",
                          "|" + "---|" * len(shown.columns)]
                         + ["| " + " | ".join(map(str, row)) + " |"
                            for row in shown.itertuples(index=False)])

    lines += [f"![{name}]({name}/figure.png)", "",
              f"**The report's blocks stacked** ({block.describe()}, the block of Figs. "
              f"4.16–4.17, under the first {settings['window']:g} s of each Section 4 record: "
              "Pacoima Dam S16E and S74W with their verticals, and the package's SUBSTITUTE "
              "accelerograms for Olive View, A-1 and B-1, horizontal only as in the report "
              f"(seed {SUBSTITUTE_SEED}, as Tables 4.1–4.3), then {settings['rest']:g} s at "
              "rest; plastic impacts, DOP853 "
              f"at rtol {settings['rtol']:g}{retried_runs(study.records, settings['rtol'])}; the "
              "block alone by the single-block engine at Housner's COR 1 − 1.5 sin²α, the "
              "plastic law's one-block case). F = overturns; max θ/α bottom first:", "",
              table(study.records.drop(columns=["height [ft]", "rtol [-]"])), "",
              "(The overturn times and blocks are those of runs at rtol 10⁻¹², to the "
              "digits shown; the number of impacts of a rocking column is not: the "
              "chatter before a landing resolves differently at each tolerance.)", "",
              "**Uplift thresholds** from a table acceleration rising at 0.5 g/s, against "
              "(g + v̈) min(A1, A2), A1 = b1 (m1 + m2) / (m1 h1 + m2 (2 h1 + h2)) (the whole "
              f"stack), A2 = b2/h2 (the top block alone): largest relative difference "
              f"{worst:.1e}; the pattern entered is the closed form's in {agree} of "
              f"{len(uplift)} stacks. The bottom block alone rocks at tan α1 (Eq. 2-1): "
              "stacking lowers the threshold.", "",
              table(uplift.drop(columns=["b1 [m]", "h1 [m]", "b2 [m]", "h2 [m]"])), "",
              "**Pulse overturning amplitudes**: the smallest half-sine pulse (ω/p of the "
              "block alone; overturned within 10 s of the pulse's end), the lowest "
              "overturning edge of the column's overturning spectrum as `spectrum --stack` "
              "finds it (a scan of relative step 0.02, the edge bisected "
              f"{settings['iterations']} times: brackets at most {100 * width:.2g} % wide), "
              "beside "
              "Housner's half-sine estimate Eq. (2-8) "
              "written for the column as one rigid body, a = g tan α_eq √(1 + (ω/p_eq)²) "
              "(an estimate, linearised: not a bound):", "",
              table(study.pulses)]
    return "\n".join(lines) + "\n"
