"""What the transient state carries from step to step instead of transforming again: the products
of the last two pressures (the warm start's K x0) and the response history (the history
displacement in displacement space, compliance.Compliance.initial_response).

The truth for each is the product it replaces, computed by the DC-FFT from the tractions: the
history displacement from the traction history (compliance.known_displacement), the warm start's
product from the elastic operator. A run with the carried fields switched off is the reference of
the run with them: both are solves of the same problems to the CG tolerance.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vc_testing import SEED_A0, SEED_TAU, seed_material, sphere_problem
from viscontact.numerics import constrained
from viscontact.solvers import transient
from viscontact.running import loop
from viscontact.physics.materials import Material
from viscontact.problem.problem import LayerSettings
from viscontact.bodies.compliance import compliance_of

THREE_MODES = Material.prony(0.2e6, [0.5e6, 0.8e6, 0.4e6], [1e-3, 1e-2, 1e-1], 0.3)


def _creep(material, scheme: str, steps: int = 30):
    return sphere_problem(material, 32, 1.5e-3, t_end=(steps - 1) * 2e-4, dt=2e-4, scheme=scheme)


@pytest.mark.parametrize("scheme", ["constant", "linear"])
@pytest.mark.parametrize("body", ["zener", "three modes", "layer on a rigid base"])
def test_response_history_is_the_transformed_traction_history(body, scheme):
    """At every step of a creep run the response history's u_z equals the DC-FFT of the traction
    history to round-off (the recursion is linear and K time-invariant)."""
    problem = _creep(THREE_MODES if body == "three modes" else seed_material(), scheme)
    if body == "layer on a rigid base":
        problem = dataclasses.replace(problem, layer=LayerSettings(0.5e-3))
    compliance = compliance_of(problem)
    state = transient.init(problem, compliance)
    assert state.response is not None
    worst = 0.0
    for state, _ in transient.steps(problem, state=state, compliance=compliance):
        t = state.t + problem.time.dt
        carried = compliance.known_from_response(state.response, t, False)
        transformed, _ = compliance.known_displacement(state.histories, t, False, need_x=False)
        worst = max(worst, float(np.abs(carried - transformed).max() / np.abs(transformed).max()))
    assert worst < 1e-12


def test_response_history_ends_at_the_first_frame_shift():
    """Sliding moves the material under the frame: the response history would need displacements
    beyond the grid's edge, so it is dropped at the first shift and the traction history used."""
    problem = sphere_problem(seed_material(), 32, 2.56 * SEED_A0, mode="frictionless_sliding",
                             speed=0.8 * SEED_A0 / SEED_TAU, t_end=0.003)
    carried = [state.response is not None for state, _ in transient.steps(problem)]
    assert carried[0] and not any(carried[2:])


@pytest.mark.parametrize("body", ["direct history", "layer on an elastic base", "periodic"])
def test_no_response_history_where_it_would_not_hold(body):
    problem = _creep(seed_material(), "constant", steps=3)
    if body == "direct history":
        problem = dataclasses.replace(problem, solver=dataclasses.replace(problem.solver, history="direct"))
    elif body == "layer on an elastic base":
        problem = dataclasses.replace(problem, layer=LayerSettings(0.3e-3, substrate="elastic",
                                                                   substrate_shear_modulus=10e6))
    else:
        problem = dataclasses.replace(problem, grid=dataclasses.replace(problem.grid, periodic=True))
    assert compliance_of(problem).initial_response() is None


def test_warm_start_product_is_the_operator_applied_to_it():
    problem = _creep(seed_material(), "constant", steps=12)
    compliance = compliance_of(problem)
    op = compliance.elastic_operator("z", False)
    checked = 0
    for state, _ in transient.steps(problem, compliance=compliance):
        warm, product = transient._warm_start(compliance, state, state.step + 1)
        if product is None:
            continue
        checked += 1
        exact = op.apply(warm)
        assert np.abs(product - exact).max() < 1e-12 * np.abs(exact).max()
    assert checked >= 8  # from the third step on (the first step's operator is another one)


def test_warm_start_with_many_clipped_points_has_no_product():
    """Where the extrapolation is negative at more than WARM_CLIP_POINTS points the warm start's
    product is left to the solve (direct sums would cost more than the transform)."""
    problem = _creep(seed_material(), "constant", steps=6)
    compliance = compliance_of(problem)
    state = list(transient.steps(problem, compliance=compliance))[-1][0]
    receding = dataclasses.replace(state, pressure_previous=3.0 * state.pressure)  # 2 p - 3 p < 0 wherever p > 0
    assert np.count_nonzero(state.pressure) > transient.WARM_CLIP_POINTS
    warm, product = transient._warm_start(compliance, receding, state.step + 1)
    assert product is None and not warm.any()


def test_start_product_gives_the_solve_of_the_product_it_replaces():
    problem = _creep(seed_material(), "constant", steps=3)
    compliance = compliance_of(problem)
    state = list(transient.steps(problem, compliance=compliance))[-1][0]
    op = compliance.elastic_operator("z", False)
    b = -(problem.gap + 0.2 * op.apply(state.pressure))
    kwargs = dict(total=0.15, cell_area=problem.grid.cell_area, tolerance=1e-10, **op.cg_options(False))
    plain = constrained.constrained_cg(op.apply, b, state.pressure, 0.0, np.inf, **kwargs)
    given = constrained.constrained_cg(op.apply, b, state.pressure, 0.0, np.inf, start_product=op.apply(state.pressure),
                                       **kwargs)
    assert given.iterations == plain.iterations
    assert np.abs(given.x - plain.x).sum() < 1e-10 * np.abs(plain.x).sum()


@pytest.mark.parametrize("mode", ["creep", "sliding"])
def test_carried_products_give_the_solves_without_them(mode, monkeypatch):
    """A run with the carried products and response history against one that transforms every
    time (the fields switched off): the same pressures to the CG tolerance, the same iterations."""
    if mode == "creep":
        problem = _creep(seed_material(), "linear", steps=40)
    else:
        problem = sphere_problem(seed_material(), 48, 2.56 * SEED_A0, mode="frictionless_sliding",
                                 speed=0.8 * SEED_A0 / SEED_TAU, t_end=0.01)
    carried = list(loop.simulate(problem))
    monkeypatch.setattr(transient, "_warm_start", lambda compliance, state, k: (
        np.maximum(2.0 * state.pressure - state.pressure_previous, 0.0) if k > 1 else state.pressure, None))
    monkeypatch.setattr(type(compliance_of(problem)), "initial_response", lambda self: None)
    plain = list(loop.simulate(problem))
    for a, b in zip(carried, plain):
        assert np.abs(a.pressure - b.pressure).sum() < 1e-8 * np.abs(b.pressure).sum()
    assert abs(sum(r.iterations for r in carried) - sum(r.iterations for r in plain)) <= 0.02 * sum(
        r.iterations for r in plain)


def test_a_checkpoint_without_the_carried_fields_resumes():
    """A checkpoint written before the state carried products (no such arrays in it) resumes with
    them absent: the next steps transform as before and give the same solves."""
    from viscontact.io.checkpoint import state_arrays, state_from_arrays

    problem = _creep(seed_material(), "constant", steps=10)
    compliance = compliance_of(problem)
    run = list(transient.steps(problem, compliance=compliance))
    arrays = {k: v for k, v in state_arrays(run[4][0]).items()
              if "pressure_product" not in k and ".response" not in k}
    old = state_from_arrays(arrays)
    assert old.response is None and old.pressure_product is None and old.step == 4
    resumed = list(transient.steps(problem, state=old, compliance=compliance))
    for (_, a), (_, b) in zip(resumed, run[5:]):
        assert np.abs(a.pressure - b.pressure).sum() < 1e-8 * np.abs(b.pressure).sum()
