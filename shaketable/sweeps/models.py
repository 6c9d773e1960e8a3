"""The model a sweep runs: the model axis of a sweep spec.

A sweep runs one model over its grid, chosen by the spec (``model = "..."``, or by the
section that gives the model's parameters): the rocking block (the default, the compiled
rocking batch, :class:`RockingSweep`), the planar block with friction (``[friction]``,
:class:`PlanarSweep`: the coupled model's batch, :mod:`shaketable.sweeps.friction`) or a
column of blocks (``[stacks]``, :class:`shaketable.sweeps.stacks.StackSweep`). Each model
says how many runs one block and COR of the grid make (its own axis, as the friction
pairs), what its sweep folder records (:meth:`manifest`), how a run is written for its
batch (:meth:`case`), which block the rows' block columns describe (:meth:`lead_block`)
and runs a chunk (:meth:`simulate`): the executor (:mod:`shaketable.sweeps.execute`) has
no path of its own for any model.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from shaketable.core.units import parse_angle_or_ratio
from shaketable.sweeps.base import SweepError

if TYPE_CHECKING:
    import pandas as pd

    from shaketable.sweeps.friction import FrictionGrid
    from shaketable.sweeps.spec import SweepSpec


@dataclass(frozen=True)
class RockingSweep:
    """The rocking block (Housner's model with the report's COR), the default model."""

    name: str = "rocking"

    #: Whether ``--workers`` counts processes that each compute whole chunks (a model
    #: whose runs are not a compiled, multi-threaded batch); else threads of the batch.
    processes = False

    @property
    def axis(self) -> tuple:
        """The model's own axis between the block and the COR (none: one value)."""
        return ()

    def manifest(self) -> dict:
        """What the sweep folder's manifest records of the model, by key (a resume with
        other entries is refused): nothing for the rocking block (its folders hold none)."""
        return {}

    def check(self, spec: SweepSpec, rocking: dict) -> None:
        """Refuse, naming the key, what the model does not take (nothing here)."""

    def describe(self) -> str | None:
        """The line the ``sweep`` command prints of the model (None: none)."""
        return None

    def case(self, subject: Any, motion: Any, cor: float, scale: float, block_label: str,
             motion_label: str) -> Any:
        """One run of the chunk as the model's batch takes it."""
        from shaketable.models.rocking.batch import Case

        return Case(subject, motion, cor, scale=scale, block_label=block_label,
                    motion_label=motion_label)

    def lead_block(self, subject: Any) -> Any:
        """The :class:`~shaketable.core.geometry.Block` of the rows' ``R [m]`` and
        block-normalised measures (the block itself)."""
        return subject

    def label(self, subject: Any) -> str:
        """The ``block`` column of the subject."""
        return subject.describe()

    def simulate(self, spec: SweepSpec, inputs: pd.DataFrame, cases: list,
                 threads: int | None) -> tuple:
        """The model's rows of a chunk (one per row of ``inputs``) and the ensemble columns
        (None without ``[ensemble]``)."""
        if spec.ensemble is None:
            return simulate_rocking(spec, inputs, cases, threads), None
        return simulate_ensembles(spec, inputs, cases, threads)


@dataclass(frozen=True)
class PlanarSweep(RockingSweep):
    """The planar block with Coulomb friction (``[friction]``): its parameters, the
    (mu_s, mu_d) pairs, are the model's axis."""

    friction: FrictionGrid | None = None
    name: str = "planar"

    @property
    def axis(self) -> tuple:
        assert self.friction is not None
        return self.friction.pairs

    def manifest(self) -> dict:
        assert self.friction is not None
        return {"friction": self.friction.manifest()}

    def check(self, spec: SweepSpec, rocking: dict) -> None:
        from shaketable.sweeps.friction import check_friction_spec

        check_friction_spec(spec, rocking)

    def describe(self) -> str | None:
        return ("[friction]: the coupled planar model (rest, slide, rock, slide-rock, flight), "
                f"{len(self.axis)} friction pair(s) (mu_s, mu_d)")

    def simulate(self, spec: SweepSpec, inputs: pd.DataFrame, cases: list,
                 threads: int | None) -> tuple:
        from shaketable.sweeps.friction import simulate_friction

        return simulate_friction(spec, inputs, cases, threads), None


#: The models a spec may name (``model = "..."``).
MODEL_NAMES = ("rocking", "planar", "stack")


def chosen_model(data: dict, where: str) -> str:
    """``model = "..."``, or the model that the sections choose: ``[stacks]`` the stack model,
    ``[friction]`` the planar model, else the rocking block; a section of another model
    is refused by name."""
    chosen = "stack" if "stacks" in data else "planar" if "friction" in data else "rocking"
    name = data.get("model", chosen)
    if name not in MODEL_NAMES:
        raise SweepError(f"{where}: 'model' must be one of {', '.join(MODEL_NAMES)}, got "
                         f"{name!r}")
    if "stacks" in data and "friction" in data:
        raise SweepError(f"{where}: [stacks] with [friction]: the stack model does not slide; "
                         "drop one of them")
    if name != chosen:
        needs = {"stack": "[stacks]", "planar": "[friction]"}
        raise SweepError(f"{where}: model = {name!r} " + (
            f"needs {needs[name]}" if name in needs else
            f"takes no {needs[chosen]} (it is the {chosen} model's section)"))
    if name == "stack" and "blocks" in data:
        raise SweepError(f"{where}: [blocks] with [stacks]: the stacks take the place of the "
                         "blocks; give the columns' sizes in [stacks]")
    return name


def simulate_rocking(spec: SweepSpec, inputs, cases: list, threads):
    """The batch rows of ``cases`` (one per row of ``inputs``), in order."""
    import pandas as pd

    from shaketable.models.rocking.batch import simulate_cases

    options = {key: value for key, value in spec.options.items() if key != "theta0"}
    theta0_text = spec.options.get("theta0")
    if theta0_text is None:
        return simulate_cases(cases, threads=threads, method=spec.method,
                              duration=spec.duration, **options)
    # "k alpha" depends on the block: one batch per block
    parts = []
    for block_index, group in inputs.groupby("block_index", sort=False):
        theta0 = parse_angle_or_ratio(theta0_text, spec.blocks[block_index].alpha)
        subset = [cases[i] for i in group.index]
        part = simulate_cases(subset, threads=threads, method=spec.method,
                              duration=spec.duration, theta0=theta0, **options)
        part.index = group.index
        parts.append(part)
    return pd.concat(parts).sort_index()


#: Ensemble columns a sweep row gains with ``[ensemble]`` (:func:`verdict_statistics` names).
ENSEMBLE_COLUMNS = {"members": "members", "overturned": "overturned members",
                    "P(overturn) [-]": "P(overturn) [-]", "P low [-]": "P low [-]",
                    "P high [-]": "P high [-]", "robust": "robust",
                    "standing members": "standing members",
                    "median max theta/alpha [-]": "median max theta/alpha [-]",
                    "p05 max theta/alpha [-]": "p05 max theta/alpha [-]",
                    "p95 max theta/alpha [-]": "p95 max theta/alpha [-]"}


def simulate_ensembles(spec: SweepSpec, inputs, cases: list, threads):
    """Each cell's ensemble in one batch: the nominal rows and the ensemble columns.

    Member k of every cell has the k-th draw of
    :func:`shaketable.core.ensemble.perturbed_members` (a function of the spec
    alone, so a chunk's rows do not depend on the chunking or on a resume);
    member 0 is the cell's own case, so its row is the row of the sweep
    without ``[ensemble]``.
    """
    import pandas as pd

    from shaketable.core.ensemble import (
        Perturbation,
        perturbed_block,
        perturbed_cor,
        perturbed_members,
        shifted,
        verdict_statistics,
    )
    from shaketable.models.rocking.batch import Case

    ensemble = spec.ensemble
    assert ensemble is not None   # called for a sweep with [ensemble] only
    members = ensemble["members"]
    drawn = perturbed_members(members, Perturbation(**ensemble["spreads"]),
                              ensemble["seed"])
    copies: dict = {}           # shifted copies of each motion, shared by its cells
    expanded = []
    for case in cases:
        key = (id(case.motion), case.motion_label)
        if key not in copies:
            copies[key] = [shifted(case.motion, s * case.motion.dt) for s in drawn.start]
        for k in range(members):
            expanded.append(Case(perturbed_block(case.block, drawn, k), copies[key][k],
                                 perturbed_cor(case.cor, drawn, k),
                                 scale=case.scale * float(drawn.amplitude[k]),
                                 block_label=case.block_label, motion_label=case.motion_label))
    repeated = inputs.loc[inputs.index.repeat(members)].reset_index(drop=True)
    frame = simulate_rocking(spec, repeated, expanded, threads)
    overturned = frame["overturned"].to_numpy().reshape(len(cases), members)
    ratio = frame["max_theta_ratio [-]"].to_numpy().reshape(len(cases), members)
    rows = []
    for k in range(len(cases)):
        summary = verdict_statistics(overturned[k], ratio[k])
        row = {name: summary[key] for key, name in ENSEMBLE_COLUMNS.items()}
        row["mark"] = "robust" if summary["robust"] else "fragile"
        rows.append(row)
    nominal = frame.iloc[::members].reset_index(drop=True)
    return nominal, pd.DataFrame(rows)


