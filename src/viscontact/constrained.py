"""Bound-constrained conjugate gradient (Polonsky & Keer 1999), shared by the normal and
tangential contact problems.

Both are quadratic programmes with a symmetric positive definite operator K (an instantaneous
compliance times a DC-FFT influence matrix):

    minimise 1/2 x.K x - b.x   subject to  lower <= x <= upper   [and  sum(x) dA = total],

whose optimality conditions are the contact conditions: with g = K x - b,

* normal (seed Eqs. 7-8, 10): x = p, lower = 0, upper = inf, g = gap; under load control the sum
  constraint holds and its multiplier is the approach delta_z (g is then taken relative to its mean
  over the contact, as in Polonsky & Keer);
* tangential (seed Eqs. 9, 11): x = q_x, bounds -/+ mu_f p, g = slip s_x: s = 0 where the bounds are
  inactive (stick), q opposes s where they are active (slip).

The iteration is Polonsky & Keer's: conjugate directions restricted to the free set, a projection on
the bounds, release of the bound points whose gradient points inwards, and a restart of conjugacy
whenever the free set changes. Convergence is measured as the relative change of x between
iterations, or reached when the gradient on the free set is at round-off (an exact preconditioner,
e.g. that of a periodic operator, converges in one iteration); the solve raises
:class:`~viscontact.errors.ConvergenceError` at the iteration cap.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from .errors import ConvergenceError

Operator = Callable[[np.ndarray], np.ndarray]
#: a gradient below this times the size of K x and b is round-off: the solve has converged
ROUNDOFF = 1e-14


@dataclass(frozen=True)
class ConstrainedSolution:
    """Result of :func:`constrained_cg`.

    Attributes
    ----------
    x
        The solution.
    gradient
        g = K x - b at the solution (for the load-controlled normal problem: minus its contact mean).
    multiplier
        Mean of K x - b over the free set when a sum constraint is imposed (the approach), else 0.
    iterations
        Iterations used (each costs one application of K plus one for the gradient).
    residual
        Last relative change of x.
    """

    x: np.ndarray
    gradient: np.ndarray
    multiplier: float
    iterations: int
    residual: float


def constrained_cg(apply_k: Operator, b: np.ndarray, x0: np.ndarray, lower: np.ndarray | float,
                   upper: np.ndarray | float, *, total: float | None = None, cell_area: float = 1.0,
                   tolerance: float = 1e-10, max_iterations: int = 2000,
                   what: str = "constrained conjugate gradient",
                   preconditioner: Operator | None = None,
                   apply_k_sparse: Operator | None = None, sparse_limit: int = 48) -> ConstrainedSolution:
    """Polonsky-Keer bound-constrained conjugate gradient.

    Parameters
    ----------
    apply_k
        x -> K x, a symmetric positive definite operator on (n, n) arrays.
    b
        Right-hand side, same shape.
    x0
        Starting point (warm start); projected on the bounds.
    lower, upper
        Bounds (arrays or scalars; ``upper`` may be ``np.inf``).
    total
        When given, impose sum(x) * cell_area = total (only with lower = 0 and upper = inf: the
        load-controlled normal problem, Polonsky & Keer 1999, Eqs. 14-23).
    tolerance, max_iterations
        Stop when sum|x - x_old| / sum|x| < tolerance; raise ConvergenceError after max_iterations.
    """
    lower = np.broadcast_to(np.asarray(lower, dtype=float), b.shape)
    upper = np.broadcast_to(np.asarray(upper, dtype=float), b.shape)
    x = np.clip(np.array(x0, dtype=float), lower, upper)
    fixed = lower >= upper
    if total is not None:
        if total <= 0:
            zero = np.zeros_like(x)
            g = apply_k(zero) - b
            return ConstrainedSolution(zero, g - g.min(), float(g.min()), 0, 0.0)
        if x.sum() <= 0:
            x = np.where(fixed, 0.0, 1.0)
        x *= total / (cell_area * x.sum())
    if np.all(fixed):
        g = apply_k(x) - b
        return ConstrainedSolution(x, g, 0.0, 0, 0.0)

    direction = np.zeros_like(x)
    g_norm_old = 1.0
    conjugate = False
    multiplier = 0.0
    residual = np.inf
    kx = apply_k(x)
    for it in range(1, max_iterations + 1):
        free = (x > lower) & (x < upper)
        if it % 25 == 0:  # refresh the incrementally updated K x against round-off drift
            kx = apply_k(x)
        g = kx - b
        if total is not None:
            multiplier = float(g[free].mean()) if free.any() else float(g.min())
            g = g - multiplier
        if not free.any() or np.max(np.abs(g[free])) <= ROUNDOFF * max(np.max(np.abs(kx)), np.max(np.abs(b))):
            # nothing free, or converged on the free set to round-off (an exact preconditioner does it
            # in one iteration: another step would divide round-off by round-off): release the bound
            # points whose gradient points inwards, or stop
            inward = ((x <= lower) & (g < 0)) | ((x >= upper) & (g > 0))
            inward &= ~fixed & ~free
            if not inward.any():
                return ConstrainedSolution(x, g, multiplier, it, 0.0)
            free = free | inward
            conjugate = False
        if preconditioner is not None:
            z = preconditioner(np.where(free, g, 0.0))
            if total is not None:
                z = z - z[free].mean()
            z = np.where(free, z, 0.0)
        else:
            z = np.where(free, g, 0.0)
        g_norm = float(np.sum(g[free] * z[free]))
        if conjugate:
            direction = np.where(free, z + (g_norm / g_norm_old) * direction, 0.0)
        else:
            direction = z
        g_norm_old = g_norm if g_norm > 0 else 1.0
        k_direction = apply_k(direction)
        r = k_direction - k_direction[free].mean() if total is not None else k_direction
        denom = float(np.sum(r[free] * direction[free]))
        if denom <= 0 or g_norm <= 0:
            return ConstrainedSolution(x, g, multiplier, it, 0.0)
        step = float(np.sum(g[free] * direction[free])) / denom
        x_old = x.copy()
        x = np.where(free, x - step * direction, x)
        x_linear = x
        clipped = (x < lower) | (x > upper)
        x = np.clip(x, lower, upper)
        release = ((x <= lower) & (g < 0)) | ((x >= upper) & (g > 0))
        release &= ~free & ~fixed
        if release.any():
            x = np.where(release, np.clip(x - step * g, lower, upper), x)
        conjugate = not (release.any() or clipped.any())
        kx = kx - step * k_direction  # exact for the move x -> x - step * direction
        if not conjugate:  # bound corrections at a few points: add their effect
            correction = x - x_linear
            if apply_k_sparse is not None and np.count_nonzero(correction) <= sparse_limit:
                kx = kx + apply_k_sparse(correction)
            else:
                kx = apply_k(x)
        if total is not None:
            s = x.sum()
            if s > 0:
                x *= total / (cell_area * s)
                kx *= total / (cell_area * s)
        scale = float(np.sum(np.abs(x)))
        residual = float(np.sum(np.abs(x - x_old))) / scale if scale > 0 else 0.0
        if residual < tolerance:
            g = kx - b  # K x kept exactly up to round-off (refreshed every 25 iterations)
            if total is not None:
                fr = x > lower
                multiplier = float(g[fr].mean()) if fr.any() else multiplier
                g = g - multiplier
            return ConstrainedSolution(x, g, multiplier, it, residual)
    raise ConvergenceError(what, max_iterations, residual, tolerance,
                           hint="raise solver.max_iterations or refine the grid")
