"""Scenes: an experiment as a TOML file that names only what it needs.

:mod:`~shaketable.scenes.parse` reads a scene once into frozen objects
(:class:`~shaketable.scenes.parse.Scene`, :class:`~shaketable.scenes.parse.Study`);
:mod:`~shaketable.scenes.catalog` finds the bundled ones by name;
:mod:`~shaketable.scenes.run` is the pipeline (motion, table, sensors, block,
theory) and :mod:`~shaketable.scenes.compare` sets the result beside the report.
The parser imports no study: the studies' items are registered here.
"""

from shaketable.scenes.parse import register_study_items
from shaketable.studies.teaching import ITEMS as _TEACHING_ITEMS

register_study_items("teaching", _TEACHING_ITEMS)
