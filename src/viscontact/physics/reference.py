"""Analytic reference solutions (Hertz, Lee & Radok, Cattaneo-Mindlin; Hertz's and Cattaneo's line
contacts) used to validate and normalise.

All functions take SI inputs and return SI outputs. ``shear_modulus`` is G, ``poisson_ratio`` nu; the
contact modulus of a rigid sphere on the half-space is E* = 2G/(1-nu).
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
    Eqs. 4.43-4.45 with a rigid cylinder): half-width a = sqrt(4 W R / (pi E*)) [m], peak pressure
    p0 = 2 W / (pi a) [Pa], p(x) = p0 sqrt(1 - x^2/a^2); the approach relative to the datum b [m]
    (:func:`line_approach`). The :class:`Hertz` returned holds a in ``radius`` and W [N/m] in ``load``."""
    e_star = contact_modulus(shear_modulus, poisson_ratio)
    a = np.sqrt(4.0 * load * cylinder_radius / (np.pi * e_star))
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
