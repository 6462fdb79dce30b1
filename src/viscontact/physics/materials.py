"""Linear viscoelastic materials: Prony shear relaxation modulus and its exact creep compliance.

The half-space is isotropic with a constant Poisson ratio nu, so every surface influence
coefficient is proportional to the shear creep compliance J(t) (correspondence principle). The
material is given by its shear relaxation modulus (seed Eq. 4, generalized Maxwell / Wiechert)

    G(t) = g_inf + sum_i g_i exp(-t / tau_i)                                  [Pa]

and the shear creep compliance follows exactly from the Laplace relation J^(s) G^(s) = 1/s^2
(seed Eq. 3):

    J(t) = J_0 + sum_m J_m (1 - exp(-t / lambda_m))                            [1/Pa]

where J_0 = 1/G(0), J_inf = 1/g_inf, and the retardation times lambda_m are the negative
reciprocals of the roots of s G^(s). Those roots interlace with the relaxation rates 1/tau_i, one
in each gap, so each is found by bracketed root finding on the secular equation (see
:meth:`Material.creep`, :mod:`viscontact.physics.prony`); this stays accurate for 40 terms over 15 decades, where the roots of the
expanded polynomial do not.

Time-temperature superposition (Williams, Landel & Ferry 1955): at temperature T every
relaxation time is tau_i(T) = a_T tau_i(T_ref) with log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)
(:func:`wlf_shift_factor`, :meth:`Material.shifted`).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from viscontact.errors import ParameterError
from viscontact.numerics.exponentials import CreepSpectrum
from viscontact.physics.prony import prony_creep_spectrum

#: multipliers of the modulus units of a Prony table (Pa, kPa, MPa, GPa) to Pa
MODULUS_UNITS = {"Pa": 1.0, "kPa": 1.0e3, "MPa": 1.0e6, "GPa": 1.0e9}


def shear_from_tensile(tensile_modulus: float | np.ndarray, poisson_ratio: float) -> float | np.ndarray:
    """G = E / (2 (1 + nu)) [Pa] of an isotropic material with constant Poisson ratio nu."""
    return tensile_modulus / (2.0 * (1.0 + poisson_ratio))


def wlf_shift_factor(temperature: float, reference_temperature: float, c1: float, c2: float) -> float:
    """WLF shift factor a_T = 10^(-C1 (T - T_ref) / (C2 + T - T_ref)) [-].

    Every relaxation (and retardation) time at T is a_T times its value at T_ref (Williams, Landel
    & Ferry, J. Am. Chem. Soc. 77, 3701, 1955). The formula diverges at T - T_ref = -C2: below
    that it is meaningless, and :class:`ParameterError` says so.

    Parameters
    ----------
    temperature, reference_temperature
        T and T_ref [deg C].
    c1
        C1 [-].
    c2
        C2 [deg C].
    """
    d_t = temperature - reference_temperature
    if not c2 + d_t > 0:
        raise ParameterError("material.temperature",
                             f"T - reference_temperature = {d_t:g} degC must be > -wlf_c2 = {-c2:g} degC "
                             f"(the WLF equation diverges at T = reference_temperature - wlf_c2 = "
                             f"{reference_temperature - c2:g} degC), got temperature = {temperature:g} degC")
    log_a = -c1 * d_t / (c2 + d_t)
    if not abs(log_a) < 300:
        raise ParameterError("material.temperature",
                             f"WLF shift factor 10^{log_a:.4g} at temperature = {temperature:g} degC is out of "
                             f"floating-point range; move temperature closer to reference_temperature "
                             f"= {reference_temperature:g} degC")
    return float(10.0 ** log_a)


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
    shift_factor
        Time-temperature shift factor a_T [-] already applied to ``tau`` (1 at the reference
        temperature); recorded for the results, see :meth:`shifted`.
    """

    g_inf: float
    g: tuple[float, ...] = ()
    tau: tuple[float, ...] = ()
    poisson_ratio: float = 0.3
    name: str = field(default="", compare=False)
    shift_factor: float = 1.0

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
        if not (np.isfinite(self.shift_factor) and self.shift_factor > 0):
            raise ParameterError("material.temperature", f"shift factor a_T must be > 0, got {self.shift_factor}")

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

    def shifted(self, shift_factor: float) -> "Material":
        """The material with every relaxation time multiplied by ``shift_factor`` a_T [-]
        (time-temperature superposition, :func:`wlf_shift_factor`); moduli unchanged."""
        if shift_factor == 1.0:
            return self
        return replace(self, tau=tuple(float(t * shift_factor) for t in self.tau),
                       shift_factor=float(self.shift_factor * shift_factor))

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

        s G^(s) = g_inf + sum_i g_i s / (s + 1/tau_i); J^(s) = 1/(s * sG^(s)) has its poles
        s_m = -1/lambda_m at the zeros of sG^(s), one between each pair of neighbouring
        relaxation rates and one below the smallest, and the residue there is -J_m
        (:func:`viscontact.physics.prony.prony_creep_spectrum`, which merges terms of equal relaxation times).
        """
        if self.is_elastic:
            return CreepSpectrum(1.0 / self.g_inf, np.zeros(0), np.zeros(0))
        spectrum = prony_creep_spectrum(self.g_inf, np.asarray(self.g, dtype=float), np.asarray(self.tau, dtype=float))
        return CreepSpectrum(1.0 / self.shear_modulus_instantaneous, spectrum.amplitudes, spectrum.retardation_times)

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
