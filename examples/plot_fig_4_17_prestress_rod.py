"""
Fig. 4.17: a block tied down by a prestress rod
===============================================

The 8 x 2 ft block held at its centre by a prestress rod (total stiffness 0.4 W/in,
prestress 0.4 W), COR 0.95, under Pacoima Dam S16E with the vertical (Section 2.8 and
Fig. 4.17).

The scene is bundled with the package (``shaketable run fig-4-17``); it names the block,
the motion, the COR and the report's values, which are compared with the run below.
"""

import pandas as pd

from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import load_scene
from shaketable.scenes.run import run_scene

scene = load_scene(resolve_scene_path("fig-4-17"))
print(scene.description)
result = run_scene(scene)
print(pd.Series(result.main.summary()).to_string())

# %%
# Report value against reproduced value:
columns = ["quantity", "report", "reproduced", "unit", "agrees"]
rows = [{name: getattr(c, name) for name in columns} for c in result.comparisons]
print(pd.DataFrame(rows, columns=columns).to_string(index=False))

# %%
# The report's Calcomp-style figure: ground motion, rotation, and the events.
result.plot()
