"""The analytic indenter shapes: one class each, registered by the name ``indenter.shape`` gives it.

A shape is a rigid surface described by a few lengths (and an angle). Each class gives

* its undeformed gap h0 [m] on a grid (:meth:`Shape.gap`, built from ``grid.mesh()``: the cell
  centres x_i = -half_width + (i + 1/2) dx, and y likewise; the shape's lowest point at the origin,
  where an even grid has a node, not a cell centre),
  so that a grid whose mesh is a single row at y = 0 (a line contact) gets the profile through the
  axis: a cylinder's x^2/(2R), a flat punch's strip of half-width ``radius``;
* its elastic contact on a half-space of contact modulus E* [Pa] (the closed forms of
  :mod:`viscontact.physics.reference`): the contact size at a load (:meth:`Shape.size_at_load`), the
  load at a size (:meth:`Shape.load_at_size`), the size at an approach (:meth:`Shape.size_at_approach`),
  the extents it covers (:meth:`Shape.extents`); each body turns these into its own estimate
  (:meth:`viscontact.bodies.base.Body.contact_radius`, its compliance in place of 1/E*), and the
  guards (:mod:`viscontact.running.guards`) compare them with the grid;
* what a grid of a given cell resolves of it (:meth:`Shape.resolution_error`, and
  :attr:`Shape.singular`: a sharp punch's rim and a cone's tip carry singular pressures that no grid
  resolves; the load, the approach and the pressure a few cells away from them converge);
* the scale of its results (:meth:`Shape.scale`: the results' ``a0``, ``p0``) and its attributes;
* its case keys (:attr:`Shape.required`, :attr:`Shape.optional`; their units and ranges are declared in
  :class:`viscontact.io.case.IndenterSection`).

A new shape is one class here with its ``@register`` (and its keys in the case schema).

Walls. A flat punch outside its face, and a roller beyond its ends, rise by :attr:`FlatPunch.wall`
(:data:`WALL_RADII` times the punch's radius, a roller's radius): a height no small-strain approach
reaches, so that the walls never touch. Walls out of contact do not enter the solution (a punch's
load to 4e-14 for walls of 20 um and 1 mm, tests/validation/test_flat_punch.py). They are why an
analytic shape's gap is not held to the rms-slope bound of a surface read from a file
(:data:`viscontact.problem.topography.MAX_RMS_SLOPE`, which counts a wall at its full height): its
heights are in metres by construction.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import numpy as np

from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid
from viscontact.physics import reference

__all__ = ["SHAPES", "Cone", "Cylinder", "Ellipsoid", "FlatPunch", "Shape", "Sphere", "peak_pressure_error",
           "register", "shape_from_keys"]

#: a flat punch's wall, a roller's end walls: this many times its radius high (never reached by an
#: approach of the small-strain theory: delta / a = pi p_mean / (2 E*) of a punch)
WALL_RADII = 1.0
#: measured load error of a flat circular punch per cell of dx/a: W / (2 a E* delta) - 1 = -0.12 dx/a
#: (tests/validation/test_flat_punch.py: -1.54 %, -0.75 %, -0.36 % at a/dx = 8, 16, 32), the rim's
#: singular pressure averaged over its cells
FLAT_FACE_LOAD_ERROR_PER_CELL = 0.12
#: measured load error of a cone per cell of dx/a at a given approach, |W / W_Sneddon - 1| <= 0.027 dx/a
#: (tests/validation/test_shapes.py: 1.1 %, 0.8 %, 0.46 %, 0.11 %, 0.045 % at a/dx = 2, 3, 4, 8, 10), the
#: tip's singular pressure averaged over its cells
CONE_LOAD_ERROR_PER_CELL = 0.03
#: cells across a punch's face or a cone's contact radius below which a run is refused, whatever its
#: small load error: a contact of a cell or two is no face or cone the grid describes (the contact
#: area, a count of cells, errs by up to 30 % at a/dx = 1.5 for a cone)
SINGULAR_MIN_CELLS = 2.0
#: a cone's flank slope cot(alpha) above which it is warned about (beyond the small-slope theory of the
#: half-space) and refused (a half-angle in the wrong unit): those of a surface's rms slope
#: (:data:`viscontact.problem.topography.WARN_RMS_SLOPE`, :data:`~viscontact.problem.topography.MAX_RMS_SLOPE`)
CONE_WARN_SLOPE, CONE_MAX_SLOPE = 1.0, 10.0


def peak_pressure_error(cells_per_radius: float) -> float:
    """Estimated relative error [-] of the Hertz peak pressure with ``a / dx`` cells across the
    contact radius: 1 - sqrt(1 - 1/(2 (a/dx)^2)), the Hertz pressure dx/sqrt(2) from the centre (the
    node nearest the centre of the contact on the cell-centred grid)."""
    return 1.0 - math.sqrt(max(1.0 - 0.5 / max(cells_per_radius, 1e-12) ** 2, 0.0))


@dataclass(frozen=True)
class Shape:
    """What every analytic shape provides (a base class; each shape a frozen dataclass whose fields
    are its case keys, lengths in m, angles in degrees).

    Class attributes: ``name`` (the ``indenter.shape`` value), ``required`` and ``optional`` (its
    case keys besides ``shape``), ``model`` (the closed form of its estimates, in messages),
    ``grows`` (whether the contact grows with the load: not a flat punch's face), ``resolved`` (what
    :meth:`resolution_error` estimates the error of), ``singular`` (what no grid resolves, or ''),
    ``min_cells`` (cells across the narrowest half-width below which a run is refused whatever the
    error estimate; 0: none but the estimate's).
    """

    name: ClassVar[str]
    required: ClassVar[tuple[str, ...]] = ()
    optional: ClassVar[tuple[str, ...]] = ()
    model: ClassVar[str] = ""
    grows: ClassVar[bool] = True
    resolved: ClassVar[str] = "the peak pressure"
    singular: ClassVar[str] = ""
    min_cells: ClassVar[float] = 0.0

    # --- geometry ---------------------------------------------------------------------------
    def gap(self, grid: Grid) -> np.ndarray:
        """The undeformed gap h0 [m] on ``grid`` (indexed [y, x], ``grid.mesh()``), the shape's lowest
        point (0) at the origin."""
        raise NotImplementedError

    def heights(self, grid: Grid) -> np.ndarray:
        """Heights of the rigid surface, z up [m]: minus :meth:`gap` (to which roughness is added)."""
        return -self.gap(grid)

    @property
    def sphere_radius(self) -> float | None:
        """The radius [m] of a sphere (:class:`Sphere`), else None (``Problem.radius``)."""
        return None

    def __post_init__(self) -> None:
        """Refuse (:class:`~viscontact.errors.ParameterError`, naming the case key) a length or angle
        that is not a finite number > 0 (``edge_radius``: >= 0), and values no shape of its kind has
        (:meth:`check`)."""
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None and f.default is None:
                continue
            least = 0.0 if f.name == "edge_radius" else None
            number = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)
            if not (number and math.isfinite(value) and (value >= least if least is not None else value > 0)):
                bound = ">= 0" if least is not None else "> 0"
                raise ParameterError(f"indenter.{f.name}", f"must be a finite number {bound}, got {value!r}")
        self.check()

    def check(self) -> None:
        """Refuse values no shape of its kind has (nothing by default)."""

    def caveats(self, grid: Grid) -> list[str]:
        """What the half-space's theory or ``grid`` cannot take of the shape and a run should be warned
        about (each a message; none by default); :func:`viscontact.running.guards.check_problem` warns
        them and refuses what :meth:`check_grid` refuses."""
        return []

    def line_profile(self) -> bool:
        """Whether the shape is a line contact's indenter (``grid.dimension = 1``, plane strain): uniform
        along y without end, its estimates per unit length and its scales :meth:`line_scale`. False by
        default; :class:`Cylinder` without a length, :class:`FlatPunch` (a strip)."""
        return False

    def line_scale(self, reference_value: float, control: str, shear_modulus: float, poisson_ratio: float,
                   datum: float) -> tuple[float, float]:
        """:meth:`scale` in line contact (loads per unit length [N/m], approaches relative to the datum
        b [m] of :mod:`viscontact.physics.kernels`), for a shape whose :meth:`line_profile` is True."""
        raise NotImplementedError(f"{self.name} is not a line contact's indenter")

    def check_grid(self, grid: Grid) -> None:
        """Refuse (:class:`~viscontact.errors.ParameterError`) a grid the shape cannot be posed on
        (nothing by default)."""

    # --- the elastic contact on a half-space of contact modulus E* [Pa] ---------------------
    def load_at_size(self, size: float, contact_modulus: float) -> float:
        """The load W [N] whose contact has the size ``size`` [m] (:meth:`size_at_load`'s inverse)."""
        raise NotImplementedError

    def size_at_load(self, load: float, contact_modulus: float) -> float:
        """The contact size [m] (its radius; a roller's half-width) under ``load`` W [N]."""
        raise NotImplementedError

    def size_at_approach(self, approach: float) -> float:
        """The contact size [m] at the approach ``approach`` [m] (on a half-space: whatever E*)."""
        raise NotImplementedError

    def extents(self, size: float) -> tuple[float, float]:
        """(the narrowest half-width to resolve, the farthest reach from the centre) [m] of the contact
        of size ``size``: a circle's (a, a), an ellipse's semi-axes, a roller's (b, length / 2)."""
        return size, size

    def strain_ratio(self, size: float) -> tuple[float, float]:
        """(contact size over the radius of curvature across it [-], that radius [m]) where strains
        grow as a/R (Hertz: about 2a/(pi R)); (NaN, NaN) for a shape without one (a punch, a cone)."""
        return float("nan"), float("nan")

    def resolution_error(self, cells: float) -> float:
        """Estimated relative error [-] of :attr:`resolved` with ``cells`` = (narrowest half-width) / dx."""
        return peak_pressure_error(cells)

    def scale(self, reference_value: float, control: str, shear_modulus: float,
              poisson_ratio: float) -> tuple[float, float]:
        """(a0 [m], p0 [Pa]) of the results: the contact size and a pressure of the shape at the
        reference load [N] (``control = "load"``) or approach [m] with G(0) [Pa] and nu."""
        raise NotImplementedError

    def result_attributes(self) -> dict[str, Any]:
        """Attributes of a result: ``indenter_shape`` and the shape's keys ``indenter_<key>``."""
        return {"indenter_shape": self.name, **{f"indenter_{f.name}": float(getattr(self, f.name))
                                                for f in fields(self) if getattr(self, f.name) is not None}}


#: the analytic shapes by their ``indenter.shape`` name
SHAPES: dict[str, type[Shape]] = {}


def register(cls: type[Shape]) -> type[Shape]:
    """Class decorator: add a shape to :data:`SHAPES` under its ``name``."""
    SHAPES[cls.name] = cls
    return cls


def shape_from_keys(name: str, keys: dict[str, Any]) -> Shape:
    """The shape ``name`` built from its case keys (``keys``: key -> value, None for a key not given),
    checked (:meth:`Shape.check`)."""
    cls = SHAPES[name]
    return cls(**{k: keys[k] for k in (*cls.required, *cls.optional) if keys.get(k) is not None})


#: cells a rounded rim or end (``edge_radius``) must span to act as rounded on the grid
ROUNDING_CELLS = 2.0


def _rounding_caveats(edge_radius: float, grid: Grid, what: str) -> list[str]:
    """A caveat where a rounding of ``edge_radius`` [m] > 0 spans fewer than :data:`ROUNDING_CELLS`
    cells of ``grid``: on it the edge acts as a sharp one (singular pressure, a cell average)."""
    if not 0.0 < edge_radius < ROUNDING_CELLS * grid.spacing:
        return []
    return [f"indenter.edge_radius = {edge_radius:.3g} m spans {edge_radius / grid.spacing:.2g} cells of "
            f"{grid.spacing:.3g} m: on this grid the {what} acts as a sharp one (its singular pressure a cell "
            f"average); a grid.n that puts {ROUNDING_CELLS:g} cells or more across it resolves the rounding"]


def _e_star(shear_modulus: float, poisson_ratio: float) -> float:
    return reference.contact_modulus(shear_modulus, poisson_ratio)


def _radial(grid: Grid) -> np.ndarray:
    x, y = grid.mesh()
    return np.hypot(x, y)


@register
@dataclass(frozen=True)
class Sphere(Shape):
    """A sphere of ``radius`` R [m]: the paraboloid gap (x^2 + y^2)/(2R); Hertz (Johnson, *Contact
    Mechanics*, Sec. 4.2): a^3 = 3 W R/(4 E*), a = sqrt(R delta)."""

    radius: float

    name: ClassVar[str] = "sphere"
    required: ClassVar[tuple[str, ...]] = ("radius",)
    model: ClassVar[str] = "Hertz"

    def gap(self, grid: Grid) -> np.ndarray:
        x, y = grid.mesh()
        return (x**2 + y**2) / (2.0 * self.radius)

    @property
    def sphere_radius(self) -> float:
        return self.radius

    def load_at_size(self, size: float, contact_modulus: float) -> float:
        return 4.0 * contact_modulus * size**3 / (3.0 * self.radius)

    def size_at_load(self, load: float, contact_modulus: float) -> float:
        return (3.0 * load * self.radius / (4.0 * contact_modulus)) ** (1.0 / 3.0)

    def size_at_approach(self, approach: float) -> float:
        return math.sqrt(self.radius * approach)

    def strain_ratio(self, size: float) -> tuple[float, float]:
        return size / self.radius, self.radius

    def scale(self, reference_value: float, control: str, shear_modulus: float,
              poisson_ratio: float) -> tuple[float, float]:
        build = reference.hertz_from_load if control == "load" else reference.hertz_from_approach
        h = build(reference_value, self.radius, shear_modulus, poisson_ratio)
        return float(h.radius), float(h.peak_pressure)

    def result_attributes(self) -> dict[str, Any]:
        """None: a sphere's result has carried its ``radius`` attribute from the start."""
        return {}


@register
@dataclass(frozen=True)
class Ellipsoid(Shape):
    """An ellipsoid of principal radii ``radius_x``, ``radius_y`` [m]: gap x^2/(2 R_x) + y^2/(2 R_y);
    Hertz's elliptical contact (:func:`viscontact.physics.reference.elliptical_hertz`). Its size is
    the equivalent radius sqrt(a_x a_y) [m] of the elliptical contact, whose eccentricity depends on
    R_x/R_y only (the semi-axes grow as W^(1/3), the approach as W^(2/3))."""

    radius_x: float
    radius_y: float

    name: ClassVar[str] = "ellipsoid"
    required: ClassVar[tuple[str, ...]] = ("radius_x", "radius_y")
    model: ClassVar[str] = "Hertz, elliptical"

    def gap(self, grid: Grid) -> np.ndarray:
        x, y = grid.mesh()
        return x**2 / (2.0 * self.radius_x) + y**2 / (2.0 * self.radius_y)

    def _unit(self) -> reference.EllipticalHertz:
        """The contact under 1 N on E* = 1 Pa (scaled to any load and modulus)."""
        return reference.elliptical_hertz(1.0, self.radius_x, self.radius_y, 1.0)

    def load_at_size(self, size: float, contact_modulus: float) -> float:
        unit = self._unit()
        return contact_modulus * (size / math.sqrt(unit.semi_axis_x * unit.semi_axis_y)) ** 3

    def size_at_load(self, load: float, contact_modulus: float) -> float:
        unit = self._unit()
        return math.sqrt(unit.semi_axis_x * unit.semi_axis_y) * (load / contact_modulus) ** (1.0 / 3.0)

    def size_at_approach(self, approach: float) -> float:
        unit = self._unit()  # delta = unit.approach (W / E*)^(2/3), size = c1 (W / E*)^(1/3)
        return math.sqrt(unit.semi_axis_x * unit.semi_axis_y) * math.sqrt(approach / unit.approach)

    def extents(self, size: float) -> tuple[float, float]:
        unit = self._unit()
        c1 = math.sqrt(unit.semi_axis_x * unit.semi_axis_y)
        return (size * min(unit.semi_axis_x, unit.semi_axis_y) / c1,
                size * max(unit.semi_axis_x, unit.semi_axis_y) / c1)

    def strain_ratio(self, size: float) -> tuple[float, float]:
        unit = self._unit()
        c1 = math.sqrt(unit.semi_axis_x * unit.semi_axis_y)
        ratios = (size * unit.semi_axis_x / c1 / self.radius_x, size * unit.semi_axis_y / c1 / self.radius_y)
        return (ratios[0], self.radius_x) if ratios[0] >= ratios[1] else (ratios[1], self.radius_y)

    def scale(self, reference_value: float, control: str, shear_modulus: float,
              poisson_ratio: float) -> tuple[float, float]:
        """a0 = sqrt(a_x a_y), p0 the peak pressure (Hertz, elliptical)."""
        e_star = _e_star(shear_modulus, poisson_ratio)
        load = reference_value if control == "load" else self.load_at_size(self.size_at_approach(reference_value),
                                                                             e_star)
        h = reference.elliptical_hertz(load, self.radius_x, self.radius_y, e_star)
        return math.sqrt(h.semi_axis_x * h.semi_axis_y), h.peak_pressure


@register
@dataclass(frozen=True)
class Cylinder(Shape):
    """A roller of ``radius`` R [m], its axis along y: gap x^2/(2R), over ``length`` L [m] with
    rounded ends of ``edge_radius`` rho [m] (the last rho of each end falls off as
    (|y| - (L/2 - rho))^2/(2 rho), the parabolic form of a rounding; 0: sharp ends, whose edge
    pressure is singular) and end walls beyond |y| = L/2 (:data:`WALL_RADII` R high). Without a
    length (None), the infinite cylinder of a line contact, loads per unit length.

    Its size is the half-width b [m] of the strip, estimated as Hertz's line contact under the load
    per unit length W / L (:func:`viscontact.physics.reference.hertz_line_half_width`;
    Johnson, Sec. 4.3): a finite roller has no closed form, its ends carry more (sharp) or less
    (rounded) than the middle; at an approach, b = sqrt(R delta) (the line contact's approach is not
    set by its width alone: it depends on the body's depth, logarithmically)."""

    radius: float
    length: float | None = None
    edge_radius: float = 0.0

    name: ClassVar[str] = "cylinder"
    required: ClassVar[tuple[str, ...]] = ("radius",)
    optional: ClassVar[tuple[str, ...]] = ("length", "edge_radius")
    model: ClassVar[str] = "Hertz, line contact"

    def check(self) -> None:
        if self.length is not None and not 2.0 * self.edge_radius <= self.length:
            raise ParameterError("indenter.edge_radius", f"must be <= length / 2 = {self.length / 2:g} m (the "
                                 f"rounded ends of a roller {self.length:g} m long), got {self.edge_radius:g}")

    def line_profile(self) -> bool:
        """The infinite cylinder (no length) is the line contact's indenter."""
        return self.length is None

    def line_scale(self, reference_value: float, control: str, shear_modulus: float, poisson_ratio: float,
                   datum: float) -> tuple[float, float]:
        """Hertz's line contact (:func:`~viscontact.physics.reference.hertz_line_from_load`,
        :func:`~viscontact.physics.reference.hertz_line_from_approach`): a0 = b, p0 = 2 W / (pi b)."""
        build = reference.hertz_line_from_load if control == "load" else reference.hertz_line_from_approach
        hertz = build(reference_value, self.radius, shear_modulus, poisson_ratio, datum)
        return float(hertz.radius), float(hertz.peak_pressure)

    def check_grid(self, grid: Grid) -> None:
        """Refuse an infinite cylinder (no length) on a 2-D grid: its contact would cross the domain."""
        if self.length is None and getattr(grid, "dimension", 2) == 2:
            raise ParameterError("indenter.length", "required for shape = 'cylinder' on a 2-D grid (a roller of "
                                 "finite length, m, with rounded ends of edge_radius): an infinite cylinder's "
                                 "contact crosses the domain")

    def caveats(self, grid: Grid) -> list[str]:
        """Rounded ends narrower than :data:`ROUNDING_CELLS` cells."""
        return _rounding_caveats(self.edge_radius, grid, "roller's rounded end")

    @property
    def wall(self) -> float:
        """Height [m] of the end walls beyond |y| = L/2."""
        return WALL_RADII * self.radius

    def gap(self, grid: Grid) -> np.ndarray:
        x, y = grid.mesh()
        gap = x**2 / (2.0 * self.radius)
        if self.length is None:
            return gap
        straight = self.length / 2.0 - self.edge_radius
        beyond = np.clip(np.abs(y) - straight, 0.0, None)
        ends = beyond**2 / (2.0 * self.edge_radius) if self.edge_radius > 0 else np.zeros_like(beyond)
        return gap + np.where(np.abs(y) <= self.length / 2.0, ends, self.wall)

    def _per_length(self, load: float) -> float:
        return load if self.length is None else load / self.length

    def load_at_size(self, size: float, contact_modulus: float) -> float:
        per_length = np.pi * contact_modulus * size**2 / (4.0 * self.radius)
        return per_length if self.length is None else per_length * self.length

    def size_at_load(self, load: float, contact_modulus: float) -> float:
        return reference.hertz_line_half_width(self._per_length(load), self.radius, contact_modulus)

    def size_at_approach(self, approach: float) -> float:
        return math.sqrt(self.radius * approach)

    def extents(self, size: float) -> tuple[float, float]:
        return size, size if self.length is None else max(size, self.length / 2.0)

    def strain_ratio(self, size: float) -> tuple[float, float]:
        return size / self.radius, self.radius

    def scale(self, reference_value: float, control: str, shear_modulus: float,
              poisson_ratio: float) -> tuple[float, float]:
        """a0 = b, p0 = 2 W' / (pi b), the line contact's at W' = W / L."""
        e_star = _e_star(shear_modulus, poisson_ratio)
        b = self.size_at_load(reference_value, e_star) if control == "load" else self.size_at_approach(reference_value)
        load = reference_value if control == "load" else self.load_at_size(b, e_star)
        return b, 2.0 * self._per_length(load) / (np.pi * b)


@dataclass(frozen=True)
class _SingularShape(Shape):
    """A shape whose pressure is singular somewhere (a sharp rim, a tip): the grid resolves its load at
    a given approach, whose error is ``load_error_per_cell`` dx/a (measured), and a contact of fewer
    than :data:`SINGULAR_MIN_CELLS` cells is refused."""

    load_error_per_cell: ClassVar[float]
    resolved: ClassVar[str] = "the load at a given approach"
    min_cells: ClassVar[float] = SINGULAR_MIN_CELLS

    def resolution_error(self, cells: float) -> float:
        """``load_error_per_cell`` dx/a, the measured load error at a given approach."""
        return self.load_error_per_cell / max(cells, 1e-12)


@register
@dataclass(frozen=True)
class FlatPunch(_SingularShape):
    """A flat circular punch of ``radius`` a [m] (in a line contact a strip of half-width a), its rim
    sharp (``edge_radius`` 0) or rounded (the face meets a rounding of ``edge_radius`` rho [m], the
    parabolic form (r - a)^2/(2 rho), as a sphere's gap is of a sphere), and a wall of
    :data:`WALL_RADII` a about it. Boussinesq/Sneddon (:class:`viscontact.physics.reference.FlatPunch`):
    its contact is its face at any load (a rounded rim's grows into the rounding by at most
    sqrt(2 rho delta)), W = 2 a E* delta.

    A cell is on the face where its centre is within a of the axis: the face drawn has the area of
    the cells counted, a disc of radius a_eff with a_eff/a - 1 a lattice count of order (dx/a)^2
    (+1.7 %, +0.5 %, +0.2 % at a/dx = 8, 16, 32)."""

    radius: float
    edge_radius: float = 0.0

    name: ClassVar[str] = "flat_punch"
    required: ClassVar[tuple[str, ...]] = ("radius",)
    optional: ClassVar[tuple[str, ...]] = ("edge_radius",)
    model: ClassVar[str] = "Boussinesq flat punch"
    grows: ClassVar[bool] = False
    load_error_per_cell: ClassVar[float] = FLAT_FACE_LOAD_ERROR_PER_CELL
    singular: ClassVar[str] = ("the pressure at a sharp rim is singular, as (a - r)^(-1/2): the grid resolves the "
                               "load, the approach and the pressure a few cells inside the rim, not the rim's "
                               "pressure (a cell average there)")

    def caveats(self, grid: Grid) -> list[str]:
        """A rounded rim narrower than :data:`ROUNDING_CELLS` cells."""
        return _rounding_caveats(self.edge_radius, grid, "punch's rounded rim")

    @property
    def wall(self) -> float:
        """Height [m] of the wall about the face (beyond the rounding)."""
        return WALL_RADII * self.radius

    def gap(self, grid: Grid) -> np.ndarray:
        r = _radial(grid)
        if self.edge_radius == 0:
            return np.where(r <= self.radius, 0.0, self.wall)
        beyond = np.clip(r - self.radius, 0.0, None)
        return np.minimum(beyond**2 / (2.0 * self.edge_radius), self.wall)

    def size_at_load(self, load: float, contact_modulus: float) -> float:
        return self.radius

    def load_at_size(self, size: float, contact_modulus: float) -> float:
        raise ValueError("a flat punch's contact is its face at any load: no load sets its size")

    def size_at_approach(self, approach: float) -> float:
        return self.radius

    def extents(self, size: float) -> tuple[float, float]:
        """(a, a + rho): a rounded rim's contact reaches into the rounding by sqrt(2 rho delta), less
        than rho while delta < rho/2."""
        return self.radius, self.radius + self.edge_radius

    def line_profile(self) -> bool:
        """In line contact the punch is a strip of half-width ``radius``."""
        return True

    def line_scale(self, reference_value: float, control: str, shear_modulus: float, poisson_ratio: float,
                   datum: float) -> tuple[float, float]:
        """The strip (:class:`~viscontact.physics.reference.StripPunch`): a0 = a, p0 = W / (pi a), the
        pressure at the centre of the face."""
        e_star = _e_star(shear_modulus, poisson_ratio)
        build = reference.StripPunch.from_load if control == "load" else reference.StripPunch.from_approach
        punch = build(reference_value, self.radius, e_star, datum)
        return self.radius, float(punch.load / (np.pi * self.radius))

    def scale(self, reference_value: float, control: str, shear_modulus: float,
              poisson_ratio: float) -> tuple[float, float]:
        """a0 = a, p0 = W / (2 pi a^2), the pressure at the centre of the face."""
        e_star = _e_star(shear_modulus, poisson_ratio)
        build = reference.FlatPunch.from_load if control == "load" else reference.FlatPunch.from_approach
        punch = build(reference_value, self.radius, e_star)
        return self.radius, punch.load / (2.0 * np.pi * self.radius**2)


@register
@dataclass(frozen=True)
class Cone(_SingularShape):
    """A cone of semi-apex angle ``half_angle`` alpha [degrees] (between the axis and the flank; 0 < alpha
    < 90; a Berkovich tip's equivalent cone has 70.3): gap r cot(alpha) (in a line contact a wedge).
    Sneddon (:class:`viscontact.physics.reference.Cone`): a = 2 delta tan(alpha) / pi,
    W = (pi/2) E* a^2 cot(alpha)."""

    half_angle: float

    name: ClassVar[str] = "cone"
    required: ClassVar[tuple[str, ...]] = ("half_angle",)
    model: ClassVar[str] = "Sneddon cone"
    load_error_per_cell: ClassVar[float] = CONE_LOAD_ERROR_PER_CELL
    singular: ClassVar[str] = ("the pressure at the tip is singular (logarithmically): the grid resolves the load, "
                               "the approach and the contact radius, not the tip's pressure (a cell average there)")

    @property
    def angle(self) -> float:
        """alpha [rad]."""
        return math.radians(self.half_angle)

    def check(self) -> None:
        """Refuse a half-angle outside (0, 90) degrees or a flank steeper than :data:`CONE_MAX_SLOPE`
        (cot alpha: an angle in radians given for degrees)."""
        if not 0.0 < self.half_angle < 90.0:
            raise ParameterError("indenter.half_angle", f"must be in (0, 90) degrees, got {self.half_angle!r}")
        if self.slope > CONE_MAX_SLOPE:
            raise ParameterError("indenter.half_angle", f"{self.half_angle:g} degrees gives flanks of slope "
                                 f"{self.slope:.3g}, beyond any half-space theory: the semi-apex angle in degrees "
                                 f"(> {math.degrees(math.atan(1 / CONE_MAX_SLOPE)):.3g})?")

    @property
    def slope(self) -> float:
        """The flanks' slope cot(alpha) [-]."""
        return 1.0 / math.tan(self.angle)

    def caveats(self, grid: Grid) -> list[str]:
        """Flanks steeper than :data:`CONE_WARN_SLOPE`: beyond the small-slope theory."""
        if self.slope <= CONE_WARN_SLOPE:
            return []
        return [f"indenter.half_angle = {self.half_angle:g} degrees: flanks of slope {self.slope:.3g}, beyond the "
                "small-slope theory of the half-space (a half-angle >= 45 degrees keeps it below 1)"]

    def gap(self, grid: Grid) -> np.ndarray:
        return _radial(grid) / math.tan(self.angle)

    def load_at_size(self, size: float, contact_modulus: float) -> float:
        return 0.5 * math.pi * contact_modulus * size**2 / math.tan(self.angle)

    def size_at_load(self, load: float, contact_modulus: float) -> float:
        return math.sqrt(2.0 * load * math.tan(self.angle) / (math.pi * contact_modulus))

    def size_at_approach(self, approach: float) -> float:
        return 2.0 * approach * math.tan(self.angle) / math.pi

    def scale(self, reference_value: float, control: str, shear_modulus: float,
              poisson_ratio: float) -> tuple[float, float]:
        """a0 = a, p0 = E* cot(alpha) / 2, the mean pressure (the same at every depth)."""
        e_star = _e_star(shear_modulus, poisson_ratio)
        build = reference.Cone.from_load if control == "load" else reference.Cone.from_approach
        cone = build(reference_value, self.angle, e_star)
        return cone.radius, cone.load / (np.pi * cone.radius**2)
