"""Analytic references of adhesive contact: JKR, DMT, Maugis-Dugdale and Kendall's flat punch.

A rigid sphere of radius R (a paraboloid) or a rigid flat punch of radius a on an elastic half-space
of contact modulus E* = 2G/(1 - nu) [Pa], with the Dupre work of adhesion w [J/m^2]. Loads are
positive in compression and negative in tension [N]; the approach delta [m] is positive into the body.

* JKR (Johnson, Kendall & Roberts 1971; Johnson, *Contact Mechanics*, 1985, §5.5): short-range
  adhesion acting inside the contact only, a crack at its edge;
* DMT (Derjaguin, Muller & Toporov 1975): long-range adhesion outside a Hertzian contact;
* Maugis-Dugdale (Maugis 1992, J. Colloid Interface Sci. 150, 243; in the notation of Johnson &
  Greenwood 1997, J. Colloid Interface Sci. 192, 326): a constant tension sigma_0 over a ring
  a < r < c around the contact, whose range w / sigma_0 sets the Maugis parameter lambda; lambda -> 0
  is DMT, lambda -> infinity JKR;
* Kendall (1971, J. Phys. D 4, 1186): the pull-off force of a flat punch;
* the JKR line contact of a cylinder in plane strain (Barquins 1988; Chaudhury et al. 1996), per unit
  length: :func:`jkr_line_load`, :func:`jkr_line_pull_off`.

The Maugis-Dugdale curve is given parametrically by m = c/a (:func:`maugis_dugdale`): for each m
the dimensionless contact radius A is the positive root of a quadratic (Maugis 1992, Eq. 6.17), so
no root bracketing is needed, and the pull-off is the minimum of the load (load control) or of the
approach (displacement control) along the curve.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

Control = Literal["load", "displacement"]


def jkr_load(contact_radius: np.ndarray | float, sphere_radius: float, contact_modulus: float,
             work_of_adhesion: float) -> np.ndarray:
    """JKR load P(a) = 4 E* a^3 / (3R) - sqrt(8 pi w E* a^3) [N] at contact radii a [m]."""
    a = np.asarray(contact_radius, dtype=float)
    return 4.0 * contact_modulus * a**3 / (3.0 * sphere_radius) - np.sqrt(8.0 * np.pi * work_of_adhesion
                                                                          * contact_modulus * a**3)


def jkr_approach(contact_radius: np.ndarray | float, sphere_radius: float, contact_modulus: float,
                 work_of_adhesion: float) -> np.ndarray:
    """JKR approach delta(a) = a^2 / R - sqrt(2 pi w a / E*) [m] at contact radii a [m]."""
    a = np.asarray(contact_radius, dtype=float)
    return a**2 / sphere_radius - np.sqrt(2.0 * np.pi * work_of_adhesion * a / contact_modulus)


def jkr_pull_off(sphere_radius: float, work_of_adhesion: float, control: Control = "load") -> float:
    """JKR pull-off force [N]: -3/2 pi w R under load control, -5/6 pi w R under displacement control
    (where the approach, not the load, reaches its minimum)."""
    factor = {"load": 1.5, "displacement": 5.0 / 6.0}[control]
    return -factor * np.pi * work_of_adhesion * sphere_radius


def dmt_load(contact_radius: np.ndarray | float, sphere_radius: float, contact_modulus: float,
             work_of_adhesion: float) -> np.ndarray:
    """DMT load P(a) = 4 E* a^3 / (3R) - 2 pi w R [N] (Hertz's contact, delta = a^2 / R)."""
    a = np.asarray(contact_radius, dtype=float)
    return 4.0 * contact_modulus * a**3 / (3.0 * sphere_radius) - 2.0 * np.pi * work_of_adhesion * sphere_radius


def dmt_pull_off(sphere_radius: float, work_of_adhesion: float) -> float:
    """DMT pull-off force -2 pi w R [N]."""
    return -2.0 * np.pi * work_of_adhesion * sphere_radius


def kendall_pull_off(punch_radius: float, contact_modulus: float, work_of_adhesion: float) -> float:
    """Pull-off force of a rigid flat punch of radius a [m] stuck to the half-space, -sqrt(8 pi w E* a^3)
    [N] (Kendall 1971): the load at which the edge crack of the punch's contact grows."""
    return -float(np.sqrt(8.0 * np.pi * work_of_adhesion * contact_modulus * punch_radius**3))


def maugis_parameter(sphere_radius: float, contact_modulus: float, work_of_adhesion: float,
                     cohesive_stress: float) -> float:
    """lambda = 2 sigma_0 (R / (pi w K^2))^(1/3) [-], K = 4 E* / 3 (Maugis 1992; Johnson & Greenwood 1997)."""
    k = 4.0 * contact_modulus / 3.0
    return float(2.0 * cohesive_stress * (sphere_radius / (np.pi * work_of_adhesion * k**2)) ** (1.0 / 3.0))


def cohesive_zone_length(contact_modulus: float, work_of_adhesion: float, cohesive_stress: float) -> float:
    """Length c - a [m] of the Dugdale cohesive zone at the edge of a JKR-like contact,
    pi E* w / (4 sigma_0^2): the zone that carries K_I = sigma_0 sqrt(8 (c - a) / pi) with the energy
    release rate w = K_I^2 / (2 E*) of a crack between a rigid and an elastic body. The Maugis-Dugdale
    ring tends to it as lambda -> infinity (:func:`maugis_dugdale`); a grid must resolve it."""
    return float(np.pi * contact_modulus * work_of_adhesion / (4.0 * cohesive_stress**2))


@dataclass(frozen=True)
class MaugisDugdale:
    """Points of the Maugis-Dugdale curve (arrays of one shape): ``contact_radius`` a [m],
    ``cohesive_radius`` c [m] (the edge of the tension ring), ``load`` P [N], ``approach`` delta [m]."""

    contact_radius: np.ndarray
    cohesive_radius: np.ndarray
    load: np.ndarray
    approach: np.ndarray


def _dimensionless_curve(m: np.ndarray, lam: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(A, P/(pi w R), Delta) at ring ratios m = c/a > 1 for the Maugis parameter ``lam``.

    Maugis 1992 (Johnson & Greenwood 1997, Eqs. 7-9), with s = sqrt(m^2 - 1) and t = arctan s:

        (lam A^2 / 2) [s + (m^2 - 2) t] + (4 lam^2 A / 3) [s t - m + 1] = 1,
        P / (pi w R) = A^3 - lam A^2 [s + m^2 t],     Delta = A^2 - (4/3) lam A s,

    A = a (K / (pi w R^2))^(1/3), Delta = delta (K^2 / (pi^2 w^2 R))^(1/3), K = 4 E* / 3. The first is a
    quadratic alpha A^2 + beta A = 1 with alpha, beta >= 0, of one positive root."""
    m = np.asarray(m, dtype=float)
    s = np.sqrt(m * m - 1.0)
    t = np.arctan(s)
    alpha = 0.5 * lam * (s + (m * m - 2.0) * t)
    beta = 4.0 / 3.0 * lam * lam * (s * t - m + 1.0)
    # the positive root of alpha A^2 + beta A - 1 = 0, written to stay exact as alpha -> 0
    a = 2.0 / (beta + np.sqrt(beta * beta + 4.0 * alpha))
    return a, a**3 - lam * a * a * (s + m * m * t), a * a - 4.0 / 3.0 * lam * a * s


def _scales(sphere_radius: float, contact_modulus: float, work_of_adhesion: float) -> tuple[float, float, float]:
    """(radius [m], load [N], approach [m]) that make A, P, Delta dimensionless."""
    k = 4.0 * contact_modulus / 3.0
    w, r = work_of_adhesion, sphere_radius
    return (np.pi * w * r * r / k) ** (1.0 / 3.0), np.pi * w * r, (np.pi**2 * w * w * r / k**2) ** (1.0 / 3.0)


def maugis_dugdale(ring_ratio: np.ndarray | float, sphere_radius: float, contact_modulus: float,
                   work_of_adhesion: float, cohesive_stress: float) -> MaugisDugdale:
    """The Maugis-Dugdale curve at ring ratios m = c/a > 1 (small m: a JKR-like contact; large m: a
    DMT-like one) of a rigid sphere of radius R [m] on a body of contact modulus E* [Pa] with the work of
    adhesion w [J/m^2] and the cohesive stress sigma_0 [Pa] (:func:`_dimensionless_curve`)."""
    lam = maugis_parameter(sphere_radius, contact_modulus, work_of_adhesion, cohesive_stress)
    a, load, approach = _dimensionless_curve(np.asarray(ring_ratio, dtype=float), lam)
    radius_scale, load_scale, approach_scale = _scales(sphere_radius, contact_modulus, work_of_adhesion)
    m = np.asarray(ring_ratio, dtype=float)
    return MaugisDugdale(a * radius_scale, m * a * radius_scale, load * load_scale, approach * approach_scale)


def maugis_dugdale_pull_off(sphere_radius: float, contact_modulus: float, work_of_adhesion: float,
                            cohesive_stress: float, control: Control = "load") -> MaugisDugdale:
    """The point of the Maugis-Dugdale curve where the sphere comes off: the least load under load
    control, the least approach under displacement control (the load there is the pull-off force).
    Found on the curve's parameter log(m - 1), first on a grid of 400 points from 1e-12 to 1e8, then
    refined (Brent) about the grid's minimum; the grid follows the curve's minimum from the JKR limit
    (m - 1 ~ 1 / lambda^2) to the DMT limit (m large)."""
    from scipy.optimize import minimize_scalar  # imported where used: scipy.optimize weighs about 20 MiB

    lam = maugis_parameter(sphere_radius, contact_modulus, work_of_adhesion, cohesive_stress)
    pick = 1 if control == "load" else 2

    def value(log_gap: float) -> float:
        return float(_dimensionless_curve(1.0 + np.exp(log_gap), lam)[pick])

    grid = np.linspace(np.log(1e-12), np.log(1e8), 400)
    values = _dimensionless_curve(1.0 + np.exp(grid), lam)[pick]
    i = int(np.argmin(values))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    best = minimize_scalar(value, bounds=(lo, hi), method="bounded", options={"xatol": 1e-10})
    m = 1.0 + np.exp(best.x if best.fun <= values[i] else grid[i])
    return maugis_dugdale(m, sphere_radius, contact_modulus, work_of_adhesion, cohesive_stress)


def jkr_line_load(half_width: np.ndarray | float, cylinder_radius: float, contact_modulus: float,
                  work_of_adhesion: float) -> np.ndarray:
    """JKR line contact (a rigid cylinder of radius R on a half-space in plane strain; Barquins 1988,
    J. Adhesion 26, 1; Chaudhury, Weaver, Hui & Kramer 1996, J. Appl. Phys. 80, 30): the load per unit
    length P(a) = pi E* a^2 / (4R) - sqrt(2 pi E* w a) [N/m] at contact half-widths a [m].

    Hertz's line load pi E* a^2/(4R) less the load of a strip punch, P1 = sqrt(2 pi E* w a), whose edge
    singularity p ~ P1 / (pi sqrt(2a (a - |x|))) has the stress intensity K_I = P1 / sqrt(pi a) and
    the energy release rate K_I^2 / (2 E*) = w (the crack criterion at each edge)."""
    a = np.asarray(half_width, dtype=float)
    return np.pi * contact_modulus * a**2 / (4.0 * cylinder_radius) - np.sqrt(2.0 * np.pi * contact_modulus
                                                                              * work_of_adhesion * a)


def jkr_line_pull_off(cylinder_radius: float, contact_modulus: float, work_of_adhesion: float) -> tuple[float, float]:
    """(pull-off load [N/m], half-width [m]) of the JKR line contact under load control: dP/da = 0 at
    a_c = (2 w R^2 / (pi E*))^(1/3), where P_c = -(3/4) pi E* a_c^2 / R = -3 (pi E* R w^2 / 16)^(1/3)
    (:func:`jkr_line_load`)."""
    a_c = (2.0 * work_of_adhesion * cylinder_radius**2 / (np.pi * contact_modulus)) ** (1.0 / 3.0)
    return -3.0 * (np.pi * contact_modulus * cylinder_radius * work_of_adhesion**2 / 16.0) ** (1.0 / 3.0), float(a_c)
