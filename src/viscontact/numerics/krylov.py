"""Restarted GMRES for the non-symmetric steady contact operator (Saad & Schultz 1986).

Right-preconditioned GMRES(m): the Krylov space is built from A M^-1, so the least-squares residual
it minimises is the true residual b - A x (the stopping rule ||b - A x|| <= rtol ||b|| is tested on
it, as ``scipy.sparse.linalg.gmres`` does at the end of a cycle). Arnoldi with classical
Gram-Schmidt applied twice (CGS2, as stable as modified Gram-Schmidt, two block operations per
iteration), Givens rotations for the small least-squares problem.

Why not ``scipy.sparse.linalg.gmres``: its orthogonalisation is BLAS level-1/2 calls, and OpenBLAS
threads on a loaded 2-core machine made them 70 % of a 256^2 steady solve (BENCHMARKS.md). The
block products here are ``np.einsum`` loops (no BLAS), the same arithmetic.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

Operator = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class KrylovSolution:
    """Result of :func:`gmres`: the solution, the iterations (operator applications inside the
    Arnoldi cycles), the final relative residual ||b - A x|| / ||b|| and whether it reached rtol."""

    x: np.ndarray
    iterations: int
    residual: float
    converged: bool


def _norm(v: np.ndarray) -> float:
    return float(np.sqrt(np.einsum("i,i->", v, v)))


def gmres(apply_a: Operator, b: np.ndarray, x0: np.ndarray, *, rtol: float, max_iterations: int,
          preconditioner: Operator | None = None, restart: int = 60,
          callback: Callable[[float], None] | None = None) -> KrylovSolution:
    """Solve A x = b (1-D vectors) to ||b - A x|| <= rtol ||b||.

    Parameters
    ----------
    apply_a
        x -> A x.
    b, x0
        Right-hand side and starting point.
    rtol
        Relative tolerance on the true residual.
    max_iterations
        Cap on the operator applications in the Arnoldi cycles.
    preconditioner
        r -> M^-1 r (right preconditioning), identity when None.
    restart
        Arnoldi vectors per cycle.
    callback
        Called after each iteration with the current relative residual estimate.
    """
    precondition = preconditioner if preconditioner is not None else (lambda r: r)
    size = b.size
    b_norm = _norm(b)
    if b_norm == 0.0:
        return KrylovSolution(np.zeros_like(b), 0, 0.0, True)
    target = rtol * b_norm
    x = x0.astype(float)  # a copy
    iterations = 0
    cycle = max(1, min(restart, size))
    # the Krylov vectors are fields of b's library; the small Hessenberg system is on the host
    # (:mod:`viscontact.numerics.arrays`)
    basis = np.empty_like(b, shape=(cycle + 1, size), dtype=float)
    directions = np.empty_like(b, shape=(cycle, size), dtype=float)
    while True:
        r = b - apply_a(x)
        beta = _norm(r)
        if beta <= target or iterations >= max_iterations:
            return KrylovSolution(x, iterations, beta / b_norm, beta <= target)
        hess = np.zeros((cycle + 1, cycle))
        cos, sin = np.zeros(cycle), np.zeros(cycle)
        g = np.zeros(cycle + 1)
        g[0] = beta
        basis[0] = r / beta
        used = 0
        for j in range(cycle):
            directions[j] = precondition(basis[j])
            w = apply_a(directions[j])
            iterations += 1
            for _ in range(2):  # CGS2
                h = np.einsum("ij,j->i", basis[: j + 1], w)
                w -= np.einsum("ij,i->j", basis[: j + 1], h)
                hess[: j + 1, j] += h if isinstance(h, np.ndarray) else h.tolist()
            hess[j + 1, j] = _norm(w)
            if hess[j + 1, j] > 0.0:
                basis[j + 1] = w / hess[j + 1, j]
            for i in range(j):  # the previous rotations on the new column
                hess[i, j], hess[i + 1, j] = (cos[i] * hess[i, j] + sin[i] * hess[i + 1, j],
                                              -sin[i] * hess[i, j] + cos[i] * hess[i + 1, j])
            d = float(np.hypot(hess[j, j], hess[j + 1, j]))
            cos[j], sin[j] = (hess[j, j] / d, hess[j + 1, j] / d) if d > 0.0 else (1.0, 0.0)
            hess[j, j], hess[j + 1, j] = d, 0.0
            g[j + 1], g[j] = -sin[j] * g[j], cos[j] * g[j]
            used = j + 1
            if callback is not None:
                callback(abs(g[j + 1]) / b_norm)
            if abs(g[j + 1]) <= target or iterations >= max_iterations or hess[j, j] == 0.0:
                break
        y = np.zeros(used)
        for i in range(used - 1, -1, -1):  # back substitution in the rotated Hessenberg matrix
            if hess[i, i] != 0.0:
                y[i] = (g[i] - np.einsum("i,i->", hess[i, i + 1: used], y[i + 1:])) / hess[i, i]
        x = x + np.einsum("ij,i->j", directions[:used], np.asarray(y, like=directions))
