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

Two root finders solve it, each kept for its callers' numbers (they agree to round-off, not bit for
bit):

* :func:`retardation_spectrum` -- one modulus, c = 0, Brent's method on each bracket (to 4 ulp;
  :func:`brent_root`, scipy's ``brentq`` step for step, without importing ``scipy.optimize``, a fifth of
  a run's memory): :attr:`viscontact.physics.materials.Material.creep`;
* :func:`prony_creep_spectra` / :func:`prony_creep_spectrum` -- many shifts c at once, bisection
  vectorised over them (:func:`secular_roots`, 110 halvings): the bulk-elastic and layered bodies'
  creep functions.
"""
from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from viscontact.numerics.exponentials import CreepSpectrum

__all__ = ["brent_root", "prony_creep_spectra", "prony_creep_spectrum", "retardation_spectrum", "secular_roots"]


def retardation_spectrum(g_inf: float, g: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Amplitudes J_m [1/Pa] and retardation times lambda_m [s] of G = g_inf + sum g_i exp(-t/tau_i).

    With r_i = 1/tau_i (ascending), G_0 = g_inf + sum g_i and w_i = g_i r_i / G_0, the retardation
    rates x_m = 1/lambda_m are the roots of the secular equation (s G^(s) = 0 at s = -x)

        f(x) = 1 - sum_i w_i / (r_i - x) = 0,

    decreasing between its poles, with exactly one root in (0, r_1) and one in each (r_i, r_{i+1}).
    Each root is bracketed and found in the offset delta = x - o from the nearer end o of its gap,
    with r_i - x = (r_i - o) - delta, so the distance to the nearest pole keeps full relative
    precision (as in LAPACK's dlaed4). The residue of J^(s) = 1/(s * sG^(s)) at s = -x_m gives
    J_m = 1 / (x_m G_0 sum_i w_i / (r_i - x_m)^2).
    """
    rates = 1.0 / tau
    order = np.argsort(rates)
    rates, g = rates[order], g[order]
    g0 = g_inf + g.sum()
    weights = g * rates / g0
    lows = np.concatenate([[0.0], rates[:-1]])
    amplitudes = np.empty(rates.size)
    retardation_rates = np.empty(rates.size)
    # the secular function is infinite at its poles: an end of a bracket within round-off of one (times
    # 1 ulp apart, times of 1e-300 s) overflows to inf, of the right sign (numpy's warning is noise)
    with np.errstate(over="ignore", divide="ignore"):
        for m, (lo, hi) in enumerate(zip(lows, rates)):
            mid = lo + 0.5 * (hi - lo)
            below = 1.0 - np.sum(weights / (rates - mid)) > 0  # f decreasing: root above mid
            origin = hi if below else lo
            diff = rates - origin

            def secular(delta: float) -> float:
                return 1.0 - float(np.sum(weights / (diff - delta)))

            span = mid - origin
            tiny = abs(span) * 1e-300 if (origin > 0) else 0.0
            a, b = (span, -tiny) if below else (tiny, span)
            if secular(a) * secular(b) > 0:  # the root sits within round-off of mid
                delta = span
            else:
                delta = brent_root(secular, a, b, xtol=abs(span) * 1e-300 + 1e-320, rtol=4 * np.finfo(float).eps,
                                   maxiter=400)
            gaps = diff - delta
            retardation_rates[m] = origin + delta
            amplitudes[m] = 1.0 / (retardation_rates[m] * g0 * np.sum(weights / gaps**2))
    lam = 1.0 / retardation_rates
    order = np.argsort(lam)
    return amplitudes[order], lam[order]


def brent_root(f: Callable[[float], float], a: float, b: float, *, xtol: float, rtol: float,
               maxiter: int = 100) -> float:
    """The root of ``f`` bracketed by [a, b] (f(a) f(b) <= 0) by Brent's method (Brent 1973, "Algorithms
    for minimization without derivatives", ch. 4), in the form of scipy's ``optimize.brentq`` (its C
    ``brentq``, C. Harris): each step inverse-quadratic interpolation, the secant or bisection, within
    (xtol + rtol |x|) / 2 of the root. The same arithmetic in the same order, so the same root to the
    last bit (tested against ``scipy.optimize.brentq``), without importing ``scipy.optimize`` (with
    ``scipy.linalg``, ``.sparse`` and ``.spatial`` it pulls in, about 23 MiB, a fifth of a run's peak
    memory at 256^2: BENCHMARKS.md).

    Raises
    ------
    ValueError
        f(a) and f(b) of the same sign.
    RuntimeError
        No convergence in ``maxiter`` steps.
    """
    # IEEE arithmetic as in C (an end at a pole gives f = inf: its quotients are inf or nan, not errors)
    with np.errstate(all="ignore"):
        return _brent(lambda v: np.float64(f(v)), np.float64(a), np.float64(b), np.float64(xtol),
                      np.float64(rtol), maxiter)


def _brent(f: Callable[[np.float64], np.float64], a: np.float64, b: np.float64, xtol: np.float64,
           rtol: np.float64, maxiter: int) -> float:
    """:func:`brent_root` in numpy's float64 scalars."""
    x_previous, x = a, b
    f_previous, fx = f(x_previous), f(x)
    if f_previous == 0:
        return float(x_previous)
    if fx == 0:
        return float(x)
    if math.copysign(1.0, f_previous) == math.copysign(1.0, fx):
        raise ValueError("brent_root: f(a) and f(b) must have different signs")
    x_block = f_block = step_previous = step = np.float64(0.0)
    for _ in range(maxiter):
        if f_previous != 0 and fx != 0 and math.copysign(1.0, f_previous) != math.copysign(1.0, fx):
            # the root lies between x and x_previous: the other end of the bracket
            x_block, f_block = x_previous, f_previous
            step_previous = step = x - x_previous
        if abs(f_block) < abs(fx):  # x the better end
            x_previous, x, x_block = x, x_block, x
            f_previous, fx, f_block = fx, f_block, fx
        delta = (xtol + rtol * abs(x)) / 2
        bisection = (x_block - x) / 2
        if fx == 0 or abs(bisection) < delta:
            return float(x)
        if abs(step_previous) > delta and abs(fx) < abs(f_previous):
            if x_previous == x_block:  # the secant
                trial = -fx * (x - x_previous) / (fx - f_previous)
            else:  # inverse quadratic interpolation
                slope_previous = (f_previous - fx) / (x_previous - x)
                slope_block = (f_block - fx) / (x_block - x)
                trial = -fx * (f_block * slope_block - f_previous * slope_previous) \
                    / (slope_block * slope_previous * (f_block - f_previous))
            if 2 * abs(trial) < min(abs(step_previous), 3 * abs(bisection) - delta):  # a good short step
                step_previous, step = step, trial
            else:
                step_previous = step = bisection
        else:
            step_previous = step = bisection
        x_previous, f_previous = x, fx
        x += step if abs(step) > delta else (delta if bisection > 0 else -delta)
        fx = f(x)
    raise RuntimeError(f"brent_root: no convergence in {maxiter} steps")


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
