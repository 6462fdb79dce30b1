"""The bound-constrained conjugate gradient with its scalars kept where the fields are (a GPU).

:func:`~viscontact.numerics.constrained.constrained_cg` decides each iteration on the host: whether
points were clipped or released, whether the step broke down, whether the change is below the
tolerance. On a GPU every such decision reads a scalar back from the device and waits for the
queue to drain: about twenty reads an iteration, which bound a CG iteration at 2048^2 to several
milliseconds on an H200, ten to twenty times its memory-bandwidth floor. This module iterates the
same method (Polonsky & Keer 1999: conjugate directions on the free set, projection on the bounds,
release of bound points whose gradient points inwards, restart of conjugacy when the free set
changes; under load control the sum constraint by rescaling, its multiplier the approach) with
every decision made by the arithmetic itself:

* the step, the conjugacy factor, the free set's size and mean, the load's rescaling factor, the
  move's size and the drift bound of the single-precision products are 0-d arrays of the fields'
  library (``np.where`` of 0-d conditions instead of ``if``);
* the projection runs every iteration (a no-op where nothing crosses a bound) and the product of its
  correction is added every iteration (in single precision: zero where nothing was clipped), so
  conjugacy restarts whenever the correction or the release is not empty;
* a step that breaks down (no curvature above round-off, or longer than
  :data:`~viscontact.numerics.constrained.BREAKDOWN_STEP`) moves nothing and restarts conjugacy;
* the host reads the relative change (the stopping test), the drift bound, the size of the free
  gradient and whether a release is pending once every ``check_every`` iterations, in one transfer
  of four numbers: the solve
  ends at the first check whose change is below the tolerance (at most ``check_every - 1``
  iterations past the host version's stop, each of which only refines the solution), and K x is
  recomputed in double there when the drift bound has passed its limit.

The solution meets the same test as the host version's (the relative change of x between two
iterations below ``tolerance``), so the two agree to the tolerance; they are not equal bit for bit
(the extra iterations, and the rescaling applied every iteration). Where the backend keeps its
scalars on the device (:attr:`viscontact.numerics.arrays.ArrayBackend.check_every` above 1: CuPy),
:func:`~viscontact.numerics.constrained.constrained_cg` hands its solve to :func:`resident_cg`.
"""
from __future__ import annotations

import numpy as np

from viscontact.errors import ConvergenceError
from viscontact.numerics.constrained import (
    BREAKDOWN_STEP,
    DRIFT_FRACTION,
    ROUNDOFF,
    SINGLE_ERROR,
    ConstrainedSolution,
    Operator,
)

#: K x is recomputed in double every this many iterations whatever the drift bound (as the host
#: version's 25: a multiple of every ``check_every`` used)
REFRESH_EVERY = 24


def resident_cg(apply_k: Operator, b, x0, lower, upper, *, total: float | None = None, cell_area: float = 1.0,
                tolerance: float = 1e-10, max_iterations: int = 2000,
                what: str = "constrained conjugate gradient", preconditioner: Operator | None = None,
                apply_k_increment: Operator | None = None, start_product=None,
                check_every: int = 4) -> ConstrainedSolution:
    """Polonsky-Keer bound-constrained CG with device-resident scalars (module docstring).

    Parameters
    ----------
    apply_k, b, x0, lower, upper, total, cell_area, tolerance, max_iterations, what, preconditioner, apply_k_increment, start_product
        As for :func:`~viscontact.numerics.constrained.constrained_cg` (b [m], x [Pa]); the bounds are
        scalars (Python floats, ``upper`` possibly ``inf``) or fields of b's library.
    check_every
        Iterations between two reads of the stopping test by the host.

    Returns
    -------
    ConstrainedSolution
        As :func:`~viscontact.numerics.constrained.constrained_cg`'s.

    Raises
    ------
    ConvergenceError
        The change is still above ``tolerance`` after ``max_iterations``.
    """
    if check_every < 1:
        raise ValueError(f"check_every must be >= 1, got {check_every}")
    x = np.clip(x0.astype(float), lower, upper)
    bounded_above = bool(np.ndim(upper)) or not np.isposinf(upper)
    movable = np.less(lower, upper) if np.ndim(lower) or np.ndim(upper) else None
    scale_start = 1.0
    if total is not None:  # the set-up's decisions: once a solve, on the host
        if total <= 0:
            zero = np.zeros_like(x)
            g = apply_k(zero) - b
            g_min = float(g.min())
            return ConstrainedSolution(zero, g - g_min, g_min, 0, 0.0)
        s = float(x.sum())
        if s <= 0:
            x = np.ones_like(x) if movable is None else movable.astype(float)
            s, start_product = float(x.sum()), None
        scale_start = total / (cell_area * s)
        x *= scale_start
    kx = np.multiply(start_product, scale_start) if start_product is not None else apply_k(x).astype(float)
    single = apply_k_increment is not None
    increment = apply_k_increment if single else apply_k
    direction = np.zeros_like(x, dtype=np.float32 if single else float)
    released = np.zeros_like(x, dtype=bool)
    conjugate = np.zeros_like(x, dtype=bool, shape=())
    g_norm_old = np.ones_like(x, shape=())
    drift = np.zeros_like(x, shape=())
    b_scale = float(np.abs(b).max())
    drift_limit = DRIFT_FRACTION * tolerance * b_scale
    multiplier = np.zeros_like(x, shape=())
    residual = np.inf

    for it in range(1, max_iterations + 1):
        if it % REFRESH_EVERY == 0:
            kx = apply_k(x).astype(float)
            drift = drift * 0.0
        g = kx - b
        free = x > lower
        if bounded_above:
            free &= x < upper
        free |= released
        if total is not None:
            multiplier = _free_mean(g, free)
            g -= multiplier
        if it == 1:  # the warm start's points whose gradient points inwards join at once (as the host version)
            free |= _inward(x, g, lower, upper, bounded_above, movable)
        free_gradient = g * free
        z = preconditioner(free_gradient.astype(direction.dtype)) if preconditioner is not None \
            else free_gradient.astype(direction.dtype)
        if total is not None:
            z = z - _free_mean(z, free).astype(z.dtype)
        g_norm = _dot(free_gradient, z)
        beta = np.where(conjugate, g_norm / g_norm_old, 0.0)
        direction = (direction * beta.astype(direction.dtype) + z) * free
        g_norm_old = np.where(g_norm > 0, g_norm, 1.0)
        k_direction = increment(direction)
        denom = _dot(k_direction, direction)
        step = _dot(free_gradient, direction) / np.where(denom > 0, denom, 1.0)
        broke_down = ~((denom > 0) & (g_norm > 0) & np.isfinite(step) & (step <= BREAKDOWN_STEP))
        step = np.where(broke_down, 0.0, step)
        change = np.abs(step) * np.abs(direction).sum(dtype=np.float64)
        x_linear = x - direction * step
        x = np.clip(x_linear, lower, upper)
        correction = x - x_linear
        k_correction = increment(correction.astype(direction.dtype))
        kx = kx - k_direction * step + k_correction
        if single:
            drift = drift + SINGLE_ERROR * (np.abs(step) * np.abs(k_direction).max() + np.abs(k_correction).max())
        corrected = np.abs(correction).sum()
        change = change + corrected
        # release: bound points (not fixed) whose gradient points inwards join the next iteration's free set
        released = _inward(x, g, lower, upper, bounded_above, movable) & ~free
        clipped = corrected > 0
        conjugate = ~(released.any() | clipped | broke_down)
        if total is not None:
            s = x.sum()
            factor = total / (cell_area * np.where(s > 0, s, 1.0))
            factor = np.where(s > 0, factor, 1.0)
            x = x * factor
            kx = kx * factor
            change = change + np.abs(factor - 1.0) * s
            scale = s * factor
            # a move that clipped every point has not converged
            relative = np.where(s > 0, change / np.where(scale > 0, scale, 1.0), np.inf)
        else:
            scale = np.abs(x).sum()
            relative = np.where(scale > 0, change / np.where(scale > 0, scale, 1.0), 0.0)
        if it % check_every and it < max_iterations:
            continue
        # the host's one read of this block of iterations: the change, the drift bound, the free gradient
        # and whether points wait for their release (a gradient at round-off ends the solve only without)
        residual, drift_now, gradient_max, pending = np.stack(
            [relative, drift, np.abs(free_gradient).max(), released.any().astype(float)]).tolist()
        if residual < tolerance or gradient_max <= ROUNDOFF * b_scale and not pending:
            return _solution(x, kx, b, lower, total, cell_area, it, residual, multiplier)
        if drift_now > drift_limit:
            kx = apply_k(x).astype(float)
            drift = drift * 0.0
    raise ConvergenceError(what, max_iterations, residual, tolerance,
                           hint="raise solver.max_iterations or refine the grid")


def _inward(x, g, lower, upper, bounded_above: bool, movable):
    """Points at a bound whose gradient points into the box (their release), movable ones only."""
    inward = (x <= lower) & (g < 0)
    if bounded_above:
        inward |= (x >= upper) & (g > 0)
    if movable is not None:
        inward &= movable
    return inward


def _dot(a, b):
    """sum(a * b) as a 0-d array, summed in double whatever the fields' precision."""
    return np.multiply(a, b).sum(dtype=np.float64)


def _free_mean(field, free):
    """Mean of ``field`` over the mask ``free`` as a 0-d array (0 where nothing is free)."""
    count = free.sum(dtype=np.float64)
    return np.multiply(field, free).sum(dtype=np.float64) / np.where(count > 0, count, 1.0)


def _solution(x, kx, b, lower, total, cell_area, it, residual, multiplier) -> ConstrainedSolution:
    """The result as :func:`~viscontact.numerics.constrained.constrained_cg` gives it: the sum
    constraint imposed exactly, the gradient relative to its mean over the contact."""
    if total is not None:
        factor = total / (cell_area * float(x.sum()))
        x, kx = x * factor, kx * factor
        g = kx - b
        on = x > lower
        mean = float(_free_mean(g, on)) if bool(on.any()) else float(multiplier)
        return ConstrainedSolution(x, g - mean, mean, it, residual)
    return ConstrainedSolution(x, kx - b, 0.0, it, residual)
