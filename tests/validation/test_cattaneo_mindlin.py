"""Partial slip against Cattaneo-Mindlin, and the Coulomb and load-balance conditions at every step.

Cattaneo-Mindlin (Johnson, Contact Mechanics, Sec. 7.2; :class:`viscontact.physics.reference.CattaneoMindlin`)
holds exactly for an elastic half-space with nu = 0.5 (no normal/tangential coupling): under a held
load W and a tangential approach delta_x, Q / mu W = 1 - (1 - delta_x / delta*)^(3/2),
c / a = (1 - Q / mu W)^(1/3), delta* = 3 mu W (2 - nu) / (16 G a). Tolerance 0.02 on Q / mu W;
measured 1e-4 at n = 64 (a spans 43 cells). The stick radius is a count of cells: tolerance 0.03 a
(about one cell). The shear traction along y = 0 is within 0.05 mu p0 of
mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)] (the cells at the two square-root edges err most).
"""
import numpy as np
import pytest

from viscontact.physics.materials import Material
from viscontact.problem.problem import PHASE_GROSS_SLIDING, PHASE_PARTIAL_SLIP, PiecewiseLinear, SolverSettings
from viscontact.physics.reference import cattaneo_mindlin, hertz_from_load
from viscontact.running.loop import simulate

from vc_testing import SEED_G0, SEED_LOAD, SEED_RADIUS, sphere_problem

G, W, MU = SEED_G0, SEED_LOAD, 0.3


def _ramp(nu: float, n: int = 64, steps: int = 40, coupling: bool = True, control: str = "load",
          value=None, reach: float = 1.2):
    hz = hertz_from_load(W, SEED_RADIUS, G, nu)
    dstar = cattaneo_mindlin(W, SEED_RADIUS, MU, G, nu).sliding_displacement
    t_end, dt = 1.0, 1.0 / steps
    half_width = 1.5 * hz.radius
    speed = 2 * half_width / n / dt  # one cell per step once sliding
    held = W if control == "load" else hz.approach
    pb = sphere_problem(Material.elastic(G, nu), n, half_width, control=control,
                        value=held if value is None else value(held, dt, t_end), mode="partial_slip", friction=MU,
                        rate=reach * dstar / t_end, speed=speed, t_end=t_end, dt=dt,
                        solver=SolverSettings(coupling=coupling))
    return pb, hz, dstar, list(simulate(pb))


def test_reference_is_consistent():
    """The closed forms of the reference agree with each other (force <-> displacement <-> stick
    radius) and with Hertz at Q = 0; the traction integrates to Q."""
    cm = cattaneo_mindlin(W, SEED_RADIUS, MU, G, 0.5)
    assert cm.contact_radius == pytest.approx(hertz_from_load(W, SEED_RADIUS, G, 0.5).radius, rel=1e-14)
    d = np.linspace(0.0, 1.0, 11) * cm.sliding_displacement
    q = cm.force(d)
    assert q[0] == 0 and q[-1] == pytest.approx(MU * W, rel=1e-14)
    np.testing.assert_allclose(cm.displacement(q), d, rtol=1e-12, atol=1e-15 * cm.sliding_displacement)
    np.testing.assert_allclose(cm.stick_ratio_from_force(q), cm.stick_ratio_from_displacement(d), atol=1e-12)
    r = np.linspace(0.0, cm.contact_radius, 20001)
    for force in (0.3 * MU * W, 0.8 * MU * W):
        ring = cm.shear_traction(0.5 * (r[1:] + r[:-1]), force) * 2 * np.pi * 0.5 * (r[1:] + r[:-1]) * np.diff(r)
        assert ring.sum() == pytest.approx(force, rel=1e-4)


def test_cattaneo_mindlin_force_stick_radius_and_traction():
    pb, hz, dstar, records = _ramp(0.5)
    cm = cattaneo_mindlin(W, SEED_RADIUS, MU, G, 0.5)
    partial = [r for r in records if r.phase == PHASE_PARTIAL_SLIP and r.delta_x > 0]
    assert len(partial) > 20
    x = pb.grid.x
    n = pb.grid.n
    for r in partial:
        q_ratio = float(cm.force(r.delta_x)) / (MU * W)
        assert r.friction_force / (MU * W) == pytest.approx(q_ratio, abs=0.02)
        stick_radius = np.sqrt(r.stick_ratio * r.contact_area / np.pi) / hz.radius
        assert stick_radius == pytest.approx(float(cm.stick_ratio_from_displacement(r.delta_x)), abs=0.03)
        row = 0.5 * (r.shear_x[n // 2 - 1] + r.shear_x[n // 2])  # y = +-dx/2 around y = 0
        exact = cm.shear_traction(np.hypot(x, 0.5 * pb.grid.spacing), float(cm.force(r.delta_x)))
        assert np.max(np.abs(row - exact)) < 0.05 * MU * hz.peak_pressure
    onset = next(r for r in records if r.phase == PHASE_GROSS_SLIDING)
    step_dx = pb.tangential.displacement_rate * pb.time.dt
    assert abs(onset.delta_x - dstar) <= step_dx + 1e-15, (onset.delta_x, dstar)


@pytest.mark.parametrize("control", ["load", "displacement"])
def test_partial_slip_begins_at_first_contact(control):
    """A normal history from zero ([[0, 0], [dt, W], ...]): no contact at t = 0, where nothing sticks
    or slips (stick ratio NaN, phase still partial slip); from the first contact (t = dt) the run is
    the held one a step later, delta_x measured from that contact (the indenter that moved before
    touching dragged nothing), so gross sliding begins a step later too; unloaded to zero once
    sliding, it stays sliding. (It slid from t = 0: the stick ratio 0 of no contact read as a
    vanished stick zone, and Q = mu W from the first loaded step.)"""
    def history(value, dt, t_end):
        return PiecewiseLinear((0.0, dt, t_end - 3 * dt, t_end), (0.0, value, value, 0.0))

    pb, hz, dstar, held = _ramp(0.5, n=32, steps=20, control=control, reach=2.0)
    _, _, _, ramped = _ramp(0.5, n=32, steps=20, control=control, value=history, reach=2.0)
    rate = pb.tangential.displacement_rate
    first = ramped[0]
    assert first.contact_area == 0 and first.friction_force == 0 and np.isnan(first.stick_ratio)
    assert first.phase == PHASE_PARTIAL_SLIP
    assert [r.delta_x for r in ramped[:5]] == pytest.approx([rate * r.t for r in ramped[:5]], rel=1e-12)
    onset = next(k for k, r in enumerate(held) if r.phase == PHASE_GROSS_SLIDING)
    assert 5 < onset < len(held) - 8
    for h, r in zip(held[:onset + 2], ramped[1:onset + 3]):
        assert r.phase == h.phase and r.stick_ratio == pytest.approx(h.stick_ratio, abs=1e-12)
        assert r.friction_force == pytest.approx(h.friction_force, abs=1e-6 * MU * W)
    assert held[1].friction_force > 0.1 * MU * W  # the shifted comparison sees the force build up
    unloaded = ramped[-1]
    assert unloaded.contact_area == 0 and unloaded.phase == PHASE_GROSS_SLIDING and np.isnan(unloaded.stick_ratio)
    assert all(r.phase == PHASE_GROSS_SLIDING for r in ramped[onset + 1:])


def test_coulomb_bounds_and_load_balance_every_step():
    pb, hz, dstar, records = _ramp(0.3, n=48, steps=30)
    for r in records:
        assert r.load == pytest.approx(W, rel=1e-8)
        assert np.all(np.abs(r.shear_x) <= MU * r.pressure * (1 + 1e-12) + 1e-12 * hz.peak_pressure)
        assert np.all(r.shear_x[r.pressure == 0] == 0)


def test_coupling_shifts_pressure_against_the_shear():
    """nu = 0.3: the shear q_x > 0 pushes the surface in ahead of it (IC_zx > 0 for x > 0), so the
    pressure moves towards -x and the coupled contact is shifted backwards, by a
    few per cent of a (measured -0.015 a, -0.027 a, -0.037 a at delta_x = 0.3, 0.6, 0.9 delta*; the
    coupled peak pressure is 3.5 % higher at delta_x = 0, where friction resists the inward Poisson slip)."""
    _, hz, dstar, coupled = _ramp(0.3, n=48, steps=20)
    _, _, _, uncoupled = _ramp(0.3, n=48, steps=20, coupling=False)
    k = 10  # delta_x = 0.6 delta*
    shift = (coupled[k].contact_shift - uncoupled[k].contact_shift) / hz.radius
    assert abs(uncoupled[k].contact_shift) < 1e-9 * hz.radius
    assert -0.05 < shift < -1e-4
    # at delta_x = 0 coupling alone (Poisson's inward slip resisted by friction) leaves part of the contact
    # stuck with radial shear and no net force
    assert 0 < coupled[0].stick_ratio < 1
    assert abs(coupled[0].friction_force) < 1e-6 * W
