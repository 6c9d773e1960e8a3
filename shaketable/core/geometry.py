"""Block geometry (Sections 2.2 and 2.6 of the report) and prestress rods (Eq. 2-14).

Nomenclature (report symbol -> code name):

=========  ================================  =======================================
report     code                              meaning
=========  ================================  =======================================
H, B       ``height``, ``width``             total height and width of the block [m]
h, b       ``h``, ``b``                      half height H/2 and half width B/2 [m]
R          ``R``                             corner-to-centroid distance [m]
alpha      ``alpha``                         block angle arctan(b/h) [rad]
p          ``p``                             frequency parameter sqrt(3g/4R) [rad/s]
I0         ``I0_per_mass``                   moment of inertia about a corner / M [m^2]
K          ``PrestressRods.stiffness``       total rod stiffness [W per m]
F0         ``PrestressRods.force``           total initial rod force [W]
S          ``PrestressRods.edge_distance``   rod distance from an edge [m]
=========  ================================  =======================================
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from shaketable.core.constants import G, length_factor
from shaketable.core.validation import nonnegative, positive


@dataclass(frozen=True)
class PrestressRods:
    """A symmetric pair of vertical prestress rods tying the block to the floor.

    The report (Section 2.8, Eq. 2-14) places one rod at distance ``S`` from
    each edge; each rod is hinged at the ground, stays elastic and is always in
    tension. Here ``stiffness`` and ``force`` are the **totals** of the pair
    (Fig. 4.17: "total stiffness 0.4 W/in, total prestressing force 0.4 W"),
    each rod carrying half. A single rod in the middle (Fig. 4.17) is
    ``edge_distance = width / 2``.

    Parameters
    ----------
    stiffness : float
        Total axial stiffness K of the rods, in block weights per metre [W/m]
        (use :meth:`from_inches` for the report's W/in).
    force : float
        Total initial prestress force F0, in block weights [W].
    edge_distance : float
        Distance S of each rod from its nearer edge of the block [m].
    """

    stiffness: float
    force: float
    edge_distance: float

    def __post_init__(self):
        object.__setattr__(self, "stiffness", nonnegative("PrestressRods.stiffness", self.stiffness))
        object.__setattr__(self, "force", nonnegative("PrestressRods.force", self.force))
        object.__setattr__(self, "edge_distance",
                           nonnegative("PrestressRods.edge_distance", self.edge_distance))

    @classmethod
    def from_inches(cls, stiffness_w_per_in: float, force_w: float,
                    edge_distance_in: float) -> "PrestressRods":
        """Rods given in the report's units: K in W/in, F0 in W, S in inches."""
        return cls(nonnegative("stiffness", stiffness_w_per_in) / length_factor("in"),
                   force_w, nonnegative("edge_distance", edge_distance_in) * length_factor("in"))


#: Accepted block dimensions [m]: from a 1 mm model to a 1 km monolith (the physics
#: has no scale, but outside this range a size is a unit mistake, and extreme values
#: overflow or underflow the block's constants p and R).
MIN_DIMENSION, MAX_DIMENSION = 1e-3, 1e3

#: Accepted aspect ratios H/B: alpha from about 0.06 degrees to 89.4 degrees.
MIN_ASPECT_RATIO, MAX_ASPECT_RATIO = 1e-2, 1e3

_SIZE = re.compile(
    r"^\s*(?P<height>[0-9]*\.?[0-9]+)\s*(?P<hunit>[a-z]+)?\s*[x×]\s*"
    r"(?P<width>[0-9]*\.?[0-9]+)\s*(?P<wunit>[a-z]+)?\s*$",
    re.IGNORECASE,
)


@dataclass(frozen=True)
class Block:
    """A rigid rectangular block rocking on its bottom edges.

    Parameters
    ----------
    height : float
        Total height H [m].
    width : float
        Total width B [m] (in the plane of rocking).
    rods : PrestressRods, optional
        Prestress rods tying the block down (Eq. 2-14); ``None`` for a
        free-standing block.
    label : str
        How the user wrote the size, height first, in the user's units
        (``"30 x 6 in"`` for ``"30x6in"``, ``"4 x 0.8 ft"`` for ``"4x0.8ft"``), set
        by :meth:`parse` and echoed by :meth:`describe` and the figures; ``""``
        otherwise. Not part of equality: ``Block.parse("30x6in") ==
        Block.from_inches(30, 6)``.

    Notes
    -----
    Density and the third dimension do not enter the response (Eq. 2-13 is
    independent of the mass), so a block is its two dimensions.
    """

    height: float
    width: float
    rods: PrestressRods | None = None
    label: str = field(default="", compare=False, repr=False)

    def __post_init__(self):
        for name in ("height", "width"):
            value = positive(f"Block.{name}", getattr(self, name), " [m]")
            if not MIN_DIMENSION <= value <= MAX_DIMENSION:
                raise ValueError(f"Block.{name} must be from {MIN_DIMENSION:g} m to "
                                 f"{MAX_DIMENSION:g} m, got {value!r} m")
            object.__setattr__(self, name, value)
        ratio = self.height / self.width
        if not MIN_ASPECT_RATIO <= ratio <= MAX_ASPECT_RATIO:
            raise ValueError(f"Block aspect ratio H/B must be from {MIN_ASPECT_RATIO:g} to "
                             f"{MAX_ASPECT_RATIO:g}, got {ratio:.3g} (height {self.height!r} m, "
                             f"width {self.width!r} m)")
        if self.rods is not None:
            if not isinstance(self.rods, PrestressRods):
                raise ValueError(f"Block.rods must be PrestressRods or None, got {self.rods!r}")
            if self.rods.edge_distance > self.width:
                raise ValueError(
                    f"PrestressRods.edge_distance ({self.rods.edge_distance} m) must not exceed "
                    f"the block width ({self.width} m)"
                )

    # ----------------------------------------------------------- constructors
    @classmethod
    def parse(cls, text: str, rods: PrestressRods | None = None) -> "Block":
        """Build a block from ``"HEIGHTxWIDTH unit"`` text, height first.

        Examples: ``"30x6in"``, ``"16x4ft"``, ``"36in x 9in"``, ``"0.5x0.1m"``.
        The report writes blocks as height x width ("30 in. x 6 in.").
        A unit is required.
        """
        if str(text).lstrip().startswith("-"):
            raise ValueError(f"block size {text!r}: the height and the width must be positive")
        match = _SIZE.match(str(text))
        if not match:
            raise ValueError(
                f"block size {text!r} not understood; expected 'HEIGHTxWIDTH<unit>' "
                "such as '30x6in' or '16x4ft'"
            )
        unit = match["wunit"] or match["hunit"]
        if unit is None:
            raise ValueError(f"block size {text!r} has no unit; write e.g. '30x6in' or '16x4ft'")
        height_unit = match["hunit"] or unit
        unit, height_unit = unit.lower(), height_unit.lower()
        label = (f"{match['height']} x {match['width']} {unit}" if height_unit == unit
                 else f"{match['height']} {height_unit} x {match['width']} {unit}")
        height, width = float(match["height"]), float(match["width"])
        for name, value in (("height", height), ("width", width)):
            if not value > 0:   # a zero size: say which text gave it
                raise ValueError(f"block size {text!r}: the {name} must be positive")
        return cls(height * length_factor(height_unit), width * length_factor(unit), rods,
                   label=label)

    @classmethod
    def from_inches(cls, height: float, width: float, rods=None) -> "Block":
        """Block with height and width in inches."""
        return cls(positive("height", height) * length_factor("in"),
                   positive("width", width) * length_factor("in"), rods)

    @classmethod
    def from_feet(cls, height: float, width: float, rods=None) -> "Block":
        """Block with height and width in feet."""
        return cls(positive("height", height) * length_factor("ft"),
                   positive("width", width) * length_factor("ft"), rods)

    @classmethod
    def from_slenderness(cls, R: float, alpha: float, rods=None) -> "Block":
        """Block from its size R [m] and block angle alpha [rad] (0 < alpha < pi/2)."""
        R = positive("R", R)
        alpha = positive("alpha", alpha)
        if alpha >= math.pi / 2:
            raise ValueError(f"alpha must be below pi/2, got {alpha!r}")
        return cls(2 * R * math.cos(alpha), 2 * R * math.sin(alpha), rods)

    # -------------------------------------------------------------- derived
    @property
    def h(self) -> float:
        """Half height h = H/2, height of the centroid [m]."""
        return self.height / 2

    @property
    def b(self) -> float:
        """Half width b = B/2, horizontal distance from an edge to the centroid [m]."""
        return self.width / 2

    @property
    def R(self) -> float:
        """Distance from a bottom corner to the centroid, sqrt(b^2 + h^2) [m]."""
        return math.hypot(self.b, self.h)

    @property
    def alpha(self) -> float:
        """Block angle alpha = arctan(b/h) [rad] (Fig. 2.2): the static stability limit."""
        return math.atan2(self.b, self.h)

    @property
    def aspect_ratio(self) -> float:
        """Height over width H/B [-]."""
        return self.height / self.width

    @property
    def p(self) -> float:
        """Frequency parameter p = sqrt(3 g / 4 R) [rad/s] (Section 2.2)."""
        return math.sqrt(3 * G / (4 * self.R))

    @property
    def I0_per_mass(self) -> float:
        """Moment of inertia about a bottom corner per unit mass, 4R^2/3 [m^2] (Eq. 2-12)."""
        return 4 * self.R ** 2 / 3

    def rocking_threshold(self, vertical: float = 0.0) -> float:
        """Horizontal acceleration that starts rocking, Eq. (2-1) [m/s^2].

        ``(B/H) (g + v)`` plus the prestress of the rods, where ``v`` is the
        vertical ground acceleration [m/s^2] (positive upward).
        """
        restoring = (G + vertical) * self.b
        if self.rods is not None:
            restoring += G * self.rods.force * self.b  # the pair's resultant acts at mid-width
        return restoring / self.h

    @property
    def length_unit(self) -> str:
        """The length unit of the block's label (:meth:`describe`): the user's unit when
        the block was parsed from text (``"m"`` for ``"2x0.5m"``), else ft or in."""
        unit = self.describe().rsplit(" ", 1)[-1]
        return unit if unit in ("m", "cm", "mm", "in", "ft") else "in"

    def describe(self, unit: str | None = None) -> str:
        """Short label, height first: ``30 x 6 in``, ``16 x 4 ft``.

        Parameters
        ----------
        unit : {None, "in"}
            ``None``: the user's text when the block was parsed from it (:attr:`label`,
            ``4 x 0.8 ft`` for ``"4x0.8ft"``), else feet when both dimensions are
            whole feet (as the report writes its Section 4 blocks), else inches.
            ``"in"``: always inches (the labels of sweep tables, kept stable so that
            a resumed sweep matches its parts).
        """
        if unit is None and self.label:
            return self.label
        inch, foot = length_factor("in"), length_factor("ft")
        in_feet = [value / foot for value in (self.height, self.width)]
        if unit is None and all(abs(value - round(value)) < 1e-9 and round(value) >= 1 for value in in_feet):
            return f"{round(in_feet[0])} x {round(in_feet[1])} ft"
        return f"{self.height / inch:g} x {self.width / inch:g} in"


def size_words(block) -> str:
    """A block's size in a message, height first, in the units it was given in as far as
    they are known: the user's text for a block parsed from it (:attr:`Block.label`),
    :meth:`Block.describe` (the report's feet or inches) when both dimensions are whole
    inches, else metres (``"1 x 0.4 m"`` for ``Block(1.0, 0.4)``, whose inches
    ``39.3701 x 15.748 in`` no one typed)."""
    inch = length_factor("in")
    if getattr(block, "label", "") or all(
            abs(value / inch - round(value / inch)) < 1e-9 for value in (block.height,
                                                                          block.width)):
        return block.describe()
    return f"{block.height:g} x {block.width:g} m"


@dataclass(frozen=True)
class AsymmetricBlock:
    """A rigid block whose centre of mass is not over the middle of its base.

    The planar idealisation of a rock, a cabinet or a machine: the centroid at height
    ``h`` over the base and at horizontal distances ``b_plus`` and ``b_minus`` from the
    two pivots. With one signed theta (``docs/conventions.md``), theta > 0 pivots on the
    corner at -x (the block tips toward -x, driven by a positive table acceleration):
    that corner is ``b_plus`` from the centroid; theta < 0 pivots on the corner at +x,
    ``b_minus`` away. Each side has its own block angle, size and inertia about its pivot,

        alpha_s = arctan(b_s / h),  R_s = sqrt(b_s^2 + h^2),  I0_s = k^2 + R_s^2,
        p_s = sqrt(g R_s / I0_s),

    and Eq. (2-13) on side s is the symmetric block's with b, R and I0 of that side.
    A symmetric :class:`Block` is the special case b_plus = b_minus = B/2,
    k^2 = R^2/3 (I0 = 4R^2/3); the solvers keep running :class:`Block` exactly as
    before, this class is a separate input.

    Parameters
    ----------
    h : float
        Height of the centroid over the base [m].
    b_plus : float
        Horizontal distance from the centroid to the pivot of theta > 0 (the -x corner) [m].
    b_minus : float
        Horizontal distance from the centroid to the pivot of theta < 0 (the +x corner) [m].
    gyration : float, optional
        Radius of gyration k about the centroid, for rocking in this plane [m]
        (I_cm = M k^2). ``None``: the rectangle of height 2h and width
        b_plus + b_minus, k^2 = (h^2 + ((b_plus + b_minus)/2)^2) / 3.
    label : str
        A name echoed by :meth:`describe`; not part of equality.
    """

    h: float
    b_plus: float
    b_minus: float
    gyration: float | None = None
    label: str = field(default="", compare=False, repr=False)

    def __post_init__(self):
        for name in ("h", "b_plus", "b_minus"):
            value = positive(f"AsymmetricBlock.{name}", getattr(self, name), " [m]")
            if not MIN_DIMENSION / 2 <= value <= MAX_DIMENSION:
                raise ValueError(f"AsymmetricBlock.{name} must be from {MIN_DIMENSION / 2:g} m "
                                 f"to {MAX_DIMENSION:g} m, got {value!r} m")
            object.__setattr__(self, name, value)
        for name in ("b_plus", "b_minus"):
            ratio = self.h / getattr(self, name)
            if not MIN_ASPECT_RATIO / 2 <= ratio <= 2 * MAX_ASPECT_RATIO:
                raise ValueError(f"AsymmetricBlock h/{name} must be from {MIN_ASPECT_RATIO / 2:g} "
                                 f"to {2 * MAX_ASPECT_RATIO:g}, got {ratio:.3g}")
        if self.gyration is not None:
            object.__setattr__(self, "gyration", positive("AsymmetricBlock.gyration",
                                                          self.gyration, " [m]"))

    @classmethod
    def from_angles(cls, alpha_plus: float, alpha_minus: float, h: float,
                    gyration: float | None = None, label: str = "") -> "AsymmetricBlock":
        """Block from its two block angles [rad] (0 < alpha < pi/2) and centroid height h [m]."""
        for name, value in (("alpha_plus", alpha_plus), ("alpha_minus", alpha_minus)):
            value = positive(name, value, " [rad]")
            if value >= math.pi / 2:
                raise ValueError(f"{name} must be below pi/2, got {value!r}")
        h = positive("h", h, " [m]")
        return cls(h, h * math.tan(alpha_plus), h * math.tan(alpha_minus), gyration, label)

    # -------------------------------------------------------------- derived
    @property
    def symmetric(self) -> bool:
        """True when both pivots are equally far from the centroid."""
        return self.b_plus == self.b_minus

    @property
    def k_squared(self) -> float:
        """Squared radius of gyration about the centroid, I_cm / M [m^2]."""
        if self.gyration is not None:
            return self.gyration ** 2
        half_width = 0.5 * (self.b_plus + self.b_minus)
        return (self.h ** 2 + half_width ** 2) / 3.0

    def b_of(self, side: float) -> float:
        """Centroid-to-pivot horizontal distance of ``side`` (+1: theta > 0, -1) [m]."""
        return self.b_plus if side > 0 else self.b_minus

    def alpha_of(self, side: float) -> float:
        """Block angle arctan(b_s / h) of ``side`` [rad]: its static stability limit."""
        return math.atan2(self.b_of(side), self.h)

    def R_of(self, side: float) -> float:
        """Pivot-to-centroid distance R_s of ``side`` [m]."""
        return math.hypot(self.b_of(side), self.h)

    def I0_of(self, side: float) -> float:
        """Moment of inertia about the pivot of ``side`` per unit mass, k^2 + R_s^2 [m^2]."""
        return self.k_squared + self.R_of(side) ** 2

    def p_of(self, side: float) -> float:
        """Frequency parameter p_s = sqrt(g R_s / I0_s) of ``side`` [rad/s]."""
        return math.sqrt(G * self.R_of(side) / self.I0_of(side))

    @property
    def alpha_plus(self) -> float:
        """Block angle of theta > 0 rocking [rad]."""
        return self.alpha_of(1.0)

    @property
    def alpha_minus(self) -> float:
        """Block angle of theta < 0 rocking [rad]."""
        return self.alpha_of(-1.0)

    @property
    def alpha(self) -> float:
        """The smaller block angle [rad]: the static stability limit of the weaker side."""
        return min(self.alpha_plus, self.alpha_minus)

    @property
    def p(self) -> float:
        """The larger frequency parameter of the two sides [rad/s]."""
        return max(self.p_of(1.0), self.p_of(-1.0))

    def housner_cor(self, onto: float) -> float:
        """Housner's coefficient of restitution of an impact onto the pivot ``onto`` [-].

        Angular momentum about the new pivot is conserved through the impact (Housner's
        assumption, Section 2.7 (5)): with the old pivot b1 and the new b2 from the
        centroid, k^2 + h^2 - b1 b2 = (k^2 + b2^2 + h^2) c, so

            c = 1 - b2 (b1 + b2) / I0_2,

        the theta' after over before (one signed theta). For a symmetric rectangle it is
        1 - 1.5 sin^2(alpha).
        """
        b2 = self.b_of(onto)
        b1 = self.b_of(-onto)
        return 1.0 - b2 * (b1 + b2) / self.I0_of(onto)

    def rocking_threshold(self, side: float) -> float:
        """Table acceleration that starts rocking toward ``side``, g tan(alpha_s) [m/s^2]."""
        return G * self.b_of(side) / self.h

    def describe(self, unit: str | None = None) -> str:
        """Short label: the user's ``label``, else the two angles and h."""
        if self.label:
            return self.label
        return (f"asymmetric alpha+ {self.alpha_plus:.4g} / alpha- {self.alpha_minus:.4g} rad, "
                f"h {self.h:.4g} m")
