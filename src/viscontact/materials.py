"""Linear viscoelastic materials: Prony shear relaxation modulus and its exact creep compliance.

The half-space is isotropic with a constant Poisson ratio nu, so every surface influence
coefficient is proportional to the shear creep compliance J(t) (correspondence principle). The
material is given by its shear relaxation modulus (seed Eq. 4, generalized Maxwell / Wiechert)

    G(t) = g_inf + sum_i g_i exp(-t / tau_i)                                  [Pa]

and the shear creep compliance follows exactly from the Laplace relation J^(s) G^(s) = 1/s^2
(seed Eq. 3):

    J(t) = J_0 + sum_m J_m (1 - exp(-t / lambda_m))                            [1/Pa]

where J_0 = 1/G(0), J_inf = 1/g_inf, and the retardation times lambda_m are the negative
reciprocals of the roots of s G^(s) (a polynomial of degree n in s after clearing denominators).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.polynomial import polynomial as P

from .errors import ParameterError


@dataclass(frozen=True)
class CreepSpectrum:
    """J(t) = J_0 + sum_m J_m (1 - exp(-t/lambda_m)); all J in 1/Pa, lambda in s."""

    instantaneous: float
    amplitudes: np.ndarray
    retardation_times: np.ndarray

    @property
    def long_term(self) -> float:
        """J_inf = J_0 + sum_m J_m [1/Pa]."""
        return float(self.instantaneous + self.amplitudes.sum())

    def compliance(self, t: np.ndarray | float) -> np.ndarray:
        """J(t) [1/Pa] at times ``t`` [s]."""
        t = np.asarray(t, dtype=float)
        out = np.full(t.shape, self.instantaneous)
        for jm, lm in zip(self.amplitudes, self.retardation_times):
            out = out + jm * (-np.expm1(-t / lm))
        return out


@dataclass(frozen=True)
class Material:
    """Isotropic linear viscoelastic material with constant Poisson ratio.

    Use :meth:`elastic`, :meth:`zener` or :meth:`prony` to build one.

    Parameters
    ----------
    g_inf
        Long-term shear modulus G(inf) [Pa], > 0.
    g
        Prony shear moduli g_i [Pa], each > 0.
    tau
        Relaxation times tau_i [s], each > 0.
    poisson_ratio
        nu in [0, 0.5].
    """

    g_inf: float
    g: tuple[float, ...] = ()
    tau: tuple[float, ...] = ()
    poisson_ratio: float = 0.3
    name: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        nu = self.poisson_ratio
        if not (np.isfinite(nu) and 0.0 <= nu <= 0.5):
            raise ParameterError("material.poisson_ratio", f"must be in [0, 0.5], got {nu}")
        if not (np.isfinite(self.g_inf) and self.g_inf > 0):
            raise ParameterError("material.g_inf", f"long-term shear modulus must be > 0 Pa, got {self.g_inf}")
        if len(self.g) != len(self.tau):
            raise ParameterError("material.g", f"g and tau must have the same length ({len(self.g)} != {len(self.tau)})")
        for gi in self.g:
            if not (np.isfinite(gi) and gi > 0):
                raise ParameterError("material.g", f"Prony moduli must be > 0 Pa, got {gi}")
        for ti in self.tau:
            if not (np.isfinite(ti) and ti > 0):
                raise ParameterError("material.tau", f"relaxation times must be > 0 s, got {ti}")

    # --- constructors ---------------------------------------------------------------------
    @classmethod
    def elastic(cls, shear_modulus: float, poisson_ratio: float) -> "Material":
        """Elastic material, G(t) = shear_modulus [Pa]."""
        if not (np.isfinite(shear_modulus) and shear_modulus > 0):
            raise ParameterError("material.shear_modulus", f"must be > 0 Pa, got {shear_modulus}")
        return cls(float(shear_modulus), (), (), float(poisson_ratio), name="elastic")

    @classmethod
    def zener(cls, shear_modulus_instantaneous: float, shear_modulus_long_term: float,
              retardation_time: float, poisson_ratio: float) -> "Material":
        """Standard linear solid from G(0), G(inf) [Pa] and its retardation (creep) time [s].

        The relaxation time is retardation_time * G(inf) / G(0) (seed Eqs. 13-14).
        """
        g0, ginf, lam = shear_modulus_instantaneous, shear_modulus_long_term, retardation_time
        if not (np.isfinite(g0) and g0 > 0):
            raise ParameterError("material.shear_modulus_instantaneous", f"must be > 0 Pa, got {g0}")
        if not (np.isfinite(ginf) and ginf > 0):
            raise ParameterError("material.shear_modulus_long_term", f"must be > 0 Pa, got {ginf}")
        if ginf > g0:
            raise ParameterError("material.shear_modulus_long_term",
                                 f"must be <= shear_modulus_instantaneous ({g0} Pa), got {ginf}")
        if not (np.isfinite(lam) and lam > 0):
            raise ParameterError("material.retardation_time", f"must be > 0 s, got {lam}")
        if ginf == g0:
            return cls.elastic(g0, poisson_ratio)
        return cls(float(ginf), (float(g0 - ginf),), (float(lam * ginf / g0),), float(poisson_ratio),
                   name="zener")

    @classmethod
    def prony(cls, g_inf: float, g: list[float] | tuple[float, ...], tau: list[float] | tuple[float, ...],
              poisson_ratio: float) -> "Material":
        """Generalized Maxwell (Wiechert) material, seed Eq. 4."""
        return cls(float(g_inf), tuple(float(x) for x in g), tuple(float(x) for x in tau),
                   float(poisson_ratio), name="prony")

    # --- moduli ---------------------------------------------------------------------------
    @property
    def shear_modulus_instantaneous(self) -> float:
        """G(0) [Pa]."""
        return float(self.g_inf + sum(self.g))

    @property
    def shear_modulus_long_term(self) -> float:
        """G(inf) [Pa]."""
        return float(self.g_inf)

    @property
    def is_elastic(self) -> bool:
        return len(self.g) == 0

    def relaxation_modulus(self, t: np.ndarray | float) -> np.ndarray:
        """G(t) [Pa] (seed Eq. 4)."""
        t = np.asarray(t, dtype=float)
        out = np.full(t.shape, self.g_inf)
        for gi, ti in zip(self.g, self.tau):
            out = out + gi * np.exp(-t / ti)
        return out

    def storage_modulus(self, omega: np.ndarray | float) -> np.ndarray:
        """G'(omega) [Pa] for angular frequency omega [rad/s]."""
        w = np.asarray(omega, dtype=float)
        out = np.full(w.shape, self.g_inf)
        for gi, ti in zip(self.g, self.tau):
            out = out + gi * (w * ti) ** 2 / (1 + (w * ti) ** 2)
        return out

    def loss_modulus(self, omega: np.ndarray | float) -> np.ndarray:
        """G''(omega) [Pa] for angular frequency omega [rad/s]."""
        w = np.asarray(omega, dtype=float)
        out = np.zeros(w.shape)
        for gi, ti in zip(self.g, self.tau):
            out = out + gi * (w * ti) / (1 + (w * ti) ** 2)
        return out

    # --- compliance -----------------------------------------------------------------------
    @cached_property
    def creep(self) -> CreepSpectrum:
        """Exact creep spectrum from J^(s) G^(s) = 1/s^2 (seed Eq. 3).

        s G^(s) = g_inf + sum_i g_i s / (s + 1/tau_i) = N(s) / D(s) with D = prod_i (s + 1/tau_i).
        J^(s) = D(s) / (s N(s)); its poles s_m = -1/lambda_m are the roots of N, and the residue
        there is -J_m, so J_m = -D(s_m) / (s_m N'(s_m)).
        """
        if self.is_elastic:
            return CreepSpectrum(1.0 / self.g_inf, np.zeros(0), np.zeros(0))
        rates = 1.0 / np.asarray(self.tau)
        denominator = P.polyfromroots(-rates)
        numerator = self.g_inf * denominator
        for i, gi in enumerate(self.g):
            others = P.polyfromroots(-np.delete(rates, i))
            numerator = P.polyadd(numerator, gi * P.polymulx(others))
        roots = P.polyroots(numerator)
        if np.max(np.abs(roots.imag)) > 1e-9 * np.max(np.abs(roots)):
            raise ParameterError("material", "creep spectrum has complex retardation rates (invalid Prony series)")
        roots = np.sort(roots.real)
        d_num = P.polyder(numerator)
        amplitudes = -P.polyval(roots, denominator) / (roots * P.polyval(roots, d_num))
        lam = -1.0 / roots
        order = np.argsort(lam)
        return CreepSpectrum(1.0 / self.shear_modulus_instantaneous, amplitudes[order], lam[order])

    def creep_compliance(self, t: np.ndarray | float) -> np.ndarray:
        """J(t) [1/Pa] (:meth:`CreepSpectrum.compliance` of :attr:`creep`)."""
        return self.creep.compliance(t)

    @property
    def shortest_time(self) -> float:
        """Shortest relaxation or retardation time [s] (inf for an elastic material)."""
        times = list(self.tau) + list(self.creep.retardation_times)
        return float(min(times)) if times else float("inf")

    def reduced_modulus(self, t: float = 0.0) -> float:
        """Contact modulus E* = 2 G(t) / (1 - nu) [Pa] of the half-space against a rigid body."""
        return float(2.0 * self.relaxation_modulus(t) / (1.0 - self.poisson_ratio))
