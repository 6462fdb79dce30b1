"""The contact problem with a non-symmetric operator (steady sliding): p >= 0, gap >= 0,
complementarity, with the load or the approach given, solved by a primal-dual active-set method
(Hintermueller, Ito & Kunisch 2002) with GMRES on each set (:mod:`viscontact.numerics.krylov`).
"""
from __future__ import annotations

import numpy as np

from viscontact.errors import ConvergenceError
from viscontact.numerics.krylov import gmres


def _restricted(fun, idx: np.ndarray, shape: tuple[int, int]):
    """The map v -> fun(v on the grid)[idx] acting on the values at the flat indices idx."""
    def restricted(v: np.ndarray) -> np.ndarray:
        full = np.zeros_like(v, shape=shape)
        full.ravel()[idx] = v
        return fun(full).ravel()[idx]

    return restricted


def _solve_on_set(apply_k, rhs: np.ndarray, active: np.ndarray, x0: np.ndarray, tol: float, maxiter: int,
                  preconditioner=None, what: str = "steady-state") -> tuple[np.ndarray, int]:
    """GMRES (:func:`viscontact.numerics.krylov.gmres`) on the active set; returns (solution on the grid,
    Krylov iterations)."""
    idx = np.flatnonzero(active)
    shape = active.shape
    op = _restricted(apply_k, idx, shape)
    m = _restricted(preconditioner, idx, shape) if preconditioner is not None else None
    sol = gmres(op, rhs.ravel()[idx], x0.ravel()[idx], rtol=tol, max_iterations=maxiter, preconditioner=m)
    if not sol.converged:
        raise ConvergenceError(f"{what} GMRES", maxiter, sol.residual, tol)
    out = np.zeros_like(rhs, shape=shape)
    out.ravel()[idx] = sol.x
    return out, sol.iterations


def _entry(like: np.ndarray, value) -> np.ndarray:
    """The one-element array [value] of ``like``'s library (the border of a bordered vector)."""
    return np.full_like(like, value, shape=1)


def _solve_bordered(apply_k, gap: np.ndarray, active: np.ndarray, p0: np.ndarray, delta0: float,
                    mean_pressure: float, row_scale: float, tol: float, maxiter: int,
                    preconditioner=None, what: str = "steady-state") -> tuple[np.ndarray, float, int]:
    """The load-controlled system on the active set in one GMRES solve: the bordered system

        [K_AA  -e] [p    ]   [-gap_A         ]
        [s e^T/m 0] [delta] = [s mean_pressure]

    (m points, e = ones, s = ``row_scale`` [m/Pa] making the load row a displacement), right
    preconditioned by the same block system with K_AA replaced by the Fourier preconditioner's M
    (without one, by s I): x = M^-1 r + delta M^-1 e with delta from the load row (M^-1 e made once
    per set). Returns
    (p on the grid, delta [m], Krylov iterations)."""
    idx = np.flatnonzero(active)
    shape = active.shape
    m = idx.size
    op = _restricted(apply_k, idx, shape)
    if preconditioner is not None:
        inv = _restricted(preconditioner, idx, shape)
    else:  # the scalar compliance: keeps pressures and displacements in their units
        def inv(r: np.ndarray) -> np.ndarray:
            return r / row_scale
    inv_e = inv(np.ones_like(gap, shape=m))
    inv_e_mean = float(inv_e.mean())

    def bordered(z: np.ndarray) -> np.ndarray:
        return np.concatenate([op(z[:m]) - z[m], _entry(z, row_scale * z[:m].mean())])

    def precondition(z: np.ndarray) -> np.ndarray:
        x = inv(z[:m])
        delta = (z[m] / row_scale - x.mean()) / inv_e_mean
        return np.concatenate([x + delta * inv_e, _entry(z, delta)])

    rhs = np.concatenate([-gap.ravel()[idx], _entry(gap, row_scale * mean_pressure)])
    sol = gmres(bordered, rhs, np.concatenate([p0.ravel()[idx], _entry(gap, delta0)]), rtol=tol,
                max_iterations=maxiter, preconditioner=precondition)
    if not sol.converged:
        raise ConvergenceError(f"{what} GMRES", maxiter, sol.residual, tol)
    out = np.zeros_like(gap)
    out.ravel()[idx] = sol.x[:m]
    return out, float(sol.x[m]), sol.iterations


#: relative GMRES tolerance of the active-set rounds before the set first settles (then ``tolerance``)
SETTLING_TOLERANCE = 1e-6
#: a cycle of the active set that the union of its sets cannot break (points with p ~ 0 and h ~ 0 at the
#: contact's edge, in tension by round-off with them in the set, penetrating by round-off without) ends
#: with the larger set's solution, its tension clipped, when that tension sums to at most this fraction
#: of the total pressure
CYCLE_TENSION = 1e-6


def solve_contact_active_set(apply_k, gap: np.ndarray, *, control: str, value: float, cell_area: float,
                             initial: np.ndarray | None = None, tolerance: float = 1e-10,
                             max_iterations: int = 2000, max_sets: int = 100,
                             preconditioner=None, settling_tolerance: float = SETTLING_TOLERANCE,
                             what: str = "steady-state") -> tuple[np.ndarray, float, int, int]:
    """Primal-dual active set for p >= 0, h = K p + gap - delta >= 0, p h = 0, with a general
    (non-symmetric) K. Returns (p [Pa], delta [m], Krylov (GMRES) iterations of all solves,
    number of active-set rounds). Raises ConvergenceError with the number of points that still
    changed set after ``max_sets`` rounds. Under load control each round is one solve of the
    bordered system (p and delta together, :func:`_solve_bordered`), under displacement control
    one solve for p.

    Inexact rounds: until the set first stays the same, the linear solves stop at the relative
    residual ``settling_tolerance`` (the set only needs the sign of p and h); the set is then solved
    again to ``tolerance`` and checked once more, and from there on every solve is to ``tolerance``
    (so the answer is that of exact rounds: a set that is stable under solves to ``tolerance``).
    A set that comes back, or a round that changes no fewer points than the one before, also ends
    the inexact rounds (points at p ~ 0 entering and leaving on the solves' error). In exact rounds a
    set that comes back is replaced by its union with the current one; when that union is the
    current set itself, the cycle is round-off at the contact's edge and the current solution is
    returned with its tension clipped, if that tension is at most :data:`CYCLE_TENSION` of the total
    pressure. ``what`` names the problem in a :class:`~viscontact.errors.ConvergenceError`.
    """
    active = initial > 0 if initial is not None and np.any(initial > 0) else gap <= np.quantile(gap, 0.05)
    p = initial.copy() if initial is not None else np.zeros_like(gap)
    delta = 0.0
    seen: list[np.ndarray] = []
    krylov = 0
    changed = 0
    tol = max(tolerance, settling_tolerance)
    for it in range(1, max_sets + 1):
        if control == "load":
            if it == 1:  # the load row in displacement units: the mean K 1_A over the first set [m/Pa]
                row_scale = float(apply_k(active.astype(float))[active].mean()) if active.any() else 1.0
            mean_pressure = value / (cell_area * max(int(active.sum()), 1))  # [Pa] on the set
            if it == 1 and not np.any(p[active] > 0):
                p = np.where(active, mean_pressure, 0.0)
            p, delta, kp = _solve_bordered(apply_k, gap, active, p, delta, mean_pressure, row_scale, tol,
                                           max_iterations, preconditioner, what)
            krylov += kp
        else:
            delta = value
            p, kp = _solve_on_set(apply_k, delta - gap, active, p, tol, max_iterations, preconditioner, what)
            krylov += kp
        h = apply_k(p) + gap - delta
        scale = np.abs(gap[active]).max() if active.any() else 1.0
        new_active = np.where(active, p > 0, h < -1e-12 * max(scale, abs(delta)))
        if np.array_equal(new_active, active):
            if tol <= tolerance:
                return np.maximum(p, 0.0), float(delta), krylov, it
            tol = tolerance  # settled under inexact solves: solve it exactly and check again
            continue
        previous, changed = changed, int(np.sum(new_active != active))  # counted before the sets are swapped
        if tol > tolerance and (changed >= previous > 0 or any(np.array_equal(new_active, s) for s in seen)):
            tol = tolerance  # no longer settling under inexact solves (points at p ~ 0): exact from here
            seen.clear()
        elif any(np.array_equal(new_active, s) for s in seen):  # cycling: keep the union, then stop on repeat
            union = new_active | active
            if np.array_equal(union, active):  # the union cannot break it: round-off at the edge (docstring)
                tension = float(np.sum(np.minimum(p, 0.0)))
                if -tension <= CYCLE_TENSION * float(np.sum(np.maximum(p, 0.0))):
                    return np.maximum(p, 0.0), float(delta), krylov, it
            new_active = union
        seen.append(active)
        active = new_active
    raise ConvergenceError(f"{what} active set", max_sets, float(changed), 0.0,
                           hint="the contact set did not settle (residual: points still changing set)")
