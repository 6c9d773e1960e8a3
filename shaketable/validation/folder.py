"""A folder of measured shake-table tests: metadata, one motion per test, outcomes per specimen.

The layout (that of the measured granite-rock tests the docs validate against, and of any
other set of tests laid out the same way)::

    FOLDER/
      metadata.csv          one row per test
      tests/T013.npz ...    one motion per test (the path in the ``file`` column)

``metadata.csv`` columns (others are kept and ignored):

* ``test``: the test's identifier (unique);
* ``file``: the motion's path relative to the folder: a ``.npz`` holding ``acc_h`` [m/s^2]
  and ``fs`` [Hz] (or ``t`` [s]), or any record file :func:`shaketable.ground.records.read`
  reads (AT2, text);
* ``specimens`` (optional): the specimens of the test joined by ``+`` (``SP1+SP2``);
* ``<specimen>_overturned`` (optional): the measured outcome, 1 overturned, 0 not. A folder
  without them is a folder to predict;
* ``pga_g``, ``pgv_mps`` (optional): peak table acceleration [g] and velocity [m/s];
  computed from the motion when absent.

Specimen names are taken from the outcome columns, else from ``specimens``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from shaketable.core.constants import G
from shaketable.core.motion import Motion

#: Suffix of an outcome column: ``SP1_overturned``.
OUTCOME_SUFFIX = "_overturned"


@dataclass(frozen=True, eq=False)
class TestFolder:
    """The tests of one folder (see the module docstring for the layout).

    Attributes
    ----------
    path : Path
        The folder.
    metadata : pandas.DataFrame
        ``metadata.csv`` as read, one row per test, with ``pga [m/s^2]`` and
        ``pgv [m/s]`` added.
    specimens : tuple of str
        The specimens (lower case, as in the outcome columns' names).
    """

    __test__ = False  # not a pytest class

    path: Path
    metadata: object
    specimens: tuple[str, ...]
    _motions: dict = field(default_factory=dict, repr=False)

    @property
    def tests(self) -> list[str]:
        """The tests' identifiers, as text."""
        return [str(value) for value in self.metadata["test"]]  # type: ignore[index]

    def has_outcomes(self, specimen: str) -> bool:
        """True when the folder holds the measured outcome of ``specimen``."""
        return f"{specimen}{OUTCOME_SUFFIX}" in self.metadata.columns  # type: ignore[attr-defined]

    def outcomes(self, specimen: str) -> np.ndarray:
        """The measured outcomes of ``specimen`` (1 overturned, 0 not), one per test."""
        column = f"{specimen}{OUTCOME_SUFFIX}"
        if not self.has_outcomes(specimen):
            raise ValueError(f"{self.path / 'metadata.csv'}: no column {column!r} (the measured "
                             f"outcome of {specimen}); this folder has none to score against")
        values = self.metadata[column].to_numpy()  # type: ignore[index]
        bad = ~np.isin(values, (0, 1))
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            raise ValueError(f"{self.path / 'metadata.csv'}, line {row + 2}: {column} must be "
                             f"0 or 1, got {values[row]!r}")
        return values.astype(int)

    def motion(self, index: int) -> Motion:
        """The table motion of test ``index`` (0-based row), horizontal [m/s^2]."""
        if index not in self._motions:
            self._motions[index] = _read_motion(self.path, self.metadata.iloc[index],  # type: ignore[attr-defined]
                                                index)
        return self._motions[index]

    def motions(self) -> list[Motion]:
        """Every test's motion, in row order."""
        return [self.motion(k) for k in range(len(self.tests))]

    def subset(self, rows) -> "TestFolder":
        """The tests of ``rows`` (0-based indices) as a folder of their own (motions shared)."""
        rows = np.asarray(rows, dtype=int)
        frame = self.metadata.iloc[rows].reset_index(drop=True)  # type: ignore[attr-defined]
        motions = {new: self._motions[old] for new, old in enumerate(rows) if old in self._motions}
        return TestFolder(self.path, frame, self.specimens, motions)


def _read_motion(folder: Path, row, index: int) -> Motion:
    path = folder / str(row["file"])
    where = f"{folder / 'metadata.csv'}, line {index + 2}"
    if not path.is_file():
        raise ValueError(f"{where}: the motion file {path} does not exist")
    if path.suffix.lower() == ".npz":
        with np.load(path) as data:
            if "acc_h" not in data:
                raise ValueError(f"{path}: no array 'acc_h' (the table acceleration [m/s^2])")
            acceleration = np.asarray(data["acc_h"], dtype=float)
            if "t" in data:
                t = np.asarray(data["t"], dtype=float)
            elif "fs" in data:
                start = float(data["t0"]) if "t0" in data else 0.0
                t = start + np.arange(acceleration.size) / float(data["fs"])
            else:
                raise ValueError(f"{path}: neither 't' [s] nor 'fs' [Hz] in the file")
        return Motion(t, acceleration, name=f"test {row['test']}")
    from shaketable.ground.records import combine, read

    return combine(read(path))


def read_folder(path) -> TestFolder:
    """Read a folder of tests (the module docstring gives the layout).

    Raises
    ------
    ValueError
        The folder or ``metadata.csv`` missing, a required column missing, duplicate tests;
        the message names the file and line.
    """
    import pandas as pd

    folder = Path(path)
    table = folder / "metadata.csv"
    if not table.is_file():
        raise ValueError(f"{folder}: no metadata.csv (a folder of tests has metadata.csv and "
                         "one motion file per test)")
    frame = pd.read_csv(table)
    for column in ("test", "file"):
        if column not in frame.columns:
            raise ValueError(f"{table}: no column {column!r}")
    duplicated = frame["test"].astype(str).duplicated()
    if duplicated.any():
        row = int(np.flatnonzero(duplicated.to_numpy())[0])
        raise ValueError(f"{table}, line {row + 2}: test {frame['test'][row]!r} appears twice")
    specimens = [name[: -len(OUTCOME_SUFFIX)] for name in frame.columns
                 if name.endswith(OUTCOME_SUFFIX)]
    if not specimens and "specimens" in frame.columns:
        names: list[str] = []
        for value in frame["specimens"].astype(str):
            names.extend(part.strip().lower() for part in value.split("+") if part.strip())
        specimens = list(dict.fromkeys(names))
    if not specimens:
        raise ValueError(f"{table}: no specimen named (neither '<specimen>{OUTCOME_SUFFIX}' "
                         "columns nor a 'specimens' column)")
    result = TestFolder(folder, frame, tuple(specimens))
    pga = (frame["pga_g"].to_numpy(dtype=float) * G if "pga_g" in frame.columns else None)
    pgv = frame["pgv_mps"].to_numpy(dtype=float) if "pgv_mps" in frame.columns else None
    if pga is None or pgv is None:
        from shaketable.ground.intensity import pgv as peak_velocity

        motions = result.motions()
        if pga is None:
            pga = np.array([motion.pga for motion in motions])
        if pgv is None:
            pgv = np.array([peak_velocity(motion) for motion in motions])
    frame["pga [m/s^2]"] = pga
    frame["pgv [m/s]"] = pgv
    return result


def specimen_labels(folder: TestFolder) -> dict[str, str]:
    """Each specimen's name as the folder spells it for people: the ``specimens`` column's
    spelling (``SP1`` of ``SP1+SP2``) of the lower-case name of the outcome columns
    (``sp1_overturned``); the name itself when the column does not give it."""
    labels = {name: name for name in folder.specimens}
    metadata: Any = folder.metadata
    if "specimens" in metadata.columns:
        for value in metadata["specimens"].astype(str):
            for part in (part.strip() for part in value.split("+")):
                if part.lower() in labels and labels[part.lower()] == part.lower():
                    labels[part.lower()] = part
    return labels
