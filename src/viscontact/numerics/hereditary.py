"""Exact hereditary integrals of a piecewise-linear history against a sum of exponentials.

y(t_j) = int_0^t_j K(t_j - s) df(s) for K(t) = K_inf + sum_i A_i exp(-t / T_i) on uniform times, by the
recursion over the exponentials of seed Eq. 6 (exact for an f linear between its samples): the
reference of the one-point time-step estimate (:mod:`viscontact.solvers.time_step_error`) and the
creep of a held load (:func:`viscontact.running.guards.contact_estimate`).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["exponential_filter", "hereditary_integral"]


def hereditary_integral(kernel_inf: float, amplitudes: np.ndarray, times: np.ndarray, f: np.ndarray,
                        h: float) -> np.ndarray:
    """y(t_j) = int_0^t_j K(t_j - s) df(s) [units of K x f] on the uniform times t_j = j h, for
    K(t) = kernel_inf + sum_i amplitudes_i exp(-t / times_i) and f linear between its samples ``f``
    with a step of f[0] at t = 0. Exact for that f (recursion over the exponentials, seed Eq. 6)."""
    y = kernel_inf * f
    slope = np.diff(f, prepend=f[0]) / h
    for amplitude, time in zip(np.atleast_1d(amplitudes), np.atleast_1d(times)):
        drive = slope * time * -math.expm1(-h / time)
        drive[0] = f[0]
        y = y + amplitude * exponential_filter(drive, h / time)
    return y


def exponential_filter(drive: np.ndarray, rate: float) -> np.ndarray:
    """y_j = exp(-rate) y_(j-1) + drive_j (y_(-1) = 0), vectorised in blocks short enough for
    exp(rate k) not to overflow: y_(s+k) = exp(-rate k) (exp(-rate) y_(s-1) + sum_i exp(rate i) drive_(s+i))."""
    out = np.empty_like(drive)
    block = max(1, min(drive.size, int(200.0 / max(rate, 1e-300))))
    carry = 0.0
    for start in range(0, drive.size, block):
        k = np.arange(min(block, drive.size - start))
        seg = np.exp(-rate * k) * (math.exp(-rate) * carry + np.cumsum(drive[start:start + k.size] * np.exp(rate * k)))
        out[start:start + k.size] = seg
        carry = seg[-1]
    return out
