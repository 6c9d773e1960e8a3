"""Parameter sweeps: a TOML spec of blocks x records x intensities x CORs, run in chunks.

:mod:`~shaketable.sweeps.spec` reads and checks the spec, :mod:`~shaketable.sweeps.execute`
runs it (locally or on a Dask cluster) and :mod:`~shaketable.sweeps.store` writes the
Parquet/CSV parts that make a sweep resumable; :mod:`~shaketable.sweeps.fragility` fits
fragility curves to the table; :mod:`~shaketable.sweeps.models` is the model axis (the
rocking block; the planar model, whose parameters :mod:`~shaketable.sweeps.friction` reads
from ``[friction]``; a column of blocks, :mod:`~shaketable.sweeps.stacks`).
"""

from shaketable.sweeps.execute import (
           SweepOutcome,
           run_sweep,
           runs_table,
           solver_identity,
)
from shaketable.sweeps.spec import SweepError, SweepSpec, load_spec, spec_from_dict
from shaketable.sweeps.store import parquet_available, read_results

__all__ = ["SweepError", "SweepOutcome", "SweepSpec", "load_spec", "parquet_available",
           "read_results", "run_sweep", "runs_table", "solver_identity", "spec_from_dict"]
