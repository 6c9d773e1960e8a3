"""Studies whose inputs are bundled scenes: the scenes are read here, above the studies layer."""

from __future__ import annotations

from dataclasses import replace

from shaketable.studies.repeatability import (
    EARTHQUAKE_ROCKING_LEVEL,
    RepeatabilityResult,
    largest_spread,
    pitch_repeatability,
)


def section_3_7_cases(phases: int = 24) -> list[RepeatabilityResult]:
    """The report's harmonic tests and earthquake-type motions on the pitching table.

    The harmonic cases are the scenes ``fig-3-7``, ``fig-3-8`` and ``fig-3-9``
    as they are (ramped start, displacement command, 30 x 6 in block, COR
    0.925). The earthquake-type cases are the motion of the scene ``fig-3-5``
    (the package's ``olive-view`` SUBSTITUTE, the report's table records are
    not available) at :data:`EARTHQUAKE_ROCKING_LEVEL`, where it rocks the
    block substantially, and at Fig. 3.5's own 0.5 g. Each case's
    ``reference_spread`` is the largest spread of the harmonic cases.
    """
    from shaketable.lab.stage import TableSetup
    from shaketable.scenes.catalog import resolve_scene_path
    from shaketable.scenes.parse import load_scene
    from shaketable.scenes.run import build_motion

    def scene_case(name, label, kind, scale=1.0):
        scene = load_scene(resolve_scene_path(name))
        setup = scene.table if scene.table is not None else TableSetup()
        motion = build_motion(scene)
        if scale != 1.0:
            motion = motion.scaled(scale)
        return pitch_repeatability(scene.block, motion, cor=scene.cors[0], phases=phases,
                                   setup=setup, name=label, kind=kind)

    level = EARTHQUAKE_ROCKING_LEVEL
    cases = [
        scene_case("fig-3-7", "Fig. 3.7: 2 Hz, 0.5 g H", "harmonic"),
        scene_case("fig-3-8", "Fig. 3.8: 2 Hz, 0.38 g H + 0.33 g V", "harmonic"),
        scene_case("fig-3-9", "Fig. 3.9: 2 Hz, 0.45 g H + 0.26 g V", "harmonic"),
        scene_case("fig-3-5", f"earthquake-type {level:g} g H + {0.4 * level:.3g} g V "
                   "(Fig. 3.5 substitute scaled)", "earthquake-type", scale=level / 0.5),
        scene_case("fig-3-5", "Fig. 3.5: earthquake-type 0.5 g H + 0.2 g V (substitute)",
                   "earthquake-type"),
    ]
    harmonic_spread = largest_spread([case for case in cases if case.kind == "harmonic"])
    return [replace(case, reference_spread=harmonic_spread) for case in cases]
