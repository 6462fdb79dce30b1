"""Recursive hereditary sum (one internal field per retardation time) against the literal sum of
seed Eq. 5 (viscontact.numerics.history).

Three implementations are compared on random traction histories, with and without frame shifts:

* ``PronyHistory`` (recursive, O(1) per step),
* ``DirectHistory`` (literal sum kept by the package as its reference),
* a literal sum written here from the creep spectrum alone, with the ramp weights integrated in
  closed form (independent of both).

They are algebraically identical, so they agree to round-off: tolerance 1e-10 relative to the
largest displacement (the recursion accumulates ~k * 1e-16 over k steps; the direct sum's 8-point
Gauss rule for the ramp average of J is exact to ~1e-15 for dt <= lambda). A wrong decay, weight,
instantaneous compliance or shift direction is off by 1e-3 or more.

Measured (30 steps, dt = 0.3 of the shortest material time, both schemes, with and without
shifts): <= 1e-14. (The literal ramp weight here uses expm1: written as a difference of two
exponentials it loses ~log10(lambda/dt) digits and reached 3e-12 for the Prony series.)

The transient test runs the whole solver (n = 24, load ramped then held, linear scheme) with either
history and compares the pressures. The two runs see right-hand sides that differ by round-off
only; the constrained CG (tolerance 1e-13 on the relative change per iteration) then follows the
same active-set path in both, so the difference stays at round-off times the conditioning of the
contact problem: measured 1.8e-14 (Zener) and 1.1e-14 (Prony). The tolerance 1e-9 is what limits
a CG stopped at 1e-13 could reach if the two runs took a different iterate path (one more or
fewer iteration near a contact-edge node whose pressure is tiny); it is still far below any
error of the history itself (a wrong weight shifts the pressure by > 1e-4).
"""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.numerics.history import DirectHistory, PronyHistory, shift_material
from viscontact.physics.materials import Material
from viscontact.problem.problem import PiecewiseLinear, SolverSettings
from viscontact.numerics.schemes import step_coefficients
from viscontact.running.loop import simulate

from vc_testing import SEED_LOAD, seed_material, sphere_problem

MATERIALS = {
    "zener": seed_material(),
    "prony3": Material.prony(1.0e5, [1.0e6, 5.0e5, 2.0e5], [1e-3, 1e-2, 1e-1], 0.25),
}
N = 6


def ramp_weight(material: Material, age: float, dt: float) -> float:
    """(1/dt) int_age^{age+dt} J(s) ds in closed form from the spectrum."""
    c = material.creep
    lam, amp = c.retardation_times, c.amplitudes
    return float(c.long_term - np.sum(amp * lam / dt * np.exp(-age / lam) * -np.expm1(-dt / lam)))


def run_histories(material: Material, scheme: str, dt: float, steps: int, shift_at: set[int], seed: int):
    """Drive the three implementations with the same random tractions; return the three
    displacement-like fields J_inst p_k + r_k (to be convolved with the IC) at every step."""
    rng = np.random.default_rng(seed)
    m = material.creep.retardation_times.size
    prony, direct = PronyHistory.zeros(m, N), DirectHistory(N)
    increments: list[np.ndarray] = []
    ages_from: list[tuple[float, bool]] = []
    previous = np.zeros((N, N))
    out = []
    for k in range(steps):
        t = k * dt
        first = k == 0
        if k in shift_at:
            regular = step_coefficients(material.creep, dt, scheme, False)
            prony, _ = prony.shifted(1, regular)
            direct, _ = direct.shifted(1, regular)
            increments = [shift_material(f)[0] for f in increments]
            previous = shift_material(previous)[0]
        coef = step_coefficients(material.creep, dt, scheme, first)
        p = rng.uniform(0.0, 2.0e5, (N, N)) * (rng.uniform(size=(N, N)) > 0.2)
        rec = coef.instantaneous * p + prony.known(coef, t)
        drc = coef.instantaneous * p + direct.known(coef, t)
        ramp = (not first) and scheme == "linear"
        increments.append(p - previous)
        ages_from.append((t, ramp))
        lit = np.zeros((N, N))
        for inc, (tn, is_ramp) in zip(increments, ages_from):
            phi = ramp_weight(material, t - tn, dt) if is_ramp else float(material.creep_compliance(t - tn))
            lit += phi * inc
        out.append((rec, drc, lit, coef.instantaneous * p))
        prony = prony.advanced(p, coef, t)
        direct = direct.advanced(p, coef, t)
        assert direct.ramps[-1] == ramp
        previous = p
    return out


@pytest.mark.parametrize("name", sorted(MATERIALS))
@pytest.mark.parametrize("scheme", ["constant", "linear"])
@pytest.mark.parametrize("shifts", [set(), {3, 4, 9, 15, 16, 17}])
def test_recursive_equals_direct_and_literal_sum(name, scheme, shifts):
    material = MATERIALS[name]
    dt = 0.3 * material.shortest_time
    for k, (rec, drc, lit, _) in enumerate(run_histories(material, scheme, dt, 30, shifts, seed=k_seed(name, scheme))):
        scale = np.max(np.abs(lit))
        assert np.max(np.abs(rec - lit)) <= 1e-10 * scale, (k, np.max(np.abs(rec - lit)) / scale)
        assert np.max(np.abs(drc - lit)) <= 1e-10 * scale, (k, np.max(np.abs(drc - lit)) / scale)


def k_seed(name: str, scheme: str) -> int:
    return sum(map(ord, name + scheme))


def test_history_matters():
    """Guard against a vacuous comparison: the hereditary part r_k is a large fraction of the
    total, so an error in it would show far above the 1e-10 tolerance."""
    material = MATERIALS["zener"]
    dt = 0.3 * material.shortest_time
    for rec, _, lit, elastic in run_histories(material, "linear", dt, 30, {5, 6}, seed=1)[1:]:
        assert np.max(np.abs(lit - elastic)) > 0.1 * np.max(np.abs(lit))


def test_step_coefficients():
    material = MATERIALS["prony3"]
    c = material.creep
    dt = 1e-3
    first = step_coefficients(c, dt, "linear", True)
    np.testing.assert_array_equal(first.weight, 1.0)
    assert first.instantaneous == pytest.approx(c.instantaneous, rel=1e-13)
    lin = step_coefficients(c, dt, "linear", False)
    np.testing.assert_allclose(lin.decay, np.exp(-dt / c.retardation_times), rtol=1e-15)
    # J_inst of a ramp step = mean of J over the step
    assert lin.instantaneous == pytest.approx(ramp_weight(material, 0.0, dt), rel=1e-13)
    with pytest.raises(ValueError, match="time.scheme"):
        step_coefficients(c, dt, "cubic", False)


def _transient(history: str, material: Material) -> list:
    load = PiecewiseLinear((0.0, 2e-3, 1.0), (0.05, SEED_LOAD, SEED_LOAD))
    problem = sphere_problem(material, 24, 1.6e-3, value=load, t_end=4e-3, dt=5e-4, scheme="linear",
                             solver=SolverSettings(tolerance=1e-13, history=history, workers=1))
    return list(simulate(problem))


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_transient_direct_history_matches_recursive(name):
    material = MATERIALS[name]
    rec, drc = _transient("recursive", material), _transient("direct", material)
    assert len(rec) == len(drc) == 9
    for a, b in zip(rec, drc):
        assert a.t == b.t
        scale = np.max(np.abs(a.pressure))
        assert np.max(np.abs(a.pressure - b.pressure)) <= 1e-9 * scale, (a.t, np.max(np.abs(a.pressure - b.pressure)) / scale)
        assert a.delta_z == pytest.approx(b.delta_z, rel=1e-9)
    # the run does creep: the approach grows after the load is held
    assert rec[-1].delta_z > 1.05 * rec[4].delta_z
