"""
Fig. 3.4: free rocking, test against theory with a calibrated COR
=================================================================

The report released the 30 x 6 in block near half its block angle, recorded the rocking
with a wire potentiometer at 50 samples/s and matched BLOKROC curves "by eye": COR 0.925
and a rest after about 6 s. The bundled scene makes the virtual test (the block, the
sensors, the digitizer), calibrates the COR from its record by least squares
(:func:`shaketable.calibration.calibrate`) and runs the theory with it.
"""

import pandas as pd

from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import load_scene
from shaketable.scenes.run import run_scene

scene = load_scene(resolve_scene_path("fig-3-4"))
result = run_scene(scene)
test = result.tests[0]
print(pd.Series(test.metrics()).to_string())

# %%
# Report value against reproduced value:
columns = ["quantity", "report", "reproduced", "unit", "agrees"]
rows = [{name: getattr(c, name) for name in columns} for c in result.comparisons]
print(pd.DataFrame(rows, columns=columns).to_string(index=False))

# %%
# The virtual test record against the theory run with the calibrated COR (Fig. 3.4):
test.plot(title="Fig. 3.4: test vs theory, 30 x 6 in block")

# %%
# And the theory run alone, Calcomp style:
result.plot()
