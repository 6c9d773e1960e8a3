"""
Calibrating the COR from a measured free-rocking record
=======================================================

The workflow of Section 3.5 of the report, for a record of your own: release the block,
record the top displacement, find the coefficient of restitution. The report overlaid
BLOKROC curves "by eye" (COR 0.925 for the 30 x 6 in block); the package fits it by least
squares and gives an interval (:func:`shaketable.calibration.calibrate`).

No measured record of the report's is available, so this example first *makes* one: the
virtual test of Fig. 3.4 (wire potentiometer at the top, anti-alias filter, 50 samples/s
digitizer), written to a CSV file in a temporary folder exactly as a data logger would
write it. From there on the steps are those for a real record. The same from the
command line::

    shaketable calibrate record.csv --block 30x6in --column "top displacement [in]" --out cal
"""

import tempfile
from pathlib import Path

import shaketable as st
from shaketable.calibration import calibrate, read_record
from shaketable.scenes.catalog import resolve_scene_path
from shaketable.scenes.parse import load_scene
from shaketable.scenes.run import run_scene

folder = Path(tempfile.mkdtemp(prefix="shaketable-calibration-"))
virtual = run_scene(load_scene(resolve_scene_path("fig-3-4"))).tests[0]
logged = virtual.measurement.to_frame()[["time [s]", "top displacement [in]"]]
logged.to_csv(folder / "free-rocking.csv", index=False)
print((folder / "free-rocking.csv").read_text().splitlines()[:4])

# %%
# Read the record and fit. The anti-alias filter of the acquisition is unknown to the
# fit: it is modelled as a Butterworth low-pass whose cutoff is fitted too.
block = st.Block.parse("30x6in")
record = read_record(folder / "free-rocking.csv", column="top displacement [in]")
calibration = calibrate(record, block)
print(calibration.text())

# %%
# The record, the best fit and the residuals; the block's true COR here is 0.925.
calibration.plot()

# %%
# The result is saved as JSON beside the record (in the temporary folder):
calibration.to_json(folder / "calibration.json")
print(sorted(path.name for path in folder.iterdir()))
