"""The Prony series' creep spectra: the inversion of a shear relaxation modulus
G(t) = g_inf + sum_i g_i exp(-t / tau_i) [Pa] into exact sums of exponentials
J0 + sum_m J_m (1 - exp(-t / lambda_m)) [1/Pa], by the roots of a secular equation.

The retardation rates 1/lambda_m are the roots of G~(s) = -c (G~(s) = s G^(s), the Carson transform;
c = 0 for the shear creep compliance J(t) of seed Eq. 3, c = 3K for the creep function L(t) of the
bulk-elastic material, :mod:`viscontact.bodies.bulk_elastic`). With r_i = 1/tau_i,
G~(s) = G(0) - sum_i g_i r_i / (s + r_i) increases between its poles -r_i, so exactly one root lies in
each interval (-r_{i+1}, -r_i) and one in (-r_1, 0). Each root is found relative to the nearer end of
its interval (as LAPACK's dlaed4 does), so the rates keep full relative accuracy over many decades,
where the roots of the expanded polynomial do not. The amplitude of a root s_m = -rho_m is the
residue J_m = 1 / (rho_m G~'(s_m)).

One root finder solves it for every caller: bisection on each root's bracket, vectorised over many
shifts c at once (:func:`secular_roots`, 110 halvings: to the last bits of the offset from the nearer
pole), through :func:`prony_creep_spectra` / :func:`prony_creep_spectrum`: the shear creep compliance
of :attr:`viscontact.physics.materials.Material.creep` (c = 0) and the bulk-elastic and layered
bodies' creep functions. It needs nothing of ``scipy.optimize`` (which with ``scipy.linalg``,
``.sparse`` and ``.spatial`` would add about 23 MiB to a run).
"""
from __future__ import annotations

import numpy as np

from viscontact.numerics.exponentials import CreepSpectrum

__all__ = ["prony_creep_spectra", "prony_creep_spectrum", "secular_roots"]


def secular_roots(rates: np.ndarray, weights: np.ndarray, levels: np.ndarray, m: int,
                   iterations: int = 110) -> tuple[np.ndarray, np.ndarray]:
    """Roots of level - sum_i w_i / (s + r_i) = 0 in (-r_m, -r_{m-1}) (r_{-1} = 0) for each of
    ``levels`` (S,); ``rates`` ascending. Returns rho = -s [1/s] and sum_i w_i / (s + r_i)^2 [Pa s],
    each (S,).

    The root is sought relative to the nearer end of its interval (decided by the sign at the
    midpoint): near a pole k, s = -r_k + delta and h(delta) = delta f(s) = delta (level -
    sum_{i != k} w_i / (r_i - r_k + delta)) - w_k, finite at delta = 0; near s = 0 (m = 0), f itself.
    Bisection on that bracket (``iterations`` halvings, vectorised over the levels) keeps full
    relative accuracy however close the root is to the pole.
    """
    levels = np.asarray(levels, dtype=float)
    lo_rate = rates[m - 1] if m > 0 else 0.0
    mid_rate = 0.5 * (rates[m] + lo_rate)
    f_mid = levels - np.sum(weights / (rates - mid_rate))
    direct = (f_mid <= 0.0) & (m == 0)                  # root in (-r_0/2, 0): no pole nearby
    origin = np.where(f_mid > 0.0, m, max(m - 1, 0))     # the nearer pole otherwise
    origin_rate = np.where(direct, 0.0, rates[origin])
    gaps = rates[None, :] - origin_rate[:, None]          # r_i - r_k (S, n)
    others = direct[:, None] | (np.arange(rates.size)[None, :] != origin[:, None])
    w_origin = np.where(direct, 0.0, weights[origin])

    def value(delta: np.ndarray) -> np.ndarray:
        denom = np.where(others, gaps + delta[:, None], 1.0)
        rest = levels - np.sum(np.where(others, weights[None, :] / denom, 0.0), axis=1)
        return np.where(direct, -rest, delta * rest - w_origin)

    # bracket: value(neg) < 0 (delta = 0), value(pos) >= 0 (delta at the midpoint)
    neg = np.zeros_like(levels)
    pos = origin_rate - mid_rate
    for _ in range(iterations):
        mid = 0.5 * (neg + pos)
        below = value(mid) < 0.0
        neg = np.where(below, mid, neg)
        pos = np.where(below, pos, mid)
    delta = 0.5 * (neg + pos)
    diffs = gaps + delta[:, None]
    return origin_rate - delta, np.sum(weights[None, :] / diffs**2, axis=1)


def prony_creep_spectra(g_inf: float, g: np.ndarray | tuple[float, ...], tau: np.ndarray | tuple[float, ...],
                        shifts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`prony_creep_spectrum` for many ``shifts`` (S,) [Pa] at once: returns the instantaneous
    values (S,) [1/Pa], amplitudes (S, M) [1/Pa] and retardation times (S, M) [s], ascending in
    time along each row (M distinct relaxation times; an infinite shift gives zeros, times 1 s)."""
    shifts = np.asarray(shifts, dtype=float)
    g = np.asarray(g, dtype=float)
    rates, inverse = np.unique(1.0 / np.asarray(tau, dtype=float), return_inverse=True)
    moduli = np.zeros(rates.size)
    np.add.at(moduli, inverse, g)
    finite = np.isfinite(shifts)
    levels = g_inf + float(moduli.sum()) + np.where(finite, shifts, 0.0)
    weights = moduli * rates
    rho = np.empty((shifts.size, rates.size))
    amps = np.empty_like(rho)
    for m in range(rates.size):
        rho[:, m], slope = secular_roots(rates, weights, levels, m)
        amps[:, m] = 1.0 / (rho[:, m] * slope)
    times = 1.0 / rho[:, ::-1]  # rates descending in m -> times ascending
    amps = amps[:, ::-1]
    return (np.where(finite, 1.0 / levels, 0.0), np.where(finite[:, None], amps, 0.0),
            np.where(finite[:, None], times, 1.0))


def prony_creep_spectrum(g_inf: float, g: np.ndarray | tuple[float, ...], tau: np.ndarray | tuple[float, ...],
                         shift: float = 0.0) -> CreepSpectrum:
    """Creep function whose Carson transform is 1 / (G~(s) + shift), for the Prony modulus
    G(t) = g_inf + sum_i g_i exp(-t/tau_i) [Pa] and a constant ``shift`` [Pa] >= 0.

    ``shift = 0`` gives the shear creep compliance J(t) (seed Eq. 3); ``shift = 3K`` the function
    L(t) of the module docstring. ``shift = inf`` gives L = 0. Equal relaxation times are merged.
    Returns a :class:`~viscontact.numerics.exponentials.CreepSpectrum` with retardation times ascending.
    """
    if np.isinf(shift):
        return CreepSpectrum(0.0, np.zeros(0), np.zeros(0))
    inst, amps, times = prony_creep_spectra(g_inf, g, tau, np.array([shift]))
    return CreepSpectrum(float(inst[0]), amps[0], times[0])
