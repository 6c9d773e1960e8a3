"""Rock, slide or anchor: one assessment of a real object, at grade or on a floor.

The report's purpose (Summary 1, Conclusion 6 of [1]_) is a decision for a free-standing
massive object: let it slide, let it rock, or anchor it. :func:`run_assessment` puts
together what the package already computes, and re-implements none of it:

1. the planar block's mode map of this object over friction at each demand level
   (:func:`shaketable.studies.mode_map.mode_map`) beside Section 2.1's rule mu = B/H;
2. free-standing: P(overturn) with its Wilson interval, the peak corner excursion and
   peak slip (median, 84th percentile, range over the records) per level at both ends
   of the friction range, the lognormal fragility
   (:func:`shaketable.sweeps.fragility.fragility_fit`) and, with a hazard curve, the
   annual rate and the design-life probability (:func:`shaketable.sweeps.risk.overturning_rate`);
3. let it slide (a lower friction, Conclusion 6): slip and excursion against the clearance;
4. anchored: the base shear, overturning moment and uplift of the same object fixed to
   its floor (a rigid body: m a(t) at its centre of mass) beside ASCE 7-16's Fp;
5. the codes' checks (:mod:`shaketable.studies.codes`);
6. a recommendation with its reasons and the assumptions.

The floor motion is :func:`shaketable.ground.floor.floor_motion` of each scaled record.
Data only: the figures are in :mod:`shaketable.plots.assess`.

References
----------
.. [1] M. Aslam, W. G. Godden and D. T. Scalise, "Rocking and overturning response of
   rigid bodies to earthquake motions", Lawrence Berkeley Laboratory, University of
   California, Berkeley.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from shaketable.core.constants import G
from shaketable.core.ensemble import wilson_interval
from shaketable.core.geometry import Block
from shaketable.core.motion import Motion
from shaketable.ground import records
from shaketable.ground.artificial import artificial
from shaketable.ground.floor import Building, floor_motion
from shaketable.ground.signals import response_spectrum, scale_to_pga
from shaketable.studies import codes
from shaketable.studies.mode_map import mode_map
from shaketable.sweeps.fragility import fragility_fit
from shaketable.sweeps.risk import HazardCurve, overturning_rate

#: Friction coefficients of the mode map's strip (mu_s = mu_d) [-], besides the object's.
MAP_FRICTIONS = tuple(np.round(np.arange(0.05, 0.801, 0.05), 3))

#: Fewest demand levels a fragility is fitted to (two stripes identify no lognormal shape).
MIN_FIT_LEVELS = 3

#: Default record suite: the bundled horizontal records of the report's Section 4 events.
DEFAULT_RECORDS = ("pacoima-dam-s16e", "pacoima-dam-s74w", "el-centro-1940-180",
                   "el-centro-1940-270")

#: The model's assumptions, stated in every report.
ASSUMPTIONS = (
    "planar motion (one horizontal component at a time; the object's width in the "
    "direction of shaking is its B)",
    "a rigid object of uniform density (centre of mass at mid-height and mid-width)",
    "Coulomb friction with mu_s = mu_d, at each end of the friction range",
    "impacts by the package's planar impact law with the stated COR (the report's "
    "Section 2.7); no bouncing beyond what the model resolves",
    "the records scaled to each level's peak ground acceleration (both components alike)",
    "floor motions by a linear modal filter of the building (no yielding, no "
    "interaction with the object); the vertical passes unchanged",
    "the anchored object is rigid and rigidly fixed: its base shear is m a_h(t) and its "
    "moment m a_h(t) H/2 about the base",
    "the choice compares the share of records that overturn the object (the point "
    "estimate of P(overturn)) with the acceptable value, and the 84th percentile of the "
    "excursion with the clearance; the 95 % intervals are given beside them",
)


@dataclass(frozen=True)
class AssessedObject:
    """The object.

    Attributes
    ----------
    block : Block
        Height H and width B [m] (B in the direction of shaking).
    mass : float
        Mass [kg].
    frictions : tuple of float
        Low and high friction coefficient [-] (mu_s = mu_d), low <= high.
    cor : float
        Coefficient of restitution [-].
    cor_source : str
        Where the COR comes from (a number given, or a calibration file).
    """

    block: Block
    mass: float
    frictions: tuple
    cor: float
    cor_source: str = "given"


@dataclass(frozen=True)
class Demand:
    """The earthquake demand.

    Attributes
    ----------
    records : tuple of str
        Bundled record names (:func:`shaketable.ground.records.available`).
    levels : tuple of float
        Peak ground accelerations the records are scaled to [m/s^2], increasing.
    level_names : tuple of str
        A label per level (e.g. ``"design"``, ``"MCE"``).
    s_ds : float or None
        S_DS [g] for ASCE 7's Fp; None: 0.4 S_DS taken as each level's PGA (ASCE 7-16
        Eq. 11.4-5 at T = 0: S_a = 0.4 S_DS).
    artificial_preset : str or None
        Preset of the artificial accelerograms added to the suite.
    artificial_count : int
        How many (seeds 1..count).
    """

    records: tuple = DEFAULT_RECORDS
    levels: tuple = (0.3 * G,)
    level_names: tuple = ("level 1",)
    s_ds: float | None = None
    artificial_preset: str | None = None
    artificial_count: int = 0


@dataclass(frozen=True)
class Criteria:
    """What decides, and the codes' parameters.

    Attributes
    ----------
    clearance : float or None
        Free space around the object [m] (None: not checked).
    acceptable : float
        Acceptable P(overturn) at the highest level [-].
    slide_friction : float or None
        Friction of the let-it-slide option [-] (None: half of B/H).
    hazard : HazardCurve or None
        Site hazard curve in PGA (m/s^2) for the annual rate.
    years : float
        Design life [yr].
    a_p, r_p, i_p : float
        ASCE 7-16 component factors [-].
    fc : float
        NTC confidence factor FC [-].
    """

    clearance: float | None = None
    acceptable: float = 0.05
    slide_friction: float | None = None
    hazard: HazardCurve | None = None
    years: float = 50.0
    a_p: float = 1.0
    r_p: float = 2.5
    i_p: float = 1.0
    fc: float = 1.0


@dataclass(frozen=True)
class Assessment:
    """One assessment: the object, where it stands, the demand and the criteria.

    Attributes
    ----------
    name : str
        A short name (the report's title and folder name).
    obj : AssessedObject
    demand : Demand
    criteria : Criteria
    building : Building or None
        The building the object stands in; None (or ``floor`` 0) puts it at grade.
    floor : int
        The floor it stands on, 0 (the ground) to ``building.storeys`` (the roof).
    description : str
        One line for the report.
    """

    name: str
    obj: AssessedObject
    demand: Demand
    criteria: Criteria = field(default_factory=Criteria)
    building: Building | None = None
    floor: int = 0
    description: str = ""

    @property
    def at_grade(self) -> bool:
        return self.building is None or self.floor == 0

    @property
    def slide_friction(self) -> float:
        value = self.criteria.slide_friction
        return 0.5 * self.obj.block.width / self.obj.block.height if value is None else value

    @property
    def where(self) -> str:
        if self.at_grade:
            return "at grade"
        assert self.building is not None
        return (f"floor {self.floor} of a {self.building.storeys}-storey building (T1 = "
                f"{self.building.period:g} s, H = {self.building.height:g} m, "
                f"{self.building.shape} mode shape, {self.building.damping:.0%} damping)")


def ground_motions(demand: Demand) -> dict[str, Motion]:
    """The suite's ground motions, unscaled, by a short name (the bundled record's name,
    ``PRESET-seedN`` for the artificial ones)."""
    motions = {name: records.load(name) for name in demand.records}
    if demand.artificial_preset is not None:
        for seed in range(1, demand.artificial_count + 1):
            motions[f"{demand.artificial_preset}-seed{seed}"] = artificial(
                demand.artificial_preset, seed=seed)
    return motions


def demand_motions(spec: Assessment) -> dict:
    """``{(level index, record name): motion where the object stands}`` [m/s^2]."""
    result = {}
    for name, motion in ground_motions(spec.demand).items():
        for k, level in enumerate(spec.demand.levels):
            scaled = scale_to_pga(motion, pga=level)
            if not spec.at_grade:
                assert spec.building is not None
                scaled = floor_motion(scaled, spec.building, floor=spec.floor)
            result[(k, name)] = scaled
    return result


def _stats(values) -> dict:
    values = np.asarray(values, dtype=float)
    if values.size == 0:
        return {key: math.nan for key in ("median", "p84", "min", "max")}
    return {"median": float(np.median(values)), "p84": float(np.percentile(values, 84)),
            "min": float(np.min(values)), "max": float(np.max(values))}


@dataclass(frozen=True)
class AssessmentResult:
    """Everything the assessment found.

    Attributes
    ----------
    spec : Assessment
    runs : pandas.DataFrame
        The mode map's rows (one per level, record and friction): ``level``, ``level name``,
        ``ground pga [g]``, ``record`` and the columns of
        :class:`shaketable.studies.mode_map.ModeMap`, its ``pga [g]`` renamed
        ``floor pga [g]``: the PGA where the object stands (the floor's, after the
        building; the ground's at grade).
    free : pandas.DataFrame
        Per level and friction (the object's two ends and the let-it-slide value):
        P(overturn) and its Wilson 95 % interval, excursion and slip statistics [m] over
        the records that did not overturn it (NaN when all did).
    anchored : pandas.DataFrame
        Per level: peak floor acceleration, base shear, overturning moment and uplift
        (median and 84th percentile over records) [m/s^2, N, N m, N] beside ASCE 7 Fp.
    codes : dict
        Per level: the codes' checks (JSON-ready).
    fragility : dict
        Per friction end: the fit (median [g], beta, intervals) or why none.
    risk : dict
        Per friction end: lambda and the design-life probability, when a hazard is given.
    spectra : dict
        ``{level index: (frequencies [Hz], median 10 %-damped spectrum [m/s^2])}``.
    recommendation : dict
        ``choice`` and ``reasons``.
    """

    spec: Assessment
    runs: pd.DataFrame
    free: pd.DataFrame
    anchored: pd.DataFrame
    codes: dict
    fragility: dict
    risk: dict
    spectra: dict
    recommendation: dict

    def to_frame(self) -> pd.DataFrame:
        """The free-standing statistics per level and friction (a copy)."""
        return self.free.copy()

    def plot(self, which: str = "mode-map", fig=None):
        """A figure of :mod:`shaketable.plots.assess`: ``"mode-map"``, ``"demands"``,
        ``"anchored"`` or ``"floor-spectra"``."""
        from shaketable.plots.assess import assessment_figure

        return assessment_figure(self, which, fig=fig)


def _mode_runs(spec: Assessment, motions: dict) -> pd.DataFrame:
    """The mode map of the object (one B/H, a strip of frictions) per level and record."""
    block = spec.obj.block
    frictions = sorted(set(MAP_FRICTIONS) | set(spec.obj.frictions) | {spec.slide_friction})
    frames = []
    for (k, name), motion in motions.items():
        frame = mode_map(motion, pga_levels=(None,), aspect_ratios=(block.width / block.height,),
                         frictions=frictions, height=block.height, cor=spec.obj.cor).frame
        # the map's own PGA column is the floor's (the motion the object stands on)
        frame = frame.rename(columns={"pga [g]": "floor pga [g]"})
        frame.insert(0, "record", name)
        frame.insert(0, "ground pga [g]", spec.demand.levels[k] / G)
        frame.insert(0, "level name", spec.demand.level_names[k])
        frame.insert(0, "level", k)
        frames.append(frame)
    return pd.concat(frames, ignore_index=True)


def _free_statistics(spec: Assessment, runs: pd.DataFrame) -> pd.DataFrame:
    rows = []
    ends = {"low": spec.obj.frictions[0], "high": spec.obj.frictions[1],
            "let it slide": spec.slide_friction}
    for k, name in enumerate(spec.demand.level_names):
        for case, mu in ends.items():
            cells = runs[(runs["level"] == k) & np.isclose(runs["mu [-]"], mu)]
            n = len(cells)
            over = int(cells["overturned"].sum())
            low, high = wilson_interval(over, n)
            standing = cells[~cells["overturned"].astype(bool)]  # a fallen block has no excursion
            excursion = _stats(standing["peak corner excursion [m]"])
            slip = _stats(standing["peak base slip [m]"])   # the slide, not the rocking
            verdicts = cells["verdict"].value_counts()
            rows.append({
                "level": k, "level name": name, "ground pga [g]": spec.demand.levels[k] / G,
                "case": case, "mu [-]": mu, "records": n, "overturned": over,
                "P(overturn) [-]": over / n, "P low [-]": low, "P high [-]": high,
                **{f"excursion {key} [m]": value for key, value in excursion.items()},
                **{f"slip {key} [m]": value for key, value in slip.items()},
                "verdicts": ", ".join(f"{verdict} {count}" for verdict, count
                                      in verdicts.items()),
            })
    return pd.DataFrame(rows)


def _fragility_and_risk(spec: Assessment, runs: pd.DataFrame) -> tuple[dict, dict]:
    fragility, risk = {}, {}
    for case, mu in (("low", spec.obj.frictions[0]), ("high", spec.obj.frictions[1])):
        cells = runs[np.isclose(runs["mu [-]"], mu)]
        if len(spec.demand.levels) < MIN_FIT_LEVELS:
            fragility[case] = {"mu [-]": mu, "fit": None, "why not": (
                f"{len(spec.demand.levels)} levels; a fragility fit needs at least "
                f"{MIN_FIT_LEVELS}")}
            continue
        try:
            try:
                fit = fragility_fit(cells["ground pga [g]"] * G, cells["overturned"],
                                    measure="pga [m/s^2]")
            except ValueError as error:
                if "interval" not in str(error):
                    raise
                fit = fragility_fit(cells["ground pga [g]"] * G, cells["overturned"],
                                    measure="pga [m/s^2]", intervals=False)
        except ValueError as error:
            fragility[case] = {"mu [-]": mu, "fit": None, "why not": str(error)}
            continue
        fragility[case] = {
            "mu [-]": mu, "fit": fit, "median pga [g]": fit.median / G, "beta [-]": fit.beta,
            "median interval [g]": [v / G for v in fit.median_interval],
            "beta interval [-]": list(fit.beta_interval)}
        if spec.criteria.hazard is not None:
            result = overturning_rate(fit, spec.criteria.hazard, years=spec.criteria.years)
            # the fit's uncertainty: lambda at the ends of the median's interval (beta kept)
            ends = [overturning_rate(replace(fit, median=median), spec.criteria.hazard,
                                     years=spec.criteria.years, interval=False).rate
                    for median in fit.median_interval if math.isfinite(median)]
            risk[case] = {"mu [-]": mu, "lambda [1/yr]": result.rate,
                          "lambda upper [1/yr]": result.upper,
                          "lambda over the median's interval [1/yr]":
                              [min(ends), max(ends)] if len(ends) == 2 else None,
                          "years": result.years,
                          "P(overturn in life) [-]": result.probability,
                          "P upper [-]": result.probability_upper}
    return fragility, risk


def _anchored(spec: Assessment, motions: dict) -> pd.DataFrame:
    """Base shear, moment and uplift of the object fixed to its floor, per level."""
    block, mass = spec.obj.block, spec.obj.mass
    weight = mass * G
    rows = []
    for k, name in enumerate(spec.demand.level_names):
        shear, moment, uplift, pfa, pva = [], [], [], [], []
        for (level, _), motion in motions.items():
            if level != k:
                continue
            a_h = np.abs(motion.horizontal)
            a_v = motion.vertical_or_zero
            pfa.append(float(np.max(a_h)))
            pva.append(float(np.max(np.abs(a_v))))
            shear.append(mass * pfa[-1])
            moment.append(mass * pfa[-1] * block.height / 2.0)
            # tension on the anchors of one side: moments about the other edge
            tension = mass * (a_h * block.height / 2.0 - (G + a_v) * block.width / 2.0) \
                / block.width
            uplift.append(max(0.0, float(np.max(tension))))
        s_ds = _s_ds(spec, k)
        fp = codes.asce7_fp(weight, s_ds, z_over_h=_z_over_h(spec), a_p=spec.criteria.a_p,
                            r_p=spec.criteria.r_p, i_p=spec.criteria.i_p)
        over = codes.asce7_overturning(fp.fp, weight, s_ds, width=block.width,
                                       height_cg=block.height / 2.0)
        rows.append({
            "level": k, "level name": name, "ground pga [g]": spec.demand.levels[k] / G,
            "pfa median [g]": float(np.median(pfa)) / G,
            "pfa p84 [g]": float(np.percentile(pfa, 84)) / G,
            "pva median [g]": float(np.median(pva)) / G,
            "base shear median [N]": float(np.median(shear)),
            "base shear p84 [N]": float(np.percentile(shear, 84)),
            "moment p84 [N m]": float(np.percentile(moment, 84)),
            "uplift median [N]": float(np.median(uplift)),
            "uplift p84 [N]": float(np.percentile(uplift, 84)),
            "S_DS [g]": s_ds, "Fp [N]": fp.fp, "Fp governs": fp.governs,
            "Fp uplift [N]": over.uplift, "dead-load factor [-]": over.factor,
        })
    return pd.DataFrame(rows)


def _s_ds(spec: Assessment, k: int) -> float:
    if spec.demand.s_ds is not None:
        return spec.demand.s_ds
    return spec.demand.levels[k] / G / 0.4  # ASCE 7-16 Eq. 11.4-5 at T = 0


def _z_over_h(spec: Assessment) -> float:
    if spec.at_grade:
        return 0.0
    assert spec.building is not None
    return spec.floor / spec.building.storeys


def _floor_spectra(motions: dict, levels: tuple) -> dict:
    """Median 10 %-damped horizontal spectrum where the object stands, per level.

    The floor filter and the spectrum are linear in the ground motion, so each record's
    spectrum is computed once, at the first level, and scaled to the others.
    """
    frequencies = np.geomspace(0.2, 33.0, 40)
    curves = [response_spectrum(motion, 1.0 / frequencies, damping=0.10)
              for (level, _), motion in motions.items() if level == 0]
    median = np.median(np.vstack(curves), axis=0)
    return {k: (frequencies, median * level / levels[0]) for k, level in enumerate(levels)}


def _codes(spec: Assessment, anchored: pd.DataFrame, spectra: dict) -> dict:
    block = spec.obj.block
    alpha0 = codes.kinematic_multiplier(block.width, block.height)
    a0 = codes.kinematic_a0(alpha0, fc=spec.criteria.fc)
    result = {}
    for row in anchored.itertuples(index=False):
        k = row.level
        demand = row[anchored.columns.get_loc("pfa median [g]")] * G
        frequencies, spectrum = spectra[k]
        sliding = codes.asce43_sliding(spec.obj.frictions[0],
                                       row[anchored.columns.get_loc("pva median [g]")] * G,
                                       frequencies=frequencies, spectrum=spectrum)
        result[spec.demand.level_names[k]] = {
            "ASCE 7-16 13.3.1": {"S_DS [g]": row[anchored.columns.get_loc("S_DS [g]")],
                                 "z/h [-]": _z_over_h(spec),
                                 "Fp [N]": row[anchored.columns.get_loc("Fp [N]")],
                                 "Fp / W [-]": row[anchored.columns.get_loc("Fp [N]")]
                                 / (spec.obj.mass * G),
                                 "governs": row[anchored.columns.get_loc("Fp governs")],
                                 "overturning uplift [N]":
                                     row[anchored.columns.get_loc("Fp uplift [N]")],
                                 "stable without anchors":
                                     row[anchored.columns.get_loc("Fp uplift [N]")] == 0.0},
            "NTC 2018 C8.7.1 (linear kinematic)": {
                "alpha0 [-]": alpha0, "FC [-]": spec.criteria.fc, "a0* [g]": a0 / G,
                "demand [g]": demand / G,
                "demand is": ("the level's PGA (a_g S) without the behaviour factor q"
                              if spec.at_grade else
                              "the median peak floor acceleration from the modal filter, "
                              "not the Circolare's floor spectrum and without q"),
                "a0* >= demand": a0 >= demand},
            "ASCE 43-05 A.1 (sliding)": {
                "mu [-]": spec.obj.frictions[0], "A_v [g]":
                    row[anchored.columns.get_loc("pva median [g]")],
                "mu_e [-]": sliding.mu_e, "c_s [g]": sliding.c_s / G,
                "f_s [Hz]": sliding.f_s,
                "10 %-damped spectrum reaches c_s": not math.isnan(sliding.f_s)},
        }
    return result


def same_friction_note(free: pd.DataFrame, level: int, ratio: float) -> str:
    """Why the low- and high-friction rows of ``level`` in ``free`` (the free-standing
    statistics) agree, when they do to the printed precision (the same overturn count,
    corner excursions to the mm): with both frictions above B/H = ``ratio`` the object
    rocks (Section 2.1), and friction changes a rocking run only where its base slips. ""
    when they differ or the object slides at either."""
    rows = free[free["level"] == level].set_index("case")
    if not {"low", "high"} <= set(rows.index):
        return ""
    low, high = rows.loc["low"], rows.loc["high"]
    if min(low["mu [-]"], high["mu [-]"]) <= ratio or low["overturned"] != high["overturned"]:
        return ""
    keys = ("excursion median [m]", "excursion p84 [m]")
    if any(f"{low[key] * 1000:.0f}" != f"{high[key] * 1000:.0f}" for key in keys):
        return ""
    slip = np.nanmax([low["slip max [m]"], high["slip max [m]"]])
    slipped = ("no base slipped in a run it survives" if not slip > SLIP_NOISE else
               f"at most {format_slip_mm(slip)} mm in a run it survives")
    return (f"with mu above B/H = {ratio:.3g} the object rocks at both frictions (Section "
            f"2.1), and friction changes a rocking run only where its base slips ({slipped})")


#: A base slip below this [m] is rounding (a corner that did not slide).
SLIP_NOISE = 1e-9


def format_slip_mm(value: float) -> str:
    """A slip [m] in mm: whole mm from 1 mm on, two significant digits below (a slip of
    a few micrometres is a slip, not 0), 0 below :data:`SLIP_NOISE`, "-" for NaN."""
    if math.isnan(value):
        return "-"
    if value < SLIP_NOISE:
        return "0"
    return f"{value * 1000:.0f}" if value >= 0.5e-3 else f"{value * 1000:.2g}"


def _count(records: int) -> str:
    return f"{records} record" + ("" if records == 1 else "s")


def _recommend(spec: Assessment, free: pd.DataFrame, anchored: pd.DataFrame,
               risk: dict) -> dict:
    """The choice at the highest level, with its reasons."""
    top = len(spec.demand.levels) - 1
    name = spec.demand.level_names[top]
    clearance = spec.criteria.clearance
    acceptable = spec.criteria.acceptable
    reasons = []

    def verdict(case: str) -> tuple[bool, str]:
        row = free[(free["level"] == top) & (free["case"] == case)].iloc[0]
        ok = row["P(overturn) [-]"] <= acceptable
        text = (f"{case} friction (mu = {row['mu [-]']:.3g}) at the {name} level: "
                f"{row['overturned']} of {_count(row['records'])} overturn it, P(overturn) = "
                f"{row['P(overturn) [-]']:.2f} {'within' if ok else 'above'} the acceptable "
                f"{acceptable:g} (95 % interval [{row['P low [-]']:.2f}, "
                f"{row['P high [-]']:.2f}] with {_count(row['records'])})")
        if ok and row["P high [-]"] > acceptable:
            text += (f"; the interval reaches above {acceptable:g}: {_count(row['records'])} "
                     f"cannot show that P(overturn) is within it")
        if clearance is not None:
            fits = bool(row["excursion p84 [m]"] <= clearance)
            ok = ok and fits
            if math.isnan(row["excursion p84 [m]"]):
                text += "; no record leaves it standing"
            else:
                text += (f"; corner excursion 84th percentile (records it survives) "
                         f"{row['excursion p84 [m]'] * 1000:.0f} mm "
                         f"{'within' if fits else 'beyond'} the clearance "
                         f"{clearance * 1000:.0f} mm")
        return bool(ok), text

    free_ok_low, text_low = verdict("low")
    free_ok_high, text_high = verdict("high")
    slide_ok, text_slide = verdict("let it slide")
    note = same_friction_note(free, top, spec.obj.block.width / spec.obj.block.height)
    if note:
        text_high += f"; as at low friction: {note}"
    reasons += [text_low, text_high, text_slide]
    for case, entry in risk.items():
        reasons.append(f"with the site hazard, {case} friction: P(overturn in "
                       f"{entry['years']:g} yr) = {entry['P(overturn in life) [-]']:.2g} "
                       f"(lambda = {entry['lambda [1/yr]']:.2g} /yr)")
    if free_ok_low and free_ok_high:
        choice = "leave it free-standing"
    elif slide_ok:
        choice = (f"let it slide: lower the friction to mu = {spec.slide_friction:.3g} "
                  f"(Conclusion 6 of the report)")
    else:
        row = anchored[anchored["level"] == top].iloc[0]
        design = max(row["base shear p84 [N]"], row["Fp [N]"])
        uplift = max(row["uplift p84 [N]"], row["Fp uplift [N]"])
        choice = (f"anchor it: design the anchors for a base shear of at least "
                  f"{design / 1000:.3g} kN and an uplift of {uplift / 1000:.3g} kN on one "
                  f"side (the larger of the dynamics' 84th percentile and ASCE 7-16 Fp)")
    return {"choice": choice, "reasons": reasons, "level": name}


def run_assessment(spec: Assessment) -> AssessmentResult:
    """Run every part of the assessment (see the module's docstring).

    Parameters
    ----------
    spec : Assessment

    Returns
    -------
    AssessmentResult
    """
    if not isinstance(spec, Assessment):
        raise ValueError(f"spec must be an Assessment, got {type(spec).__name__}")
    motions = demand_motions(spec)
    runs = _mode_runs(spec, motions)
    free = _free_statistics(spec, runs)
    fragility, risk = _fragility_and_risk(spec, runs)
    anchored = _anchored(spec, motions)
    spectra = _floor_spectra(motions, spec.demand.levels)
    checks = _codes(spec, anchored, spectra)
    recommendation = _recommend(spec, free, anchored, risk)
    return AssessmentResult(spec, runs, free, anchored, checks, fragility, risk, spectra,
                            recommendation)
