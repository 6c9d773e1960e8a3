"""
A sweep: fragility curves of three blocks
=========================================

How likely is a block to overturn at a given peak ground acceleration? A *sweep* runs
every combination of blocks, CORs, records and PGA levels named in a spec and returns one
tidy row per run (:func:`shaketable.sweeps.execute.run_sweep`); the fraction overturned
at each PGA, with a lognormal fragility curve fitted by maximum likelihood, is drawn by
:func:`shaketable.plots.sweeps.fragility_curve`.

The spec below is a small version of ``experiments/sweeps/artificial-fragility.toml``
(6 instead of 20 realisations of the olive-view SUBSTITUTE accelerogram, 8 PGA levels):
144 runs, a few seconds. The same from the command line::

    shaketable sweep experiments/sweeps/artificial-fragility.toml --out fragility
"""

import tempfile

from shaketable.plots.sweeps import fragility_curve
from shaketable.sweeps.execute import run_sweep
from shaketable.sweeps.spec import spec_from_dict

spec = spec_from_dict({
    "name": "fragility-demo",
    "seed": 1,
    "blocks": {"sizes": ["30x6in", "4x1ft", "8x2ft"]},
    "rocking": {"cor": 0.9},
    "records": [{"preset": "olive-view", "seeds": 6}],
    "intensity": {"pga": ["0.1 g", "0.2 g", "0.3 g", "0.4 g", "0.5 g", "0.6 g", "0.7 g",
                          "0.8 g"]},
})
outcome = run_sweep(spec, tempfile.mkdtemp(prefix="shaketable-sweep-"), progress=False)
table = outcome.table
print(f"{len(table)} runs in {outcome.seconds:.1f} s")
print(table[["block", "seed", "pga [g]", "status", "max_theta_ratio [-]"]].head(8)
      .to_string(index=False))

# %%
# Fraction overturned per block and PGA:
print(table.pivot_table(index="pga [g]", columns="block", values="overturned",
                        aggfunc="mean").round(2).to_string())

# %%
# Points: the fraction overturned at each PGA; lines: the lognormal fits.
fragility_curve(table)
