"""Analytic reference solutions (Hertz, Lee & Radok, Cattaneo-Mindlin, elliptical Hertz, Sneddon's
flat punch and cone; Hertz's and Cattaneo's line contacts) used to validate and normalise.

All functions take SI inputs and return SI outputs. ``shear_modulus`` is G, ``poisson_ratio`` nu; the
contact modulus of a rigid indenter on the half-space is E* = 2G/(1-nu) (``contact_modulus`` where a
function takes E* itself).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Hertz:
    """Hertz contact of a rigid sphere on an elastic half-space (Johnson, Contact Mechanics, 4.2).

    Attributes: ``radius`` a [m], ``peak_pressure`` p0 [Pa], ``approach`` delta [m], ``load`` W [N].
    """

    radius: float
    peak_pressure: float
    approach: float
    load: float

    def pressure(self, r: np.ndarray) -> np.ndarray:
        """p(r) = p0 sqrt(1 - r^2/a^2) inside the contact, 0 outside [Pa]."""
        r = np.asarray(r, dtype=float)
        return self.peak_pressure * np.sqrt(np.clip(1.0 - (r / self.radius) ** 2, 0.0, None))


def contact_modulus(shear_modulus: float, poisson_ratio: float) -> float:
    """E* = 2G / (1 - nu) [Pa] of a rigid indenter on the half-space."""
    return 2.0 * shear_modulus / (1.0 - poisson_ratio)


def hertz_from_load(load: float, sphere_radius: float, shear_modulus: float, poisson_ratio: float) -> Hertz:
    """Hertz solution for a load W [N]: a = (3WR/4E*)^(1/3), p0 = 3W/(2 pi a^2), delta = a^2/R."""
    e_star = contact_modulus(shear_modulus, poisson_ratio)
    a = (3.0 * load * sphere_radius / (4.0 * e_star)) ** (1.0 / 3.0)
    return Hertz(a, 3.0 * load / (2.0 * np.pi * a**2), a**2 / sphere_radius, load)


def hertz_from_approach(approach: float, sphere_radius: float, shear_modulus: float, poisson_ratio: float) -> Hertz:
    """Hertz solution for an approach delta [m]: a = sqrt(R delta), W = 4/3 E* sqrt(R) delta^(3/2)."""
    e_star = contact_modulus(shear_modulus, poisson_ratio)
    a = np.sqrt(sphere_radius * approach)
    load = 4.0 / 3.0 * e_star * np.sqrt(sphere_radius) * approach**1.5
    return Hertz(a, 3.0 * load / (2.0 * np.pi * a**2), approach, load)


# --- the other indenters of an indentation test --------------------------------------------------

@dataclass(frozen=True)
class EllipticalHertz:
    """Hertz contact of a rigid ellipsoid, gap x^2/(2 R_x) + y^2/(2 R_y), on an elastic half-space
    (:func:`elliptical_hertz`). Attributes: semi-axes ``semi_axis_x`` a_x and ``semi_axis_y`` a_y [m]
    of the elliptical contact, ``peak_pressure`` p0 [Pa], ``approach`` delta [m], ``load`` W [N],
    ``eccentricity`` e [-] (e^2 = 1 - (minor/major)^2)."""

    semi_axis_x: float
    semi_axis_y: float
    peak_pressure: float
    approach: float
    load: float
    eccentricity: float

    def pressure(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """p = p0 sqrt(1 - x^2/a_x^2 - y^2/a_y^2) inside the ellipse, 0 outside [Pa]."""
        inside = 1.0 - (np.asarray(x) / self.semi_axis_x) ** 2 - (np.asarray(y) / self.semi_axis_y) ** 2
        return self.peak_pressure * np.sqrt(np.clip(inside, 0.0, None))


#: |R_x/R_y - 1| below which :func:`elliptical_hertz` is the sphere's Hertz contact (e -> 0: K - E loses
#: its digits to cancellation there)
ELLIPSE_ROUND = 1e-9


def _curvature_ratio(m: float) -> float:
    """B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)) [-] of the elliptical contact with e^2 = ``m``."""
    from scipy import special  # not at import: the command line's parser loads this module

    k, e = special.ellipk(m), special.ellipe(m)
    return (e / (1.0 - m) - k) / (k - e)


def elliptical_hertz(load: float, radius_x: float, radius_y: float, contact_modulus: float) -> EllipticalHertz:
    """Hertz's elliptical contact (Johnson, *Contact Mechanics*, 1985, Sec. 4.2, Eqs. 4.31-4.43) of a
    rigid ellipsoid with principal radii ``radius_x``, ``radius_y`` [m] (gap A x^2 + B y^2 with
    A = 1/(2 R_x), B = 1/(2 R_y)) pressed by ``load`` W [N] on a half-space of E* [Pa].

    With the major semi-axis a along the larger radius, the minor b = a sqrt(1 - e^2) and K(e), E(e) the
    complete elliptic integrals of the first and second kind (modulus e; ``scipy.special.ellipk`` and
    ``ellipe`` take m = e^2), the pressure p0 sqrt(1 - (x/a)^2 - (y/b)^2) displaces the surface by
    delta - A' x'^2 - B' y'^2 inside the ellipse with

        A' = p0 b (K - E) / (E* e^2 a^2),   B' = p0 b ((a/b)^2 E - K) / (E* e^2 a^2),   delta = p0 b K / E*

    (primes: along the major and the minor axis). Matching the gap: e solves B'/A' = R_major/R_minor
    (``scipy.optimize.brentq``), then with W = (2/3) pi a b p0

        a^3 = 3 W (K - E) / (2 pi A' E* e^2),   p0 = 3 W / (2 pi a b),   delta = p0 b K / E*.

    R_x = R_y is the sphere (:func:`hertz_from_load`; e = 0)."""
    from scipy import optimize, special  # not at import: the command line's parser loads this module

    major, minor = max(radius_x, radius_y), min(radius_x, radius_y)
    if abs(major / minor - 1.0) < ELLIPSE_ROUND:
        h = hertz_from_load(load, minor, contact_modulus * 0.5, 0.0)
        return EllipticalHertz(h.radius, h.radius, h.peak_pressure, h.approach, load, 0.0)
    ratio = major / minor
    m = optimize.brentq(lambda m: _curvature_ratio(m) - ratio, 1e-12, 1.0 - 1e-15, xtol=1e-16, rtol=1e-15)
    k, e = special.ellipk(m), special.ellipe(m)
    a = (3.0 * load * (k - e) * 2.0 * major / (2.0 * np.pi * contact_modulus * m)) ** (1.0 / 3.0)
    b = a * np.sqrt(1.0 - m)
    p0 = 3.0 * load / (2.0 * np.pi * a * b)
    semi_x, semi_y = (a, b) if radius_x >= radius_y else (b, a)
    return EllipticalHertz(float(semi_x), float(semi_y), float(p0), float(p0 * b * k / contact_modulus),
                           float(load), float(np.sqrt(m)))


@dataclass(frozen=True)
class FlatPunch:
    """Boussinesq's rigid flat circular punch (Sneddon 1965; Johnson, *Contact Mechanics*, 1985,
    Sec. 3.8) of radius a [m] pressed by delta [m] on a half-space of E* [Pa]:

        W = 2 a E* delta (the stiffness dW/d delta = 2 a E*),   p(r) = W / (2 pi a sqrt(a^2 - r^2)),

    singular (integrably, as (a - r)^(-1/2)) at the rim; the centre's pressure is W / (2 pi a^2).
    Attributes: ``radius`` a [m], ``approach`` delta [m], ``load`` W [N]."""

    radius: float
    approach: float
    load: float

    @classmethod
    def from_approach(cls, approach: float, radius: float, contact_modulus: float) -> "FlatPunch":
        return cls(radius, approach, 2.0 * radius * contact_modulus * approach)

    @classmethod
    def from_load(cls, load: float, radius: float, contact_modulus: float) -> "FlatPunch":
        return cls(radius, load / (2.0 * radius * contact_modulus), load)

    def pressure(self, r: np.ndarray) -> np.ndarray:
        """p(r) [Pa] on the face (r < a), 0 outside (inf on the rim itself)."""
        r = np.asarray(r, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            p = self.load / (2.0 * np.pi * self.radius * np.sqrt(self.radius**2 - r**2))
        return np.where(r < self.radius, p, np.where(r == self.radius, np.inf, 0.0))


@dataclass(frozen=True)
class Cone:
    """Sneddon's (1948, 1965) rigid cone on a half-space of E* [Pa]; its semi-apex angle alpha (the
    angle between the axis and the flank), gap h(r) = r cot(alpha). From Sneddon's integrals for a
    profile f(r), delta = a int_0^1 f'(a x) / sqrt(1 - x^2) dx and W = 2 E* int_0^a (delta - g(t)) dt,
    g(t) = t int_0^t f'(r) / sqrt(t^2 - r^2) dr, with f' = cot(alpha):

        delta = (pi / 2) a cot(alpha),   W = (pi / 2) E* a^2 cot(alpha) = (2 / pi) E* tan(alpha) delta^2,
        p(r) = (E* cot(alpha) / 2) arccosh(a / r)   (r < a),

    the mean pressure W / (pi a^2) = E* cot(alpha) / 2 at every depth (geometric similarity) and a
    logarithmic singularity at the tip (Johnson, *Contact Mechanics*, 1985, Sec. 5.6; the
    same relations with beta = 90 deg - alpha, the inclination of the flank, and cot(alpha) = tan(beta)).
    Attributes: ``radius`` a [m], ``approach`` delta [m], ``load`` W [N], ``half_angle`` alpha [rad]."""

    radius: float
    approach: float
    load: float
    half_angle: float

    @classmethod
    def from_approach(cls, approach: float, half_angle: float, contact_modulus: float) -> "Cone":
        """The cone of semi-apex ``half_angle`` alpha [rad] pressed by ``approach`` delta [m]."""
        a = 2.0 * approach * np.tan(half_angle) / np.pi
        return cls(float(a), approach, float(0.5 * np.pi * contact_modulus * a**2 / np.tan(half_angle)), half_angle)

    @classmethod
    def from_load(cls, load: float, half_angle: float, contact_modulus: float) -> "Cone":
        """The cone of semi-apex ``half_angle`` alpha [rad] pressed by ``load`` W [N]."""
        a = np.sqrt(2.0 * load * np.tan(half_angle) / (np.pi * contact_modulus))
        return cls(float(a), float(0.5 * np.pi * a / np.tan(half_angle)), load, half_angle)

    def pressure(self, r: np.ndarray) -> np.ndarray:
        """p(r) [Pa] inside the contact (inf at the tip), 0 outside."""
        r = np.asarray(r, dtype=float)
        mean = 0.5 * self.load / (0.5 * np.pi * self.radius**2)
        with np.errstate(divide="ignore"):
            ratio = self.radius / np.clip(r, 0.0, self.radius)
        return np.where(r < self.radius, mean * np.arccosh(np.maximum(ratio, 1.0)), 0.0)


def hertz_line_half_width(load_per_length: float, radius: float, contact_modulus: float) -> float:
    """Half-width b [m] of Hertz's line contact of a rigid cylinder of ``radius`` R [m] pressed by
    ``load_per_length`` W' [N/m] on a half-space of E* [Pa] (plane strain; Johnson, *Contact Mechanics*,
    1985, Sec. 4.3, Eq. 4.45): b = sqrt(4 W' R / (pi E*)), its peak pressure 2 W' / (pi b)."""
    return float(np.sqrt(4.0 * load_per_length * radius / (np.pi * contact_modulus)))


# --- line contact (plane strain) -------------------------------------------------------------------

def line_approach(contact_half_width: float, cylinder_radius: float, datum: float) -> float:
    """Approach delta [m] of a rigid cylinder (radius R [m]) in Hertz line contact of half-width a [m],
    relative to the datum b [m] (the surface points at distance b from a line load stay put, the
    convention of :mod:`viscontact.physics.kernels`):

        delta = (a^2 / 2R) (ln(2b/a) + 1/2) = (2W / (pi E*)) (ln(2b/a) + 1/2).

    From u_z(0) = -(2/(pi E*)) int p(s) ln(|s|/b) ds with p = p0 sqrt(1 - s^2/a^2) and
    the integral of sqrt(1 - t^2) ln|t| over [-1, 1], -(pi/2)(ln 2 + 1/2) (Gradshteyn & Ryzhik 4.241). The approach of
    a line contact is defined only relative to a datum (Johnson, *Contact Mechanics*, 1985, §2.2 after
    Eq. 2.19 and §4.3: it depends on where it is measured from).
    """
    a = contact_half_width
    return a**2 / (2.0 * cylinder_radius) * (np.log(2.0 * datum / a) + 0.5)


def hertz_line_from_load(load: float, cylinder_radius: float, shear_modulus: float, poisson_ratio: float,
                         datum: float) -> Hertz:
    """Hertz line contact of a rigid cylinder (radius R [m], axis along y) on an elastic half-space in
    plane strain under a load W per unit length [N/m] (Johnson, *Contact Mechanics*, 1985, §4.3,
    Eqs. 4.43-4.45 with a rigid cylinder): half-width a = sqrt(4 W R / (pi E*)) [m]
    (:func:`hertz_line_half_width`), peak pressure
    p0 = 2 W / (pi a) [Pa], p(x) = p0 sqrt(1 - x^2/a^2); the approach relative to the datum b [m]
    (:func:`line_approach`). The :class:`Hertz` returned holds a in ``radius`` and W [N/m] in ``load``."""
    a = hertz_line_half_width(load, cylinder_radius, contact_modulus(shear_modulus, poisson_ratio))
    return Hertz(a, 2.0 * load / (np.pi * a), line_approach(a, cylinder_radius, datum), load)


def hertz_line_from_approach(approach: float, cylinder_radius: float, shear_modulus: float, poisson_ratio: float,
                             datum: float) -> Hertz:
    """:func:`hertz_line_from_load` for the approach delta [m] relative to the datum b [m]: a [m] solves
    :func:`line_approach` (monotone for a < 2b), then W = pi a^2 E* / (4 R) [N/m]."""
    from scipy.optimize import brentq

    if approach <= 0:
        return Hertz(0.0, 0.0, float(approach), 0.0)
    top = 2.0 * datum
    if approach >= line_approach(top * (1.0 - 1e-12), cylinder_radius, datum):
        raise ValueError(f"approach {approach:g} m: no Hertz line contact narrower than 4 b = {2 * top:g} m")
    a = brentq(lambda a: line_approach(a, cylinder_radius, datum) - approach, 1e-300, top, xtol=1e-15 * top,
               rtol=1e-14)
    e_star = contact_modulus(shear_modulus, poisson_ratio)
    load = np.pi * a**2 * e_star / (4.0 * cylinder_radius)
    return Hertz(a, 2.0 * load / (np.pi * a), float(approach), load)


@dataclass(frozen=True)
class StripPunch:
    """A rigid flat strip punch of half-width a [m] (a flat punch in line contact, plane strain) pressed
    on a half-space of E* [Pa] by a load W per unit length [N/m] (Johnson, *Contact Mechanics*, 1985,
    §2.8, Eq. 2.64):

        p(x) = W / (pi sqrt(a^2 - x^2)),   delta = (2 W / (pi E*)) ln(2b / a),

    the pressure singular (integrably) at the edges, its value at the centre W / (pi a); the approach
    relative to the datum b [m] (:func:`line_approach`'s convention), from the integral of
    ln|x - s| / (pi sqrt(a^2 - s^2)) over s in [-a, a], ln(a/2) for |x| <= a (the displacement is
    uniform over the face). Attributes: ``half_width`` a [m], ``approach`` delta [m], ``load`` W [N/m],
    ``datum`` b [m]."""

    half_width: float
    approach: float
    load: float
    datum: float

    @classmethod
    def from_load(cls, load: float, half_width: float, contact_modulus: float, datum: float) -> "StripPunch":
        return cls(half_width, 2.0 * load / (np.pi * contact_modulus) * np.log(2.0 * datum / half_width), load, datum)

    @classmethod
    def from_approach(cls, approach: float, half_width: float, contact_modulus: float, datum: float) -> "StripPunch":
        return cls(half_width, approach, np.pi * contact_modulus * approach / (2.0 * np.log(2.0 * datum / half_width)),
                   datum)

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """p(x) [Pa] on the face (|x| < a), 0 outside (inf at the edges themselves)."""
        x = np.asarray(x, dtype=float)
        a = self.half_width
        with np.errstate(divide="ignore", invalid="ignore"):
            p = self.load / (np.pi * np.sqrt(a**2 - x**2))
        return np.where(np.abs(x) < a, p, np.where(np.abs(x) == a, np.inf, 0.0))


@dataclass(frozen=True)
class LineCattaneo:
    """Partial slip of a rigid cylinder in line contact (plane strain) under a load W [N/m] and a growing
    tangential force Q [N/m] (Cattaneo 1938; Johnson, *Contact Mechanics*, 1985, §7.1, Eqs. 7.4-7.8):
    the shear traction is mu_f p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)], the stick zone
    |x| < c with c/a = sqrt(1 - Q / (mu_f W)). Exact without normal-tangential coupling (nu = 0.5;
    else the coupling terms, proportional to 1 - 2 nu, are neglected as in Johnson's).

    Attributes: ``contact_half_width`` a [m], ``load`` W [N/m], ``friction_coefficient`` mu_f [-],
    ``cylinder_radius`` R [m], ``datum`` b [m] (for :meth:`displacement`).
    """

    contact_half_width: float
    load: float
    friction_coefficient: float
    cylinder_radius: float
    datum: float

    def stick_ratio_from_force(self, force: np.ndarray | float) -> np.ndarray:
        """c/a = (1 - Q/(mu_f W))^(1/2) [-] for Q [N/m], 0 <= Q <= mu_f W."""
        q = np.asarray(force, dtype=float) / (self.friction_coefficient * self.load)
        return np.sqrt(np.clip(1.0 - q, 0.0, None))

    def shear_traction(self, x: np.ndarray, force: float) -> np.ndarray:
        """q(x) [Pa] in the direction of Q at x [m] (the second term inside the stick zone only)."""
        a = self.contact_half_width
        c = float(self.stick_ratio_from_force(force)) * a
        p0 = 2.0 * self.load / (np.pi * a)
        x = np.asarray(x, dtype=float)
        outer = np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
        inner = (c / a) * np.sqrt(np.clip(1.0 - (x / c) ** 2, 0.0, None)) if c > 0 else 0.0 * x
        return self.friction_coefficient * p0 * (outer - inner)

    def displacement(self, force: np.ndarray | float) -> np.ndarray:
        """Tangential displacement delta_x [m] of the stick zone relative to the datum b:
        mu_f [a^2 (ln(2b/a) + 1/2) - c^2 (ln(2b/c) + 1/2)] / (2R), the two Hertz-like traction
        distributions' displacements (:func:`line_approach`; the tangential kernel of plane strain
        equals the normal one)."""
        a, r, b = self.contact_half_width, self.cylinder_radius, self.datum
        c = self.stick_ratio_from_force(force) * a
        with np.errstate(divide="ignore", invalid="ignore"):
            inner = np.where(c > 0, c**2 * (np.log(2.0 * b / np.where(c > 0, c, 1.0)) + 0.5), 0.0)
        return self.friction_coefficient * (a**2 * (np.log(2.0 * b / a) + 0.5) - inner) / (2.0 * r)


def line_cattaneo(load: float, cylinder_radius: float, friction_coefficient: float, shear_modulus: float,
                  poisson_ratio: float, datum: float) -> LineCattaneo:
    """:class:`LineCattaneo` of a rigid cylinder (R [m]) pressed by W [N/m] on an elastic half-space
    (G [Pa], nu), Coulomb friction mu_f, datum b [m]: the Hertz half-width of :func:`hertz_line_from_load`."""
    a = hertz_line_from_load(load, cylinder_radius, shear_modulus, poisson_ratio, datum).radius
    return LineCattaneo(float(a), float(load), float(friction_coefficient), float(cylinder_radius), float(datum))


def oedometric_modulus(shear_modulus: float, poisson_ratio: float) -> float:
    """M = 2 G (1 - nu)/(1 - 2 nu) [Pa], the modulus of uniaxial strain (lateral strain zero); inf at
    nu = 0.5."""
    if poisson_ratio == 0.5:
        return float("inf")
    return 2.0 * shear_modulus * (1.0 - poisson_ratio) / (1.0 - 2.0 * poisson_ratio)


def winkler_sphere(load: float, sphere_radius: float, thickness: float, shear_modulus: float,
                   poisson_ratio: float) -> Hertz:
    """A rigid sphere (R [m], load W [N]) on a thin compressible layer (h [m], G [Pa], nu < 0.5) bonded
    to a rigid base, in the thin-layer limit h/a -> 0.

    Far from the contact edge (a distance of order h) the layer is in uniaxial strain: each point's
    displacement is h/M times its pressure, M the :func:`oedometric_modulus`, a Winkler foundation
    of stiffness M/h (Johnson, *Contact Mechanics*, 1985, Sec. 4.3, the elastic foundation model,
    with M in place of K as the layer is bonded). With the gap r^2/2R,

        p(r) = (M/h) (delta - r^2/2R),   p(a) = 0: delta = a^2/(2R),   p0 = M a^2/(2 R h),
        W = int_0^a 2 pi r p dr = pi M a^4/(4 R h):   a = (4 W R h/(pi M))^(1/4).

    Returns a :class:`Hertz` record of (a, p0, delta, W) (the pressure profile is the parabola above,
    not :meth:`Hertz.pressure`'s)."""
    modulus = oedometric_modulus(shear_modulus, poisson_ratio)
    a = (4.0 * load * sphere_radius * thickness / (np.pi * modulus)) ** 0.25
    return Hertz(a, modulus * a**2 / (2.0 * sphere_radius * thickness), a**2 / (2.0 * sphere_radius), load)


# --- viscoelastic Hertz: Lee & Radok (1960) ------------------------------------------------------

@dataclass(frozen=True)
class ViscoelasticHertz:
    """Contact of a rigid sphere on a linear viscoelastic half-space at the times ``time`` [s].

    Attributes (arrays with the shape of ``time``): ``radius`` a(t) [m], ``approach`` delta(t) [m],
    ``load`` W(t) [N]. Valid while the contact radius does not decrease (Lee & Radok 1960).
    """

    time: np.ndarray
    radius: np.ndarray
    approach: np.ndarray
    load: np.ndarray


def _times(t: np.ndarray | float) -> np.ndarray:
    t = np.asarray(t, dtype=float)
    if np.any(t < 0):
        raise ValueError("times must be >= 0 s")
    return t


def lee_radok_creep(load: float, sphere_radius: float, material, t: np.ndarray | float) -> ViscoelasticHertz:
    """Creep of a rigid sphere under a load W [N] applied at t = 0 and held (Lee & Radok 1960;
    Johnson, *Contact Mechanics*, §6.5).

    The correspondence principle turns 1/E* = (1 - nu)/(2G) into the creep operator (1 - nu) J(t)/2,
    and because the contact radius grows monotonically the elastic Hertz relations hold with it:

        a(t)^3 = 3 W R (1 - nu) J(t) / 8     [m^3],     delta(t) = a(t)^2 / R     [m],

    with J(t) the shear creep compliance [1/Pa] of ``material`` (:class:`viscontact.physics.materials.Material`)
    and R = ``sphere_radius`` [m]. At t = 0 this is Hertz with G(0); as t -> inf, Hertz with G(inf).
    With a time-dependent Poisson ratio (:class:`viscontact.bodies.bulk_elastic.BulkElasticMaterial`) (1 - nu) J(t)
    is the creep function of the operator (1 - nu)/G (:func:`normal_creep`).
    """
    t = _times(t)
    a = (3.0 * load * sphere_radius * normal_creep(material, t) / 8.0) ** (1.0 / 3.0)
    return ViscoelasticHertz(t, a, a**2 / sphere_radius, np.full(t.shape, float(load)))


def normal_creep(material, t: np.ndarray | float) -> np.ndarray:
    """Creep function [1/Pa] of the normal compliance operator (1 - nu)/G at times t [s]:
    (1 - nu) J(t) for a constant Poisson ratio (:class:`viscontact.physics.materials.Material`), the
    computed spectrum of :meth:`viscontact.bodies.bulk_elastic.BulkElasticMaterial.factor` ("normal") when the
    bulk modulus is elastic and nu(t) varies. With it, Lee & Radok's creep under a held load reads
    a(t)^3 = 3 W R normal_creep(t) / 8 for both."""
    if hasattr(material, "bulk_modulus"):
        return material.factor("normal").compliance(t)
    return (1.0 - material.poisson_ratio) * material.creep_compliance(t)


def lee_radok_relaxation(approach: float, sphere_radius: float, material, t: np.ndarray | float) -> ViscoelasticHertz:
    """Relaxation under an approach delta [m] applied at t = 0 and held (Lee & Radok 1960).

    The contact radius stays a = sqrt(R delta) and the load relaxes with the shear modulus:

        W(t) = 8 G(t) sqrt(R) delta^(3/2) / (3 (1 - nu))     [N],   i.e.  W(t)/W(0) = G(t)/G(0),

    the elastic Hertz load with E* = 2 G(t)/(1 - nu); G(t) [Pa] is the relaxation modulus of
    ``material``. The pressure is the Hertz one scaled by G(t)/G(0).
    """
    t = _times(t)
    nu = material.poisson_ratio
    w = 8.0 * material.relaxation_modulus(t) * np.sqrt(sphere_radius) * approach**1.5 / (3.0 * (1.0 - nu))
    a = np.sqrt(sphere_radius * approach)
    return ViscoelasticHertz(t, np.full(t.shape, a), np.full(t.shape, float(approach)), w)


def lee_radok_cone_load(t: np.ndarray | float, times, depths, half_angle: float, material) -> np.ndarray:
    """Load W(t) [N] on a rigid cone of semi-apex ``half_angle`` alpha [rad] pushed into ``material``
    (a :class:`viscontact.physics.materials.Material`, constant nu) along the piecewise-linear depth
    history through (``times`` [s], ``depths`` [m]), from delta = 0, while the depth never decreases
    (the contact grows or holds: Lee & Radok 1960).

    Sneddon's W = (2/pi) E* tan(alpha) delta^2 (:class:`Cone`) with E* = 2G/(1 - nu) becomes, by the
    correspondence principle, the hereditary integral

        W(t) = 4 tan(alpha) / (pi (1 - nu)) int_0^t G(t - s) d(delta^2)(s),

    evaluated exactly: on a segment where delta = d0 + v (s - s0), d(delta^2)/ds = 2 v (d0 + v (s - s0))
    is linear in s, and each Prony term g exp(-(t - s)/tau) integrates in closed form. The contact
    radius is Sneddon's, a = 2 delta tan(alpha)/pi, whatever the modulus.
    """
    t = _times(t)
    times, depths = np.asarray(times, dtype=float), np.asarray(depths, dtype=float)
    if np.any(np.diff(depths) < 0):
        raise ValueError("the depth must never decrease (Lee & Radok: a growing or held contact)")
    if depths[0] != 0:
        times, depths = np.r_[times[0], times], np.r_[0.0, depths]  # pushed in at the first time
    flat = t.ravel()
    total = np.zeros_like(flat)
    for s0, s1, d0, d1 in zip(times[:-1], times[1:], depths[:-1], depths[1:]):
        v = (d1 - d0) / (s1 - s0)
        if v == 0:
            continue
        hi = np.clip(flat, s0, s1)  # the part of the segment before t
        # d(delta^2)/ds = A + B (s - s0), A = 2 v d0, B = 2 v^2, integrated against G(t - s)
        a_, b_ = 2.0 * v * d0, 2.0 * v * v
        u = hi - s0
        total += material.g_inf * (a_ * u + 0.5 * b_ * u**2)
        for g, tau in zip(material.g, material.tau):
            c = 1.0 / tau

            def primitive(s, c=c):  # of exp(-c (t - s)) (A + B (s - s0)) over s
                return np.exp(-c * (flat - s)) * ((a_ + b_ * (s - s0)) / c - b_ / c**2)

            total += g * np.where(flat > s0, primitive(hi) - primitive(np.full_like(flat, s0)), 0.0)
    return (4.0 * np.tan(half_angle) / (np.pi * (1.0 - material.poisson_ratio)) * total).reshape(t.shape)


def lee_radok_centre_pressure(load: float, sphere_radius: float, material, t: np.ndarray | float) -> np.ndarray:
    """Pressure p(0, t) [Pa] at the centre of the contact under a held load W [N] (Lee & Radok 1960).

    With a growing radius a(t) (:func:`lee_radok_creep`) the pressure is the hereditary integral of
    the elastic Hertz pressure p = 4 G sqrt(a^2 - r^2) / (pi R (1 - nu)) with G -> G(t):

        p(0, t) = 4 / (pi R (1 - nu)) [ G(t) a(0) + int_0^t G(t - s) a'(s) ds ]     [Pa].

    It is not the Hertz pressure of a(t): while the material creeps, the newly loaded rim responds
    with the stiffer short-time modulus, so the pressure is flatter than Hertzian and the centre
    pressure lies below 3W/(2 pi a(t)^2); both agree at t = 0 (G(0)) and as t -> inf (G(inf)). The integral is evaluated by adaptive quadrature (``scipy.integrate.quad``,
    relative accuracy about 1e-10); a'(s) = a(s) J'(s) / (3 J(s)) exactly.
    """
    from scipy.integrate import quad

    t = _times(t)
    nu = material.poisson_ratio
    creep = material.creep
    factor = 4.0 / (np.pi * sphere_radius * (1.0 - nu))
    a0 = float(lee_radok_creep(load, sphere_radius, material, 0.0).radius)

    def rate(s: float) -> float:
        j = float(material.creep_compliance(s))
        dj = float(np.sum(creep.amplitudes / creep.retardation_times * np.exp(-s / creep.retardation_times)))
        return a0 * (j / creep.instantaneous) ** (1.0 / 3.0) * dj / (3.0 * j)

    out = np.empty(t.shape)
    for idx, ti in np.ndenumerate(t):
        integral = 0.0
        if ti > 0 and creep.amplitudes.size:
            integral, _ = quad(lambda s, ti=ti: float(material.relaxation_modulus(ti - s)) * rate(s), 0.0, ti,
                               epsabs=0.0, epsrel=1e-11, limit=200)
        out[idx] = factor * (float(material.relaxation_modulus(ti)) * a0 + integral)
    return out


# --- Cattaneo-Mindlin partial slip -------------------------------------------------------------

@dataclass(frozen=True)
class CattaneoMindlin:
    """Partial slip of a rigid sphere on an elastic half-space under a constant normal load W and a
    monotonically growing tangential force Q (Cattaneo 1938, Mindlin 1949; Johnson, *Contact
    Mechanics*, §7.2, Eqs. 7.38-7.42 with a rigid second body).

    Exact only without normal/tangential coupling (nu = 0.5, or neglecting the (1 - 2 nu) terms).

    Attributes: ``contact_radius`` a [m] (Hertz), ``load`` W [N], ``friction_coefficient`` mu_f [-],
    ``shear_modulus`` G [Pa], ``poisson_ratio`` nu [-].
    """

    contact_radius: float
    load: float
    friction_coefficient: float
    shear_modulus: float
    poisson_ratio: float

    @property
    def sliding_displacement(self) -> float:
        """delta* = 3 mu_f W (2 - nu) / (16 G a) [m]: tangential displacement at which gross sliding
        begins (c = 0, Q = mu_f W)."""
        mu, w, nu = self.friction_coefficient, self.load, self.poisson_ratio
        return 3.0 * mu * w * (2.0 - nu) / (16.0 * self.shear_modulus * self.contact_radius)

    def stick_ratio_from_force(self, force: np.ndarray | float) -> np.ndarray:
        """c/a = (1 - Q/(mu_f W))^(1/3) [-] for a tangential force Q [N] (0 <= Q <= mu_f W)."""
        q = np.asarray(force, dtype=float) / (self.friction_coefficient * self.load)
        return np.clip(1.0 - q, 0.0, None) ** (1.0 / 3.0)

    def stick_ratio_from_displacement(self, displacement: np.ndarray | float) -> np.ndarray:
        """c/a = (1 - delta_x/delta*)^(1/2) [-] for a tangential displacement delta_x [m]."""
        d = np.asarray(displacement, dtype=float) / self.sliding_displacement
        return np.sqrt(np.clip(1.0 - d, 0.0, None))

    def force(self, displacement: np.ndarray | float) -> np.ndarray:
        """Q(delta_x) = mu_f W [1 - (1 - delta_x/delta*)^(3/2)] [N], = mu_f W beyond delta*."""
        d = np.asarray(displacement, dtype=float) / self.sliding_displacement
        return self.friction_coefficient * self.load * (1.0 - np.clip(1.0 - d, 0.0, None) ** 1.5)

    def displacement(self, force: np.ndarray | float) -> np.ndarray:
        """delta_x(Q) = delta* [1 - (1 - Q/(mu_f W))^(2/3)] [m]."""
        return self.sliding_displacement * (1.0 - self.stick_ratio_from_force(force) ** 2)

    def shear_traction(self, r: np.ndarray, force: float) -> np.ndarray:
        """q(r) [Pa] in the direction of Q: mu_f p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)]
        (the second term only inside the stick radius c)."""
        a = self.contact_radius
        c = float(self.stick_ratio_from_force(force)) * a
        p0 = 3.0 * self.load / (2.0 * np.pi * a**2)
        r = np.asarray(r, dtype=float)
        outer = np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))
        inner = (c / a) * np.sqrt(np.clip(1.0 - (r / c) ** 2, 0.0, None)) if c > 0 else 0.0 * r
        return self.friction_coefficient * p0 * (outer - inner)

    # --- Mindlin & Deresiewicz (1953): oscillating Q under the held W (Johnson §7.3) -----------------
    def unloading_force(self, displacement: np.ndarray | float, amplitude: float) -> np.ndarray:
        """Q [N] on the unloading branch from delta_x = ``amplitude`` delta_a (< delta*) down to -delta_a:
        a reversed Cattaneo-Mindlin distribution of twice the friction superposed on the loading one,
        Q = Q_a - 2 Q_L((delta_a - delta_x)/2), Q_L = :meth:`force` (the loading curve) and
        Q_a = Q_L(delta_a); in Johnson's form delta = delta_a - 2 delta_L((Q_a - Q)/2)."""
        d = np.asarray(displacement, dtype=float)
        return self.force(amplitude) - 2.0 * self.force(0.5 * (amplitude - d))

    def reloading_force(self, displacement: np.ndarray | float, amplitude: float) -> np.ndarray:
        """Q [N] on the reloading branch from delta_x = -delta_a back to delta_a: the unloading branch
        turned by half a turn, Q = -Q_a + 2 Q_L((delta_a + delta_x)/2)."""
        return -self.unloading_force(-np.asarray(displacement, dtype=float), amplitude)

    def cycle_energy(self, amplitude: float) -> float:
        """Energy [J] dissipated in one full cycle of delta_x between -delta_a and delta_a, the area of
        the loop: 9 mu_f^2 W^2 (2 - nu) / (10 G a) {1 - (1 - Q_a/(mu_f W))^(5/3) - (5 Q_a / (6 mu_f W))
        [1 + (1 - Q_a/(mu_f W))^(2/3)]} with Q_a = Q_L(delta_a) (Johnson §7.3; equal to the
        integral of the two branches to round-off, tests/validation/test_fretting.py)."""
        mu_w = self.friction_coefficient * self.load
        r = float(self.force(amplitude)) / mu_w
        scale = 9.0 * mu_w**2 * (2.0 - self.poisson_ratio) / (10.0 * self.shear_modulus * self.contact_radius)
        return scale * (1.0 - (1.0 - r) ** (5.0 / 3.0) - 5.0 * r / 6.0 * (1.0 + (1.0 - r) ** (2.0 / 3.0)))


def cattaneo_mindlin(load: float, sphere_radius: float, friction_coefficient: float, shear_modulus: float,
                     poisson_ratio: float) -> CattaneoMindlin:
    """Cattaneo-Mindlin solution for a rigid sphere of radius R [m] pressed by W [N] on an elastic
    half-space (G [Pa], nu) with Coulomb friction mu_f: Hertz radius a, stick radius
    c/a = (1 - Q/mu_f W)^(1/3), delta* = 3 mu_f W (2 - nu)/(16 G a) and
    Q(delta_x)/(mu_f W) = 1 - (1 - delta_x/delta*)^(3/2) (Johnson, *Contact Mechanics*, §7.2)."""
    a = hertz_from_load(load, sphere_radius, shear_modulus, poisson_ratio).radius
    return CattaneoMindlin(float(a), float(load), float(friction_coefficient), float(shear_modulus),
                           float(poisson_ratio))


@dataclass(frozen=True)
class Carter:
    """Steady rolling with traction of a rigid cylinder on an elastic half-plane (plane strain; Carter
    1926; Johnson, *Contact Mechanics*, 1985, Sec. 8.2, with a rigid second body): a held load W'
    [N/m], a traction Q' [N/m] (|Q'| < mu_f W'), Hertz half-width a [m] and peak p0 = 2 W'/(pi a) [Pa].

    Signs of viscontact's rolling (the cylinder rolls in +x; Q' the traction on the body, > 0 when
    braking): the stick zone of half-width c = a sqrt(1 - |Q'|/(mu_f W')) at the leading edge,
    [a - 2c, a]; the traction sgn(Q') mu_f p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - (x - a + c)^2/c^2)]
    (the second term on the stick zone); the creepage (V_c - V)/V, the surface strain du_x/dx that the
    stick zone carries,

        xi = -sgn(Q') (2 mu_f p0 / E*) (1 - c/a) = -sgn(Q') (mu_f a / R) (1 - sqrt(1 - |Q'|/(mu_f W'))),

    from du_x/dx = -(2 / (pi E*)) PV int q(s) / (x - s) ds on the half-plane's surface. Exact without
    the normal-tangential coupling (nu = 0.5). Attributes: ``half_width`` a [m], ``load`` W' [N/m],
    ``friction_coefficient`` mu_f [-], ``contact_modulus`` E* [Pa] (2 G / (1 - nu) for a rigid
    cylinder on the body)."""

    half_width: float
    load: float
    friction_coefficient: float
    contact_modulus: float

    @property
    def peak_pressure(self) -> float:
        """p0 = 2 W' / (pi a) [Pa]."""
        return 2.0 * self.load / (np.pi * self.half_width)

    def stick_half_width(self, force: float) -> float:
        """c = a sqrt(1 - |Q'|/(mu_f W')) [m] for the traction Q' [N/m]."""
        return self.half_width * float(np.sqrt(max(1.0 - abs(force) / (self.friction_coefficient * self.load), 0.0)))

    def creepage(self, force: np.ndarray | float) -> np.ndarray:
        """xi(Q') = -sgn(Q') (2 mu_f p0 / E*) (1 - c/a) [-] (class docstring); beyond |Q'| = mu_f W'
        the contact slides."""
        ratio = np.clip(np.abs(np.asarray(force, dtype=float)) / (self.friction_coefficient * self.load), 0.0, 1.0)
        scale = 2.0 * self.friction_coefficient * self.peak_pressure / self.contact_modulus
        return -np.sign(force) * scale * (1.0 - np.sqrt(1.0 - ratio))

    def force(self, creepage: np.ndarray | float) -> np.ndarray:
        """Q'(xi) [N/m]: the inverse of :meth:`creepage`, mu_f W' sgn(-xi) (1 - (1 - |xi|/xi*)^2) up to
        |xi| = xi* = 2 mu_f p0 / E*, mu_f W' sgn(-xi) beyond (full slip)."""
        xi = np.asarray(creepage, dtype=float)
        scale = 2.0 * self.friction_coefficient * self.peak_pressure / self.contact_modulus
        stick = np.clip(1.0 - np.abs(xi) / scale, 0.0, 1.0)
        return -np.sign(xi) * self.friction_coefficient * self.load * (1.0 - stick**2)

    def shear_traction(self, x: np.ndarray, force: float) -> np.ndarray:
        """q(x) [Pa] on the body for the traction Q' [N/m] (class docstring)."""
        a, c = self.half_width, self.stick_half_width(force)
        x = np.asarray(x, dtype=float)
        outer = np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
        inner = (c / a) * np.sqrt(np.clip(1.0 - ((x - a + c) / c) ** 2, 0.0, None)) if c > 0 else 0.0 * x
        return float(np.sign(force)) * self.friction_coefficient * self.peak_pressure * (outer - inner)


def carter(load_per_length: float, radius: float, friction_coefficient: float, shear_modulus: float,
           poisson_ratio: float) -> Carter:
    """:class:`Carter`'s rolling of a rigid cylinder of radius R [m] pressed by W' [N/m] on an elastic
    half-plane (G [Pa], nu; E* = 2 G / (1 - nu)) with Coulomb friction mu_f."""
    modulus = contact_modulus(shear_modulus, poisson_ratio)
    return Carter(hertz_line_half_width(load_per_length, radius, modulus), float(load_per_length),
                  float(friction_coefficient), modulus)


def hertz_axis_stresses(depth: np.ndarray | float, contact_radius: float, peak_pressure: float,
                        poisson_ratio: float) -> tuple[np.ndarray, np.ndarray]:
    """(sigma_r, sigma_z) [Pa] on the axis r = 0 below a Hertz pressure p0 sqrt(1 - r^2/a^2) at
    depths z [m] (Johnson, *Contact Mechanics*, Eq. 3.45; tension positive):

        sigma_r = p0 [ -(1 + nu) (1 - (z/a) atan(a/z)) + 1 / (2 (1 + z^2/a^2)) ]
        sigma_z = -p0 / (1 + z^2/a^2)

    The principal shear |sigma_z - sigma_r|/2 peaks at 0.31 p0 at z = 0.48 a for nu = 0.3.
    """
    z = np.asarray(depth, dtype=float) / contact_radius
    with np.errstate(divide="ignore"):
        ratio = np.where(z > 0, z * np.arctan(1.0 / np.where(z > 0, z, 1.0)), 0.0)
    sigma_r = peak_pressure * (-(1 + poisson_ratio) * (1 - ratio) + 0.5 / (1 + z**2))
    return sigma_r, -peak_pressure / (1 + z**2)


# --- Hunter (1961): a rigid cylinder sliding (rolling) steadily on a standard linear solid ----------

@dataclass(frozen=True)
class HunterCylinder:
    """The steady contact of a rigid cylinder moving at constant speed on a standard linear solid in
    plane strain (:func:`hunter_cylinder`): the isolated cylinder, no images, frictionless.

    Attributes: ``trailing_edge`` -b and ``leading_edge`` a' [m] of the contact (the cylinder moves
    towards +x, so the leading edge is the one at +x), ``load`` W [N/m], ``mu_app`` = int p x dx / (R W)
    [-] (the resistance F_T / W: the pressure on the cylinder's slope x / R), ``coefficients`` f_n [Pa]
    (n = 0, 1, ...) of the pressure p = sum_n f_n sin(n theta) on x = c + h cos(theta)."""

    trailing_edge: float
    leading_edge: float
    load: float
    mu_app: float
    coefficients: np.ndarray

    @property
    def centre(self) -> float:
        """c = (a' - b) / 2 [m], the contact's centre (ahead of the axis: c > 0)."""
        return 0.5 * (self.leading_edge + self.trailing_edge)

    @property
    def half_width(self) -> float:
        """h = (a' + b) / 2 [m], the contact's half-width."""
        return 0.5 * (self.leading_edge - self.trailing_edge)

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """p(x) = sum_n f_n sin(n theta), cos(theta) = (x - c) / h, inside the contact; 0 outside [Pa]."""
        x = np.asarray(x, dtype=float)
        t = (x - self.centre) / self.half_width
        inside = np.abs(t) < 1.0
        theta = np.arccos(np.clip(t[inside], -1.0, 1.0))
        out = np.zeros_like(x)
        n = np.arange(self.coefficients.size)
        out[inside] = np.sin(np.multiply.outer(theta, n)) @ self.coefficients
        return out


def hunter_cylinder(load: float, cylinder_radius: float, shear_modulus_instantaneous: float,
                    shear_modulus_long_term: float, retardation_time: float, poisson_ratio: float,
                    speed: float) -> HunterCylinder:
    """Hunter's (1961) isolated rigid cylinder moving steadily on a standard linear solid.

    S. C. Hunter, "The rolling contact of a rigid cylinder with a viscoelastic half space", J. Appl.
    Mech. 28 (1961) 611-617, poses the problem (frictionless, plane strain, one retardation time) and
    reduces it to a singular integral equation over the contact (-b, a') whose solution involves the
    modified Bessel functions of the contact's half-width; the equations below are re-derived here
    (not transcribed) and solved in closed form up to one numerical root, the contact's half-width.

    The body: J(t) = J_0 + (J_inf - J_0)(1 - exp(-t/tau)) with J = 1/G [1/Pa] (``retardation_time``
    tau [s], G(0) = ``shear_modulus_instantaneous``, G(inf) = ``shear_modulus_long_term`` [Pa]) and a
    constant nu: the compliance of the contact is (1 - nu) J(t) / 2 (1/E* elastic). The cylinder
    (radius R [m], gap x^2/2R, load W [N/m]) moves at v [m/s] towards +x; a material point now at x
    was at x + xi a time xi/v ago, L = v tau [m]. With H(x) = (1/pi) PV int p(s)/(x - s) ds [Pa], the
    surface slope is (Johnson, *Contact Mechanics*, 1985, Eq. 2.25b, and the hereditary integral)

        w'(x) = -(1 - nu) [ J_0 H(x) + (J_inf - J_0) Psi(x) ],  Psi(x) = int_0^inf exp(-u) H(x + L u) du,

    and in the contact w' = -x/R. Since Psi - L Psi' = H, the operator (1 - L d/dx) turns this into a
    first-order differential relation for H inside the contact,

        J_inf H - L J_0 H' = (x - L) / ((1 - nu) R),

    so H(x) = A x + B + C exp(lambda x) there, with A = G(inf) / ((1 - nu) R) (relaxed Hertz),
    B = -A L (1 - G(inf)/G(0)), lambda = G(0) / (G(inf) L), and C a constant: Hunter's airfoil
    equation with an exponential right-hand side. On x = c + h t = c + h cos(theta) the pressure
    bounded (zero) at both edges is p = sum_{n>=1} f_n sin(n theta) = sqrt(1 - t^2) sum f_n U_{n-1}(t),
    f_n the Chebyshev coefficients of the right-hand side (the finite Hilbert transform maps
    sqrt(1 - t^2) U_{n-1} to T_n; Muskhelishvili's bounded solution). With exp(lambda (c + h t)) =
    exp(lambda c) [I_0(z) + 2 sum_n I_n(z) T_n(t)], z = lambda h, and K = C exp(lambda c):

        f_0 = A c + B + K I_0(z) = 0           (the solvability condition: p bounded at both edges),
        f_1 = A h + 2 K I_1(z),   f_n = 2 K I_n(z) (n >= 2),
        W = (pi h / 2) f_1,   int p x dx = c W + (pi h^2 / 4) f_2,   mu_app = int p x dx / (R W).

    Given h, the load and the solvability condition give A c + B and K in closed form; the constant
    C lost by (1 - L d/dx) is fixed by the slope condition at the leading edge a' = c + h (a homogeneous
    term exp(x/L) in w' + x/R vanishes iff it vanishes there), which needs H ahead of the contact only:
    there H = sum_n f_n r^n, r = t - sqrt(t^2 - 1) (t > 1), and Psi(a') = int_0^inf exp(-s^2) 2 s
    H(a' + L s^2) ds is one smooth quadrature (scipy.integrate.quad). That leading-edge equation in
    h is solved by Brent's method between the instantaneous and the relaxed Hertz half-widths.
    Ratios I_n(z) / I_0(z) come from the exponentially scaled Bessel functions (scipy.special.ive), so
    slow speeds (z ~ 1e5) neither overflow nor lose the series (~12 sqrt(z) terms).

    Limits: v tau -> 0 and v tau -> inf give Hertz's line contact (:func:`hertz_line_from_load`) with
    G(inf) and G(0), mu_app -> 0; in between the contact shifts ahead (c > 0). mu_app R / a0 and the
    edges over a0 (a0 the Hertz half-width with G(0)) depend on v tau / a0 and G(0)/G(inf) alone;
    for G(0)/G(inf) = 10, mu_app R / a0 peaks at 1.527 at v tau / a0 = 4.27.

    Parameters: ``load`` W [N/m], ``cylinder_radius`` R [m], the moduli [Pa], ``retardation_time``
    tau [s], ``poisson_ratio`` nu [-], ``speed`` v > 0 [m/s]. Returns a :class:`HunterCylinder`.
    """
    from scipy.integrate import quad
    from scipy.optimize import brentq
    from scipy.special import ive

    g0, g_inf = float(shear_modulus_instantaneous), float(shear_modulus_long_term)
    if not (g0 >= g_inf > 0.0 and speed > 0.0 and retardation_time > 0.0):
        raise ValueError("hunter_cylinder needs G(0) >= G(inf) > 0, a speed > 0 and a retardation time > 0")
    length = speed * retardation_time
    slope_scale = (1.0 - poisson_ratio) * cylinder_radius
    a_coef = g_inf / slope_scale
    b_coef = -a_coef * length * (1.0 - g_inf / g0)
    lam = g0 / (g_inf * length)

    def coefficients(h: float) -> tuple[float, np.ndarray]:
        z = lam * h
        ratio = ive(np.arange(int(60 + 12 * np.sqrt(z)) + 1), z) / ive(0, z)  # I_n(z) / I_0(z)
        linear = (a_coef * h - 2.0 * load / (np.pi * h)) / (2.0 * ratio[1])  # A c + B, from the load
        f = -2.0 * linear * ratio  # 2 K I_n, K = -(A c + B) / I_0
        f[0] = 0.0
        f[1] += a_coef * h
        return (linear - b_coef) / a_coef, f

    def leading_edge_residual(h: float) -> float:
        c, f = coefficients(h)
        n = np.arange(f.size)

        def ahead(s: float) -> float:  # H(a' + L s^2) s exp(-s^2) 2
            t = 1.0 + length * s * s / h
            return 2.0 * s * np.exp(-s * s) * float(f @ (t - np.sqrt(t * t - 1.0)) ** n)

        psi = quad(ahead, 0.0, np.inf, limit=400, epsabs=1e-13 * float(np.abs(f).sum()), epsrel=1e-12)[0]
        slope = (1.0 / g0) * f.sum() + (1.0 / g_inf - 1.0 / g0) * psi  # H(a') = sum f_n
        return (slope - (c + h) / slope_scale) * slope_scale / h

    e_star0 = contact_modulus(g0, poisson_ratio)
    a0 = hertz_line_half_width(load, cylinder_radius, e_star0)
    a_inf = a0 * np.sqrt(g0 / g_inf)
    h = brentq(leading_edge_residual, 0.95 * a0, 1.05 * a_inf, xtol=1e-14 * a0, rtol=1e-13)
    c, f = coefficients(h)
    moment = c * load + np.pi * h * h / 4.0 * f[2]
    return HunterCylinder(float(c - h), float(c + h), float(load), float(moment / (cylinder_radius * load)), f)
