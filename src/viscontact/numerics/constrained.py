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
whenever the free set changes; the first iteration releases those of the warm start at once (a
growing contact's new points: one restart fewer a solve). Convergence is measured as the relative change of x between
iterations, sum |x_new - x_old| / sum |x|, or reached when the gradient on the free set is at
round-off (an exact preconditioner, e.g. that of a periodic operator, converges in one iteration)
or a step breaks down (no curvature above round-off along the direction: a preconditioned step
beyond :data:`BREAKDOWN_STEP`, the gradient then lying in the operator's null space); a move that
clips every point under load control has not converged; the solve raises
:class:`~viscontact.errors.ConvergenceError` at the iteration cap. The change is taken from the move
itself, |step| sum |d|, with no copy of the old x (to 1e-7: d is a float32 field);
an iteration that corrects points on the bounds adds the corrections' sum |x - x_linear| and the load
rescaling's |factor - 1| sum x, an upper bound of the change (triangle inequality), so the test never
stops earlier than the exact change would.

Mixed precision. K x is not recomputed each iteration but updated, K x <- K x - step K d (plus
the product of the bound corrections, x minus its unclipped update), and recomputed by a full product
at the start and every 25 iterations. The products of these increments may be computed in single
precision (``apply_k_increment``: float32 transforms, about half the time). Their rounding error is
at most :data:`SINGLE_ERROR` of the largest value of each product, so relative to the move: the
iteration adds up that bound and recomputes K x in double whenever it exceeds
:data:`DRIFT_FRACTION` of ``tolerance`` times max |b| (the scale of K x at the solution). From a
warm start the moves shrink geometrically and a solve needs about one such refresh, if any; a solve
whose iterates travel far and come back (the tangential problem of partial slip, whose bounds move)
gets as many as it needs. The solution, the gradient and every sum are in double; the search
direction, the preconditioned gradient and K d are float32 fields (any direction serves: x and K x
move along the float32 direction exactly, in double), which halves their memory traffic. The drift left
in K x, amplified by the inverse operator and carried by the history over the steps, keeps the
solution within the tolerance of an all-double solve (tested against a solve 1000 times tighter);
measured at 128^2 and 256^2 it is as close as all-double (BENCHMARKS.md), with the same iterations.

Every decision above reads a scalar on the host, which on a GPU waits for the device: there the
support windows' solves run :func:`viscontact.numerics.resident_cg.resident_cg`, the same iteration
with its scalars kept on the device and its stopping test read every few iterations.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from viscontact.errors import ConvergenceError

Operator = Callable[[np.ndarray], np.ndarray]
#: a gradient below this times the size of K x and b is round-off: the solve has converged
ROUNDOFF = 1e-14
#: bound corrections of at most this many points by direct sums when a single-precision product is
#: available (it costs about as much as 24 direct sums; a double product about 48)
SPARSE_LIMIT_MIXED = 24
#: bound on the error of a single-precision product relative to its largest value (measured: 1.3e-7
#: for the DC-FFT at 12^2 to 256^2; float32 rounding is 6e-8)
SINGLE_ERROR = 1e-6
#: K x is recomputed in double when the bound on its drift exceeds this fraction of tolerance x max|b|
#: (at the whole tolerance the sliding test case ends 5.6e-8 from the truth, at a tenth 1e-8)
DRIFT_FRACTION = 0.1
#: under load control the iterate is rescaled to the total load (Polonsky & Keer) unless the factor
#: is within this of 1: a conjugate move keeps the sum to float32 rounding of the direction (factors
#: 1 +- 1e-11 and less), which a rescale of x and K x (four passes over the grid) would not improve;
#: the solution returned is rescaled exactly
LOAD_ROUNDOFF = 1e-12
#: a preconditioned step longer than this is round-off: exact steps lie within the reciprocal spectrum
#: of the preconditioned operator P K on the free set (at most 1/lambda_min(P K): P_FF >= lambda_min
#: (K_FF)^-1 in the Loewner order), at most 1.6 over the test suite's 1.2e5 preconditioned steps; a
#: direction in the null space of K (the constant mode of a periodic operator in full contact, which
#: the load multiplier's round-off leaves in the gradient) gave steps of 1e13 to 1e25
BREAKDOWN_STEP = 1e6


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
        Last relative change of x (module docstring).
    product
        K x in double precision from one product of the final x, where the caller computed it
        (:func:`~viscontact.numerics.support_window.windowed_cg`'s check), else None.
    """

    x: np.ndarray
    gradient: np.ndarray
    multiplier: float
    iterations: int
    residual: float
    product: np.ndarray | None = None


def constrained_cg(apply_k: Operator, b: np.ndarray, x0: np.ndarray, lower: np.ndarray | float,
                   upper: np.ndarray | float, *, total: float | None = None, cell_area: float = 1.0,
                   tolerance: float = 1e-10, max_iterations: int = 2000,
                   what: str = "constrained conjugate gradient",
                   preconditioner: Operator | None = None,
                   apply_k_sparse: Operator | None = None, sparse_limit: int = 48,
                   apply_k_increment: Operator | None = None,
                   start_product: np.ndarray | None = None) -> ConstrainedSolution:
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
    preconditioner
        r -> approximate K^-1 r (on the free set).
    apply_k_sparse, sparse_limit
        x -> K x by direct sums for an x of at most ``sparse_limit`` non-zeros (the bound
        corrections), cheaper there than ``apply_k`` (at most :data:`SPARSE_LIMIT_MIXED` with
        ``apply_k_increment``).
    apply_k_increment
        x -> K x in lower precision (single-precision transforms) for the search directions and the
        bound corrections of more than :data:`SPARSE_LIMIT_MIXED` points (module docstring, mixed
        precision); None: ``apply_k`` for the directions and a full ``apply_k`` of x after such
        corrections.
    start_product
        K x0 when the caller knows it in double precision (e.g. from the products of earlier time
        steps, :func:`viscontact.solvers.transient.step`): used instead of the first product, so x0 must
        lie within the bounds. None: computed.
    """
    # a scalar lower bound and no upper one (the normal problem): the points at the bound are exactly
    # those not free, which spares the release test its element-wise passes on x
    plain_bounds = np.ndim(lower) == 0 and np.ndim(upper) == 0 and np.isposinf(upper)
    # scalar bounds stay Python floats, array bounds are fields of b's library (:mod:`viscontact.numerics.arrays`)
    lower, upper = _bound(lower), _bound(upper)
    x = x0.astype(float)  # a copy, clipped in place
    np.clip(x, lower, upper, out=x)
    # fixed points (lower = upper): a field, or one flag for scalar bounds
    fixed = np.greater_equal(lower, upper) if np.ndim(lower) or np.ndim(upper) else lower >= upper
    scale_start = 1.0
    if total is not None:
        if total <= 0:
            zero = np.zeros_like(x)
            g = apply_k(zero) - b
            return ConstrainedSolution(zero, g - g.min(), float(g.min()), 0, 0.0)
        if x.sum() <= 0:
            x = np.where(fixed, 0.0, 1.0) if np.ndim(fixed) else np.full_like(x, 0.0 if fixed else 1.0)
            start_product = None
        scale_start = total / (cell_area * x.sum())
        x *= scale_start
    if np.all(fixed):
        g = apply_k(x) - b
        return ConstrainedSolution(x, g, 0.0, 0, 0.0)

    # work arrays, allocated once per solve: the iteration itself allocates only what the operator,
    # the preconditioner and the sparse corrections return (BENCHMARKS.md: the freed temporaries
    # were a fifth of the run's CPU time)
    x_linear, g, work = (np.zeros_like(x) for _ in range(3))
    # mixed precision: the search direction, the preconditioned gradient and K d are float32 fields
    # (any direction serves; x and K x move by it exactly, in double), which halves their traffic
    single = apply_k_increment is not None
    direction = np.zeros_like(x, dtype=np.float32 if single else float)
    free_gradient = np.zeros_like(x, dtype=np.float32) if single and preconditioner is not None else work
    free, bound, mask, mask2 = (np.empty_like(x, dtype=bool) for _ in range(4))
    # points released at the last iteration: free for the next direction, wherever they sit
    released_points = np.zeros_like(x, dtype=bool)
    released = False
    movable = np.logical_not(fixed)
    # the normal problem has no upper bound and no negative x: skip their element-wise passes
    bounded_above = not bool(np.isposinf(upper).all())
    nonnegative = bool(np.min(lower) >= 0)
    b_scale = float(np.max(np.abs(b)))
    # mixed precision: bound on the error the single-precision increments have left in K x since its
    # last full product, and the bound at which K x is recomputed (module docstring)
    drift, drift_limit = 0.0, DRIFT_FRACTION * tolerance * b_scale
    # direct sums pay up to a product's cost: a single-precision one costs about half a double one
    limit = min(sparse_limit, SPARSE_LIMIT_MIXED) if apply_k_increment is not None else sparse_limit
    g_norm_old = 1.0
    conjugate = False
    multiplier = 0.0
    residual = np.inf
    # a step that broke down (round-off curvature): the next iteration releases or stops
    broke_down = False
    if start_product is not None:
        kx = np.multiply(start_product, scale_start)  # own copy: updated in place below
    else:
        kx = apply_k(x).astype(float)  # own copy: updated in place below

    def solution(it: int, residual: float) -> ConstrainedSolution:
        """The solve's result from the current x and K x: the sum constraint imposed to round-off
        (the iteration skips rescalings by less than LOAD_ROUNDOFF), the gradient from K x."""
        if total is not None and x.sum() > 0:
            factor = total / (cell_area * float(x.sum()))
            x_final, kx_final = x * factor, kx * factor
            g_final = kx_final - b
            on = x_final > lower
            mean = float(g_final[on].mean()) if on.any() else multiplier
            return ConstrainedSolution(x_final, g_final - mean, mean, it, residual)
        return ConstrainedSolution(x, kx - b - multiplier, multiplier, it, residual)
    for it in range(1, max_iterations + 1):
        np.greater(x, lower, out=free)
        if bounded_above:
            free &= np.less(x, upper, out=mask)
        if released:
            free |= released_points
        if it % 25 == 0 or drift > drift_limit:  # refresh the incrementally updated K x against drift
            kx = apply_k(x).astype(float)
            drift = 0.0
        np.subtract(kx, b, out=g)
        n_free = int(np.count_nonzero(free))
        if total is not None:
            multiplier = _free_mean(g, free, n_free) if n_free else float(g.min())
            g -= multiplier
        np.multiply(g, free, out=free_gradient)  # the gradient on the free set
        restarted = not n_free or broke_down or _at_roundoff(_max_abs(free_gradient), kx, b_scale)
        if restarted or it == 1:
            # nothing free, or converged on the free set to round-off (an exact preconditioner does it
            # in one iteration: another step would divide round-off by round-off), or the last step
            # broke down: release the bound points whose gradient points inwards, or stop. The first
            # iteration releases them too: the warm start's support misses the points a growing
            # contact takes (from the warm start's gradient, the move of the first iteration takes
            # them, which otherwise the second would, with a restart of conjugacy)
            inward = ((x <= lower) & (g < 0)) | ((x >= upper) & (g > 0))
            inward &= movable & ~free
            if inward.any():
                free |= inward
                n_free = int(np.count_nonzero(free))
                conjugate = broke_down = False
                np.multiply(g, free, out=free_gradient)
            elif restarted:
                return solution(it, 0.0)
        np.logical_not(free, out=bound)
        if preconditioner is not None:
            z = preconditioner(free_gradient)
            if total is not None:
                z -= _free_mean(z, free, n_free)
        else:
            z = free_gradient
        # the sums below are over the free set: the free gradient vanishes off it (z need not)
        g_norm = _dot(free_gradient, z)
        if conjugate:
            direction *= g_norm / g_norm_old
            direction += z
        else:
            np.copyto(direction, z)
        np.copyto(direction, 0.0, where=bound)
        g_norm_old = g_norm if g_norm > 0 else 1.0
        k_direction = apply_k_increment(direction) if apply_k_increment is not None else apply_k(direction)
        # under load control K d would be taken relative to its free mean: the direction sums to zero
        # on the free set, so the mean drops out of d.K d
        denom = _dot(k_direction, direction)
        step = _dot(free_gradient, direction) / denom if denom > 0 and g_norm > 0 else np.inf
        if not np.isfinite(step) or preconditioner is not None and step > BREAKDOWN_STEP:
            # no curvature above round-off along d: the gradient on the free set is round-off
            if restarted:
                return solution(it, 0.0)
            broke_down, conjugate, released = True, False, False
            continue
        # the move's size, sum |x_new - x_old| before bound corrections and rescaling (the free gradient
        # is no longer needed: its array takes |direction|)
        change = abs(step) * float(np.abs(direction, out=free_gradient).sum())
        x -= np.multiply(direction, step, out=work)  # the direction vanishes off the free set
        if plain_bounds:
            clipped = float(x.min()) < lower
        else:
            clipped = bool(np.less(x, lower, out=mask).any() or bounded_above and np.greater(x, upper, out=mask).any())
        if clipped:  # x_linear: x before the bound corrections (the clip)
            np.copyto(x_linear, x)
            if bounded_above:
                np.clip(x, lower, upper, out=x)
            else:
                np.maximum(x, lower, out=x)
        # release: bound points (not fixed) whose gradient points inwards join the free set of the next
        # iteration where they are (Polonsky & Keer move them by -step g, which is in x's units only
        # without a preconditioner: with one, the move fell below x's rounding at small lengths or
        # large moduli, the point stayed on its bound, was released again every iteration and the
        # solve converged off the optimum)
        if plain_bounds:  # every point not free sits at the lower bound (the direction left it there)
            release = np.logical_and(np.less(g, 0.0, out=mask2), bound, out=mask)
        else:
            release = np.less_equal(x, lower, out=mask)
            release &= np.less(g, 0.0, out=mask2)
            if bounded_above:
                release |= np.greater_equal(x, upper, out=mask2) & (g > 0)
            release &= bound
            release &= movable
        released = bool(release.any())
        if released:
            np.copyto(released_points, release)
        conjugate = not (released or clipped)
        kx -= np.multiply(k_direction, step, out=work)  # exact for the move x -> x - step * direction
        if apply_k_increment is not None:
            drift += SINGLE_ERROR * abs(step) * _max_abs(k_direction)
        if clipped:  # bound corrections: add their effect
            correction = np.subtract(x, x_linear, out=work)
            points = np.count_nonzero(correction)
            if apply_k_sparse is not None and points <= limit:
                kx += apply_k_sparse(correction)
            elif apply_k_increment is not None:  # an increment of the size of the move, as K d
                k_correction = apply_k_increment(correction)
                kx += k_correction
                drift += SINGLE_ERROR * _max_abs(k_correction)
            else:
                kx = apply_k(x).astype(float)
            change += float(np.abs(correction, out=correction).sum())  # the triangle inequality: a bound
        if total is not None:
            s = float(x.sum())
            factor = total / (cell_area * s) if s > 0 else 1.0
            if abs(factor - 1.0) > LOAD_ROUNDOFF:
                x *= factor
                kx *= factor
                change += abs(factor - 1.0) * s  # x >= 0
                s *= factor
            scale = s
        else:
            scale = float(x.sum()) if nonnegative else float(np.abs(x, out=work).sum())
        # under load control x sums to the total: a move that clipped every point has not converged
        residual = change / scale if scale > 0 else (np.inf if total is not None else 0.0)
        if residual < tolerance:
            return solution(it, residual)
    raise ConvergenceError(what, max_iterations, residual, tolerance,
                           hint="raise solver.max_iterations or refine the grid")


def _bound(value: np.ndarray | float) -> np.ndarray | float:
    """A bound as the iteration takes it: a scalar as a Python float, a field as a float field of
    its own library."""
    return float(value) if np.ndim(value) == 0 else value.astype(float, copy=False)


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    """sum(a * b) without a temporary (and without BLAS threads: an ``np.vdot`` in this loop made a
    run 5x slower on a loaded machine, BENCHMARKS.md); two float32 fields are summed by rows in
    single precision and over the rows in double (relative error about 1e-7)."""
    axes = "ijklmn"[:a.ndim]
    if a.dtype == np.float32 and b.dtype == np.float32 and a.ndim > 1:  # rows in single, their sum in double
        return float(np.einsum(f"{axes},{axes}->{axes[0]}", a, b).sum(dtype=np.float64))
    return float(np.einsum(f"{axes},{axes}->", a, b))


def _at_roundoff(free_gradient_max: float, kx: np.ndarray, b_scale: float) -> bool:
    """Whether max |g| on the free set is round-off: at most :data:`ROUNDOFF` times max(|K x|, |b|)
    (max |K x| only looked at when the gradient is small enough for it to matter)."""
    if free_gradient_max <= ROUNDOFF * b_scale:
        return True
    return free_gradient_max <= 1e-6 * b_scale and free_gradient_max <= ROUNDOFF * _max_abs(kx)


def _max_abs(field: np.ndarray) -> float:
    """max |field| without a temporary."""
    return max(float(field.max()), -float(field.min()))


def _free_mean(field: np.ndarray, free: np.ndarray, n_free: int) -> float:
    """Mean of ``field`` over the ``n_free`` points of the mask ``free``, without a masked copy: one
    pass, summed in double whatever the field's precision (an einsum: device libraries have no
    ``np.sum(..., where=...)``; as fast on the CPU)."""
    axes = "ijklmn"[:field.ndim]
    return float(np.einsum(f"{axes},{axes}->", field, free, dtype=np.float64)) / n_free
