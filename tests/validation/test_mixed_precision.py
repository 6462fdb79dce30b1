"""Mixed precision (``solver.mixed_precision``): single-precision increments in the constrained CG
give the all-double answer.

The truth is a solve at a 1000 times tighter tolerance in double: the mixed-precision run must be
within the tolerance of it (as the double run is), with the same iterations. (Without the drift
refresh of K x, or with it at the whole tolerance instead of a tenth, the sliding case is off by
5.6e-8 at 64^2; without any drift in K x it is as close as double, 1e-9: the residual difference is
the drift the bound allows, amplified by the inverse operator and the steps.) The single-precision
product itself is checked against the double one, and the drift bound of the incremental K x
against a solve whose iterates travel far from their end point (partial slip, the case that stalled
the coupling loop before K x was refreshed by that bound)."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vc_testing import SEED_A0, seed_material, sphere_problem
from viscontact.numerics import constrained
from viscontact.physics.kernels import half_space_convolver
from viscontact.numerics.grid import Grid
from viscontact.problem.problem import SolverSettings
from viscontact.bodies.compliance import compliance_of
from viscontact.solvers.transient import init, step
from viscontact.running.loop import simulate


def _final(problem, mixed: bool, tolerance: float):
    solver = dataclasses.replace(problem.solver, mixed_precision=mixed, tolerance=tolerance, workers=1)
    records = list(simulate(dataclasses.replace(problem, solver=solver)))
    return records[-1], sum(r.iterations for r in records)


def test_single_precision_product_is_the_double_one_to_float32_rounding():
    conv = half_space_convolver(Grid(48, 1e-3), 0.3, workers=1, components=("zz",))
    field = np.random.default_rng(1).random((48, 48)) * 1e5
    double, single = conv.apply("zz", field), conv.apply("zz", field, single=True)
    assert single.dtype == np.float32 and double.dtype == np.float64
    error = np.abs(single - double).max() / np.abs(double).max()
    assert 1e-9 < error < constrained.SINGLE_ERROR  # float32 rounding, within the bound the CG assumes


@pytest.mark.parametrize("mode", ["creep", "sliding"])
def test_mixed_precision_is_as_close_to_a_tight_solve_as_double(mode):
    if mode == "creep":
        pb = sphere_problem(seed_material(), 64, 1.5e-3, t_end=0.01, dt=2e-4)
    else:
        pb = sphere_problem(seed_material(), 64, 2.56 * SEED_A0, mode="frictionless_sliding", speed=0.8 * SEED_A0 / 0.01,
                            t_end=0.01)
    truth, _ = _final(pb, False, 1e-11)
    double, it_double = _final(pb, False, 1e-8)
    mixed, it_mixed = _final(pb, True, 1e-8)
    scale = np.abs(truth.pressure).sum()
    err_double = np.abs(double.pressure - truth.pressure).sum() / scale
    err_mixed = np.abs(mixed.pressure - truth.pressure).sum() / scale
    assert err_double < 1e-8  # the tight solve is the truth
    assert err_mixed < 1e-8
    assert abs(it_mixed - it_double) <= 0.05 * it_double
    assert not np.array_equal(mixed.pressure, double.pressure)  # the single-precision path did run


def test_partial_slip_coupling_converges_in_mixed_precision_as_in_double():
    """The tangential solve's iterates go far and come back (its bounds move with p): without the
    drift refresh, K x was off by 1e-7 of |b| and the coupling loop stalled at 3e-8 > 1e-8."""
    results = {}
    for mixed in (False, True):
        pb = sphere_problem(seed_material(), 12, 1.5e-3, mode="partial_slip", friction=0.3, rate=2e-3, speed=0.125,
                            t_end=0.012, solver=SolverSettings(workers=1, mixed_precision=mixed))
        sub = compliance_of(pb)
        state = init(pb, sub)
        for _ in range(4):
            state, record = step(pb, sub, state)
        results[mixed] = record
    for field in ("pressure", "shear_x"):
        a, b = getattr(results[False], field), getattr(results[True], field)
        assert np.abs(a - b).sum() <= 1e-7 * np.abs(a).sum(), field
    assert results[True].coupling_iterations <= results[False].coupling_iterations + 1


def test_drift_bound_keeps_the_incremental_product_exact_to_the_tolerance():
    """An operator whose increments are off by 1e-7 (a perturbed kernel) and a start far from the
    answer: the returned gradient is the exact one to tolerance x max|b|."""
    n = 24
    conv = half_space_convolver(Grid(n, 1e-3), 0.3, workers=1, components=("zz",))
    exact = lambda x: conv.apply("zz", x) * 1e-6  # noqa: E731

    def rough(x):  # an increment product with a relative error of 1e-7 of its size
        out = exact(x)
        return out * (1 + 1e-7 * np.cos(np.arange(out.size).reshape(out.shape)))

    grid = Grid(n, 1e-3)
    x, y = grid.mesh()
    b = 1e-5 - (x**2 + y**2) / 0.02
    sol = constrained.constrained_cg(exact, b, np.ones((n, n)), 0.0, np.inf, tolerance=1e-8, apply_k_increment=rough)
    true_gradient = exact(sol.x) - b
    assert np.abs(sol.gradient - true_gradient).max() <= 1e-8 * np.abs(b).max()
