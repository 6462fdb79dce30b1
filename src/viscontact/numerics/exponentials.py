"""Sums of decaying exponentials: the time responses of linear viscoelasticity.

A creep function (a compliance [1/Pa]) is phi(t) = J_0 + sum_m J_m (1 - exp(-t/lambda_m)): its
instantaneous value J_0, the amplitudes J_m and the retardation times lambda_m [s]. The Prony series
of a material turns into one (:mod:`viscontact.physics.prony`); the hereditary histories
(:mod:`viscontact.numerics.history`) and time schemes (:mod:`viscontact.numerics.schemes`) integrate
it; its Laplace-Carson transform and complex compliance give the steady sliding operators.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable

import numpy as np


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


def carson_transform(spectrum: CreepSpectrum, s: np.ndarray | float) -> np.ndarray:
    """s phi^(s) = phi(inf) - sum_m J_m s / (s + 1/lambda_m) [1/Pa] at Laplace variables s [1/s]."""
    s = np.asarray(s, dtype=complex if np.iscomplexobj(s) else float)
    out = np.full(s.shape, spectrum.long_term, dtype=s.dtype)
    for jm, lm in zip(spectrum.amplitudes, spectrum.retardation_times):
        out = out - jm * s / (s + 1.0 / lm)
    return out


def linear_combination(parts: Iterable[tuple[float, CreepSpectrum]]) -> CreepSpectrum:
    """sum_k c_k phi_k as one spectrum (amplitudes of equal retardation times added, zeros dropped,
    times sorted ascending)."""
    inst = 0.0
    amps: list[np.ndarray] = []
    times: list[np.ndarray] = []
    for coef, spec in parts:
        if coef == 0.0:
            continue
        inst += coef * spec.instantaneous
        amps.append(coef * np.asarray(spec.amplitudes, dtype=float))
        times.append(np.asarray(spec.retardation_times, dtype=float))
    if not amps:
        return CreepSpectrum(0.0, np.zeros(0), np.zeros(0))
    a, lam = np.concatenate(amps), np.concatenate(times)
    uniq, inverse = np.unique(lam, return_inverse=True)
    summed = np.zeros(uniq.size)
    np.add.at(summed, inverse, a)
    keep = summed != 0.0
    return CreepSpectrum(float(inst), summed[keep], uniq[keep])


def complex_compliance(spectrum: CreepSpectrum, omega: np.ndarray | float) -> np.ndarray:
    """phi*(omega) = J_0 + sum_m J_m / (1 + i omega lambda_m) [1/Pa] at angular frequencies omega
    [rad/s] (exp(i omega t) convention): the Carson transform at s = i omega."""
    return carson_transform(spectrum, 1j * np.asarray(omega, dtype=float))
