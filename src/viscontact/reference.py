"""Analytic reference solutions (Hertz, Lee & Radok, Cattaneo-Mindlin) used to validate and normalise.

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
