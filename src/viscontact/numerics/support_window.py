"""Support-window solve of the normal contact problem: the constrained CG on a sub-box of the grid.

The normal problem of a step (:func:`~viscontact.numerics.constrained.constrained_cg` with x = p >= 0, seed
Eqs. 7-8, 10) is a convex quadratic programme whose solution vanishes outside the contact. Restricted
to a box W of the grid (p = 0 outside), it is the same kind of problem with the operator K_WW, which
is again a DC-FFT convolution (Liu, Wang & Liu 2000) on the smaller m x m box, its kernel a crop of
the full one (translation invariance): every CG iteration then costs transforms of (2m)^2 points
instead of (2n)^2. The restricted solution, extended by zero, is the solution of the full problem
if and only if the gap is non-negative outside W (the Karush-Kuhn-Tucker conditions of the full
problem: inside W they hold by construction), which one full-domain product checks; the solution
of the strictly convex programme being unique, it equals the full-domain solve's to the CG tolerance.

The box (:func:`window_side`) holds the support of the warm start (the extrapolated pressure of the
last steps, :func:`viscontact.solvers.transient.step`) plus a margin of :data:`MARGIN_CELLS` cells or
:data:`MARGIN_FRACTION` of its extent, its side m rounded up so that the padded length 2m is an
FFT-friendly size of the backend (:attr:`viscontact.numerics.arrays.ArrayBackend.fast_length`: on the CPU
``scipy.fft.next_fast_len``; on a GPU a coarser ladder, whose cuFFT plans a growing contact reuses). Where the check finds a penetration outside W, the
box is enlarged over those points and the solve repeated from the same warm start (not from the last
box's solution: Polonsky and Keer's stopping test, the relative change of p in an iteration, would
pass at once from a point that is exact on the old box, with the new points still unloaded); after
:data:`MAX_ENLARGEMENTS`, or when the box would cover more than :data:`FULL_FRACTION` of the grid's
side, the full-domain solve runs instead. The window depends only on the warm start, so a resumed
run repeats the same sequence of windows (bit-exact resume).

The tangential problem of partial slip (:func:`windowed_bounded_cg`) needs no check: its bounds
-mu_f p <= q_x <= mu_f p pin q_x = 0 outside the contact, so the box of the contact holds every
unknown and the restricted solution is exact.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from viscontact.numerics.arrays import cpu_fast_length
from viscontact.numerics.constrained import ConstrainedSolution, constrained_cg
from viscontact.numerics.grid import mask_span
from viscontact.numerics.resident_cg import resident_cg

#: margin [cells] at least around the support of the warm start (the extrapolated warm start already
#: holds the contact's growth to first order: 4 cells and 3 % gave the same solves as 3 cells and 2 %
#: on the creep and sliding benchmarks, with boxes 5-8 % wider; 2 cells and 1 % re-solved twice as
#: often under a load ramp, BENCHMARKS.md)
MARGIN_CELLS = 3
#: margin as a fraction of the support's extent
MARGIN_FRACTION = 0.02
#: a box side above this fraction of the grid's is not worth it: the full-domain solve
FULL_FRACTION = 0.95
#: enlargements of the box after a failed check before the full-domain solve
MAX_ENLARGEMENTS = 3


def window_side(extent: int, n: int, fast_length: Callable[[int], int] = cpu_fast_length) -> int | None:
    """Side m [cells] of the box for a support of ``extent`` cells on an n x n grid: the extent plus two
    margins, rounded up so that the padded length 2m is a ``fast_length`` (the backend's,
    :attr:`~viscontact.numerics.arrays.ArrayBackend.fast_length`: on the CPU ``scipy.fft.next_fast_len``);
    None above :data:`FULL_FRACTION` n (the full grid is then the cheaper box)."""
    m = extent + 2 * max(MARGIN_CELLS, math.ceil(MARGIN_FRACTION * extent))
    while fast_length(2 * m) != 2 * m:
        m = (fast_length(2 * m) + 1) // 2
    return m if m <= FULL_FRACTION * n else None


def _start(span: tuple[int, int], m: int, n: int) -> int:
    """First index of an m-long range centred on ``span`` and kept inside 0..n."""
    return min(max((span[0] + span[1] - m) // 2, 0), n - m)


def _box(mask: np.ndarray, fast_length: Callable[[int], int]) -> tuple[int, tuple[slice, slice]] | None:
    """(m, the m x m box) around the True cells of ``mask`` (n, n) with :func:`window_side`'s margins
    and the backend's ``fast_length``; None when that box would not be worth it."""
    n = mask.shape[0]
    rows, cols = mask_span(mask, 0), mask_span(mask, 1)
    m = window_side(max(rows[1] - rows[0], cols[1] - cols[0]), n, fast_length)
    if m is None:
        return None
    r0, c0 = _start(rows, m, n), _start(cols, m, n)
    return m, (slice(r0, r0 + m), slice(c0, c0 + m))


def _solve(op, b, x0, lower, upper, mixed_precision: bool, **options) -> ConstrainedSolution:
    """:func:`~viscontact.numerics.constrained.constrained_cg` with ``op``'s action and options, or where the
    operator's backend keeps the CG's scalars on the device (``op.check_every`` above 1: a GPU)
    :func:`~viscontact.numerics.resident_cg.resident_cg`, which needs no direct sums (it corrects every
    iteration's clip by a product)."""
    cg = op.cg_options(mixed_precision)
    if op.check_every > 1:
        return resident_cg(op.apply, b, x0, lower, upper, check_every=op.check_every,
                           preconditioner=cg["preconditioner"], apply_k_increment=cg.get("apply_k_increment"),
                           **options)
    return constrained_cg(op.apply, b, x0, lower, upper, **cg, **options)


def windowed_cg(op, b: np.ndarray, x0: np.ndarray, *, total: float | None = None, cell_area: float = 1.0,
                tolerance: float = 1e-10, max_iterations: int = 2000,
                what: str = "constrained conjugate gradient", mixed_precision: bool = True,
                start_product: np.ndarray | None = None) -> ConstrainedSolution:
    """:func:`~viscontact.numerics.constrained.constrained_cg` of the normal problem (bounds 0 and inf) on a box
    around the support of ``x0`` (module docstring), the same solution to the CG tolerance.

    Parameters
    ----------
    op
        The step's :class:`~viscontact.bodies.compliance.ElasticOperator` (``op.window(m)``: the operator on an
        m x m box; None: the full-domain solve).
    b, x0, total, cell_area, tolerance, max_iterations, what
        As for :func:`~viscontact.numerics.constrained.constrained_cg` (b: minus the gap and the known
        displacement [m]; x0: the warm start [Pa]).
    mixed_precision
        Search directions and preconditioner in single precision
        (:meth:`~viscontact.bodies.compliance.ElasticOperator.cg_options`).
    start_product
        K x0 on the whole grid in double precision, where the caller knows it (x0 >= 0): spares the
        first product of every solve (:func:`~viscontact.numerics.constrained.constrained_cg`); x0 is
        supported in every box, so its product there is a crop.

    Returns
    -------
    ConstrainedSolution
        On the whole grid: x, the gradient K x - b (minus the multiplier under load control) from one
        full-domain product, and the iterations of every solve done; ``product`` is that K x where
        the box passed its check (None after the full-domain solve, whose K x carries the drift of
        its single-precision increments).
    """
    n = b.shape[0]

    def full(start: np.ndarray, done: int) -> ConstrainedSolution:
        sol = _solve(op, b, start, 0.0, np.inf, mixed_precision, total=total, cell_area=cell_area,
                     tolerance=tolerance, max_iterations=max_iterations, what=what, start_product=start_product)
        return replace(sol, iterations=sol.iterations + done)

    support = x0 > 0
    if op.window is None or b.shape != (n, n) or (total is not None and total <= 0) or not support.any():
        return full(x0, 0)
    iterations, cover = 0, support
    for _ in range(MAX_ENLARGEMENTS + 1):
        window = _box(cover, op.fast_length)
        if window is None:
            break
        m, box = window
        sub = op.window(m)
        sol = _solve(sub, b[box], x0[box], 0.0, np.inf, mixed_precision, total=total, cell_area=cell_area,
                     tolerance=tolerance, max_iterations=max_iterations, what=what,
                     start_product=None if start_product is None else start_product[box])
        iterations += sol.iterations
        x = np.zeros_like(b)
        x[box] = sol.x
        product = op.apply(x)
        gradient = product - b
        multiplier = 0.0
        if total is not None:  # as constrained_cg: the mean gradient over the contact
            contact = x > 0
            multiplier = float(gradient[contact].mean()) if contact.any() else sol.multiplier
            gradient -= multiplier
        cover = gradient < 0  # penetration
        cover[box] = False
        if not cover.any():
            return ConstrainedSolution(x, gradient, multiplier, iterations, sol.residual, product)
        cover[box] = True  # the next box covers this one and the points that penetrate
    return full(x0, iterations)


def windowed_bounded_cg(op, b: np.ndarray, x0: np.ndarray, lower: np.ndarray, upper: np.ndarray, *,
                        tolerance: float = 1e-10, max_iterations: int = 2000,
                        what: str = "constrained conjugate gradient",
                        mixed_precision: bool = True) -> ConstrainedSolution:
    """:func:`~viscontact.numerics.constrained.constrained_cg` with array bounds that coincide outside a region,
    on a box around that region: exact, no check needed (the points outside are fixed at the bound).

    The tangential problem of partial slip (seed Eqs. 9, 11) is one: -mu_f p <= q_x <= mu_f p pins
    q_x = 0 outside the contact, so its solution is that of the problem restricted to a box holding
    the contact, with the operator ``op.window(m)`` (module docstring). One full-domain product gives
    the gradient (the slip) everywhere.

    Parameters
    ----------
    op
        The step's :class:`~viscontact.bodies.compliance.ElasticOperator`.
    b, x0, lower, upper, tolerance, max_iterations, what
        As for :func:`~viscontact.numerics.constrained.constrained_cg` (``lower``, ``upper``: (n, n) arrays).
    mixed_precision
        As for :func:`windowed_cg`.
    """
    movable = lower < upper
    window = _box(movable, op.fast_length) if op.window is not None and movable.any() else None
    if window is None:
        return _solve(op, b, x0, lower, upper, mixed_precision, tolerance=tolerance, max_iterations=max_iterations,
                      what=what)
    m, box = window
    sub = op.window(m)
    sol = _solve(sub, b[box], x0[box], lower[box], upper[box], mixed_precision, tolerance=tolerance,
                 max_iterations=max_iterations, what=what)
    x = np.clip(x0, lower, upper)
    x[box] = sol.x
    gradient = op.apply(x)
    gradient -= b
    return ConstrainedSolution(x, gradient, 0.0, sol.iterations, sol.residual)
