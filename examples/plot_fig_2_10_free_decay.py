"""
Fig. 2.10: free rocking with energy loss
========================================

Free rocking of the 36 x 9 in block from 0.15 rad with COR 0.95: each impact takes
energy, the amplitude decays and the period shortens.

The scene is bundled with the package (``shaketable run fig-2-10``); it names the block,
the motion and the COR (the report gives this figure without numbers to compare).
"""

import pandas as pd

from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import load_scene
from shaketable.scenes.run import run_scene

scene = load_scene(resolve_scene_path("fig-2-10"))
print(scene.description)
result = run_scene(scene)
print(pd.Series(result.main.summary()).to_string())


# %%
# The report's Calcomp-style figure: ground motion, rotation, and the events.
result.plot()
