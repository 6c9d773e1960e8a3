"""What the parts of a sweep spec share: :class:`SweepError` and :class:`RecordSpec`.

They sit below :mod:`shaketable.sweeps.spec` so that the section readers it calls
(:mod:`~shaketable.sweeps.targets`, :mod:`~shaketable.sweeps.suites`,
:mod:`~shaketable.sweeps.friction`) can use them without importing the spec parser.
"""

from __future__ import annotations

from dataclasses import dataclass


class SweepError(ValueError):
    """A sweep spec (or output folder) that cannot be used; the message names file and key."""


@dataclass(frozen=True)
class RecordSpec:
    """One entry of ``[[records]]``.

    Attributes
    ----------
    kind : str
        ``"bundled"``, ``"file"`` or ``"artificial"``.
    label : str
        Name in the result table (``motion`` column).
    name : str
        Bundled record name (:func:`shaketable.ground.records.available`).
    vertical : bool
        Keep the bundled record's vertical component.
    file : str
        Absolute path of a record file.
    options : tuple
        Reader options (``units``, ``dt`` [s], ``value_column``) for a file,
        or generator options (``duration`` [s], ``dt`` [s], ``pga`` [m/s^2],
        ``vertical_pga`` [m/s^2]) for an artificial record, as (key, value) pairs.
    preset : str
        Artificial preset (:data:`shaketable.ground.generators.PRESETS`).
    seeds : tuple of int
        Seeds of the artificial realisations (``(None,)`` for a recorded motion).
    """

    kind: str
    label: str
    name: str = ""
    vertical: bool = True
    file: str = ""
    options: tuple = ()
    preset: str = ""
    seeds: tuple = (None,)
    suite: str = ""
