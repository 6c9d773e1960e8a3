"""Scenes: an experiment as a TOML file that names only what it needs.

:mod:`~shaketable.scenes.parse` reads a scene once into frozen objects
(:class:`~shaketable.scenes.parse.Scene`, :class:`~shaketable.scenes.parse.Study`);
:mod:`~shaketable.scenes.catalog` finds the bundled ones by name;
:mod:`~shaketable.scenes.run` is the pipeline (motion, table, sensors, block,
theory) and :mod:`~shaketable.scenes.compare` sets the result beside the report.
The parser imports no study and no pipeline module: the studies' items and the
parsers of the ``[sensors]`` and ``[theory]`` sections are registered here (each
loaded when a scene asks for it).
"""

from typing import Any

from shaketable.scenes.parse import register_section_parser, register_study_items


def _teaching_items() -> tuple[str, ...]:
    from shaketable.studies.teaching import ITEMS  # the engine: loaded when a scene asks

    return tuple(ITEMS)


register_study_items("teaching", _teaching_items)


def _sensors(section: dict, where: str) -> Any:
    from shaketable.scenes.virtual_test import sensors_from_dict

    return sensors_from_dict(section, where)


def _theory(section: dict, where: str) -> Any:
    from shaketable.scenes.virtual_test import theory_from_dict

    return theory_from_dict(section, where)


def _floor(section: dict, where: str) -> Any:
    from shaketable.scenes.assess import floor_from_dict

    return floor_from_dict(section, where)


def _stack(scene: dict, where: str) -> Any:
    from shaketable.scenes.stack import stack_scene_from_dict

    return stack_scene_from_dict(scene, where)


register_section_parser("sensors", _sensors)
register_section_parser("theory", _theory)
register_section_parser("floor", _floor)
register_section_parser("stack", _stack)   # a whole scene with [stack] (a column of blocks)
