"""Scenes: an experiment as a TOML file that names only what it needs.

:mod:`~shaketable.scenes.parse` reads a scene once into frozen objects
(:class:`~shaketable.scenes.parse.Scene`, :class:`~shaketable.scenes.parse.Study`);
:mod:`~shaketable.scenes.catalog` finds the bundled ones by name;
:mod:`~shaketable.scenes.run` is the pipeline (motion, table, sensors, block,
theory) and :mod:`~shaketable.scenes.compare` sets the result beside the report.
The parser imports no study: the studies' items are registered here.
"""

from shaketable.scenes.parse import register_study_items


def _teaching_items() -> tuple[str, ...]:
    from shaketable.studies.teaching import ITEMS  # the engine: loaded when a scene asks

    return tuple(ITEMS)


register_study_items("teaching", _teaching_items)
