"""Probe (issue 35, not shipped): a one-time correction of the warm start on the ring of cells around
the predicted contact edge before the constrained CG of each normal solve. It did not pay
(BENCHMARKS.md, issue 35): kept to reproduce the measurement.

    PYTHONPATH=src .venv/bin/python benchmarks/probe_ring_warm_start.py --case creep_indentation --n 256 \\
        [--steps 161] [--ring 2] [--reach 0] [--tolerance 1e-6] [--off]

Per load-controlled normal solve (``contact_laws.windowed_cg``, wrapped here): the residual of the
warm start p0 (from the step's known product where there is one), g = K p0 - b minus its mean over
the contact; the ring R = cells within ``--ring`` cells of the edge of p0 > 0 on both sides (square
dilation minus erosion); the ring block K_RR of the influence matrix from the kernel's column
(a unit load at a corner: K depends on |di|, |dj| only), dense, or truncated to offsets
|di|, |dj| <= ``--reach`` (sparse); the bounded problem on R, min 1/2 y K_RR y - (K_RR p0_R - g_R) y,
y >= 0, sum y = sum p0_R (the rest of p0 held), by the same constrained CG with a diagonal
preconditioner to ``--tolerance``; p0_R <- y, and the CG then starts from it (its first product
recomputed). Printed: CG iterations a step (the ring's apart), process CPU time a step, the ring's
time and iterations a solve.
"""
from __future__ import annotations

import argparse
import time
import warnings
from pathlib import Path

import numpy as np
import scipy.sparse
from scipy import ndimage

from viscontact.io.case import load_case
from viscontact.numerics.constrained import constrained_cg
from viscontact.solvers import contact_laws, transient


def ring_block(column: np.ndarray, i: np.ndarray, j: np.ndarray, n: int, reach: int):
    """K_RR of the ring cells (i, j): dense (reach 0) or truncated to |di|, |dj| <= reach (sparse)."""
    if not reach:
        return column[np.abs(i[:, None] - i[None, :]), np.abs(j[:, None] - j[None, :])]
    index = np.full((n + 2 * reach, n + 2 * reach), -1, dtype=np.int64)
    index[i + reach, j + reach] = np.arange(i.size)
    rows, cols, values = [], [], []
    for di in range(-reach, reach + 1):
        for dj in range(-reach, reach + 1):
            other = index[i + reach + di, j + reach + dj]
            ok = other >= 0
            rows.append(np.nonzero(ok)[0])
            cols.append(other[ok])
            values.append(np.full(int(ok.sum()), column[abs(di), abs(dj)]))
    return scipy.sparse.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                                   shape=(i.size, i.size))


def ring_corrected(solve, ring: int, reach: int, tolerance: float, stats: dict):
    """``windowed_cg`` with the warm start corrected on the ring first (load control only)."""
    columns: dict[int, np.ndarray] = {}

    def wrapped(op, b, x0, *, total=None, cell_area=1.0, start_product=None, **options):
        if total is not None and (x0 > 0).any():
            start = time.process_time()
            n = b.shape[0]
            contact = x0 > 0
            g = (start_product if start_product is not None else op.apply(x0)) - b
            g -= g[contact].mean()
            square = np.ones((3, 3), bool)
            cells = (ndimage.binary_dilation(contact, square, iterations=ring)
                     & ~ndimage.binary_erosion(contact, square, iterations=ring))
            i, j = np.nonzero(cells)
            if id(op) not in columns:
                unit = np.zeros((n, n))
                unit[0, 0] = 1.0
                columns[id(op)] = op.apply_sparse(unit)
            k_rr = ring_block(columns[id(op)], i, j, n, reach)
            diagonal = columns[id(op)][0, 0]
            x_r = x0[i, j]
            sol = constrained_cg(lambda v: k_rr @ v, k_rr @ x_r - g[i, j], x_r, 0.0, np.inf, total=float(x_r.sum()),
                                 tolerance=tolerance, max_iterations=500, what="ring correction",
                                 preconditioner=lambda r: r / diagonal)
            x0 = x0.copy()
            x0[i, j] = sol.x
            start_product = None
            stats["time"] += time.process_time() - start
            stats["solves"] += 1
            stats["iterations"] += sol.iterations
            stats["cells"] += i.size
        return solve(op, b, x0, total=total, cell_area=cell_area, start_product=start_product, **options)
    return wrapped


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", default="creep_indentation")
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--steps", type=int, default=None)
    ap.add_argument("--ring", type=int, default=2, help="ring half-width [cells]")
    ap.add_argument("--reach", type=int, default=0, help="kernel offsets kept [cells] (0: dense block)")
    ap.add_argument("--tolerance", type=float, default=1e-6, help="the ring solve's CG tolerance")
    ap.add_argument("--off", action="store_true", help="no correction (the tree's own solver)")
    args = ap.parse_args()
    stats = {"time": 0.0, "solves": 0, "iterations": 0, "cells": 0}
    if not args.off:
        contact_laws.windowed_cg = ring_corrected(contact_laws.windowed_cg, args.ring, args.reach, args.tolerance, stats)
    case = Path(contact_laws.__file__).parents[1] / "cases" / f"{args.case}.toml"
    problem = load_case(case).with_overrides({"grid.n": args.n, "output.fields": []}).to_problem()
    iterations = []
    start = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _, record in transient.steps(problem):
            iterations.append(record.iterations)
            if args.steps is not None and len(iterations) >= args.steps:
                break
    cpu = (time.process_time() - start) / len(iterations)
    its = np.asarray(iterations, dtype=float)
    solves = max(stats["solves"], 1)
    print(f"{args.case} {args.n}^2 x {its.size}: CG it/step {its.mean():.2f} (later half {its[its.size // 2:].mean():.2f}), "
          f"CPU/step {1e3 * cpu:.1f} ms; ring: {stats['cells'] / solves:.0f} cells, {stats['iterations'] / solves:.1f} it, "
          f"{1e3 * stats['time'] / solves:.1f} ms a solve")


if __name__ == "__main__":
    main()
