"""Rolling with traction (``tangential.mode = "rolling"``): the steady rolling solver and the transient.

References, all for a rigid sphere on an elastic half-space with nu = 0.5 (normal and tangential
problems decouple), Hertz radius a:

* Coulomb saturation: at a creepage far beyond the creep region the contact slides everywhere,
  friction_force = -sign(xi) mu_f W, stick ratio 0 (exact up to the solver's tolerance);
* the stick region at the leading edge (+x, the indenter rolls in +x): Carter 1926, Kalker 1990;
* Kalker's linear theory at vanishing creepage, F = -G_K c^2 C11 xi (c = a for a circle) with the
  combined modulus 1/G_K = (1/G_1 + 1/G_2)/2, i.e. G_K = 2 G for a rigid indenter, and C11 = 5.20
  for a circular contact with nu = 0.5 (Kalker 1967, reproduced in Johnson, Contact Mechanics 1985,
  Table 8.1). Measured at xi = -1e-5 (full stick): 5.281, 5.266, 5.233 at n = 64, 128, 256 (a over
  21, 43, 85 cells): the error falls with the cell (1.6 %, 1.3 %, 0.6 %); tolerance 2 % at n = 64,
  and the refined grid closer;
* force control and creepage control give the same state; frictionless rolling is frictionless
  sliding (Hunter 1961); the transient tends to the steady state (the same discretisation: the
  steady one is the transient's fixed point);
* viscoelastic: a slow and a fast steady rolling equal the elastic ones with G(inf) and G(0).
"""
from dataclasses import replace

import numpy as np
import pytest

from viscontact.physics.materials import Material
from viscontact.physics.reference import hertz_from_load
from viscontact.problem.problem import PHASE_ROLLING, TangentialLoading, TimeStepping
from viscontact.running.loop import simulate
from viscontact.solvers.steady_rolling import creepage_sweep, solve_steady_rolling

from vc_testing import SEED_G0, SEED_LOAD, SEED_RADIUS, sphere_problem

G, W, MU, V = SEED_G0, SEED_LOAD, 0.3, 0.1
KALKER_C11 = 5.20  # circle, nu = 0.5 (Kalker 1967; Johnson 1985, Table 8.1)


def _rolling(n: int, creepage: float | None = -2e-3, force: float | None = None, *, material=None,
             friction: float = MU, widths: float = 0.0, speed: float = V, half_width: float = 1.5):
    """A rolling sphere problem on n x n cells of [-w a, w a]^2 (w: ``half_width``; a: Hertz with G(0),
    nu = 0.5), its transient ``widths`` contact diameters long (one cell per step)."""
    hz = hertz_from_load(W, SEED_RADIUS, G, 0.5)
    pb = sphere_problem(material or Material.elastic(G, 0.5), n, half_width * hz.radius, t_end=1.0, dt=1.0)
    dx = pb.grid.spacing
    steps = max(int(widths * 2 * hz.radius / dx), 1)
    tan = TangentialLoading("rolling", friction, rolling_speed=speed, creepage=creepage, tangential_force=force)
    return replace(pb, tangential=tan, time=TimeStepping(steps * dx / speed, dx / speed, "constant")), hz


def test_traction_saturates_at_mu_w_and_is_odd_in_the_creepage():
    pb, _ = _rolling(32)
    for xi in (-0.1, 0.1):
        rec = solve_steady_rolling(pb, creepage=xi)
        assert rec.friction_force == pytest.approx(-np.sign(xi) * MU * rec.load, rel=1e-9)
        assert rec.stick_ratio == 0.0 and rec.phase == PHASE_ROLLING
    small = creepage_sweep(pb, [-2e-3, 2e-3])
    assert 0 < small[0].friction_force < MU * W  # braking (xi < 0): the traction on the body in +x
    assert small[1].friction_force == pytest.approx(-small[0].friction_force, rel=1e-9)


def test_stick_region_at_the_leading_edge():
    pb, hz = _rolling(32)
    rec = solve_steady_rolling(pb, creepage=-2e-3)
    assert 0.5 < rec.stick_ratio < 1.0
    x = pb.grid.x
    contact = rec.pressure > 0
    for row in range(pb.grid.n):
        stuck, slipping = x[rec.stick[row]], x[contact[row] & ~rec.stick[row]]
        if stuck.size and slipping.size:
            assert stuck.min() > slipping.max()  # slip only behind the stick zone
    centroid = float((x[None, :] * rec.stick).sum() / rec.stick.sum())
    assert centroid > 0.05 * hz.radius


def test_creep_coefficient_of_kalkers_linear_theory():
    errors = []
    for n in (64, 128):
        pb, hz = _rolling(n)
        rec = solve_steady_rolling(pb, creepage=-1e-5)
        c11 = rec.friction_force / (-2 * G * hz.radius**2 * rec.creepage)
        errors.append(abs(c11 / KALKER_C11 - 1))
    assert errors[0] < 0.02 and errors[1] < errors[0], errors


def test_force_control_agrees_with_creepage_control():
    pb, _ = _rolling(32)
    held = solve_steady_rolling(pb, creepage=-2e-3)
    force_pb, _ = _rolling(32, creepage=None, force=held.friction_force)
    found = solve_steady_rolling(force_pb)
    assert found.creepage == pytest.approx(-2e-3, rel=1e-6)
    np.testing.assert_array_equal(found.stick, held.stick)
    # the transient under the held force finds the same creepage once steady
    transient, _ = _rolling(32, creepage=None, force=held.friction_force, widths=4)
    records = list(simulate(transient))
    assert np.isnan(records[0].creepage)  # nothing has rolled at t = 0
    assert records[-1].friction_force == pytest.approx(held.friction_force, rel=1e-8)
    assert records[-1].creepage == pytest.approx(-2e-3, rel=2e-3)


def test_transient_tends_to_the_steady_state():
    pb, _ = _rolling(32, widths=6)
    records = list(simulate(pb))
    steady = solve_steady_rolling(pb)
    assert records[0].friction_force == pytest.approx(0.0, abs=1e-12)  # at standstill: no traction yet
    last = records[-1]
    assert last.friction_force == pytest.approx(steady.friction_force, rel=2e-3)
    assert last.stick_ratio == pytest.approx(steady.stick_ratio, abs=0.01)
    assert all(r.phase == PHASE_ROLLING and r.creepage == -2e-3 for r in records)


def test_frictionless_rolling_is_frictionless_sliding():
    pb, _ = _rolling(32, friction=0.0, widths=1)
    sliding = replace(pb, tangential=TangentialLoading("frictionless_sliding", sliding_speed=V))
    rolled, slid = list(simulate(pb)), list(simulate(sliding))
    for a, b in zip(rolled, slid):
        np.testing.assert_array_equal(a.pressure, b.pressure)
        assert a.friction_force == 0.0 and a.hysteresis_force == b.hysteresis_force


@pytest.mark.parametrize("limit", ["slow", "fast"])
def test_viscoelastic_rolling_tends_to_the_elastic_limits(limit):
    """Zener, G(0)/G(inf) = 10, retardation time tau: rolling at V tau = 1e-4 a is relaxed (G(inf)), at
    V tau = 1e4 a glassy (G(0)); traction and stick ratio as the elastic ones (0.5 %)."""
    tau = 0.01
    material = Material.zener(G, G / 10, tau, 0.5)
    _, hz = _rolling(32)
    speed = (1e-4 if limit == "slow" else 1e4) * hz.radius / tau
    wide = 1.5 * 10 ** (1 / 3)  # the relaxed contact is 10^(1/3) times wider
    pb, _ = _rolling(48, material=material, speed=speed, half_width=wide)
    elastic, _ = _rolling(48, material=Material.elastic(G / 10 if limit == "slow" else G, 0.5), speed=speed,
                          half_width=wide)
    vis, ref = solve_steady_rolling(pb), solve_steady_rolling(elastic)
    assert vis.friction_force == pytest.approx(ref.friction_force, rel=5e-3)
    assert vis.contact_area == pytest.approx(ref.contact_area, rel=0.02)


@pytest.mark.parametrize("nu", [0.5, 0.3])
def test_viscoelastic_transient_tends_to_the_steady_state(nu):
    """Zener (G(0)/G(inf) = 10) at V tau = a(G(0)): the transient from standstill, 16 contact diameters
    on a domain wide enough for the wake ([-3.2 a, 3.2 a]^2, 64^2 cells), against the steady solver
    on the same grid (whose kernel holds the material's whole past). With nu = 0.3 both alternate the
    normal-tangential coupling, which here reverses the traction at this creepage (the coupling's
    own creep, Bentall & Johnson 1967). Measured: traction 0.12 % (nu = 0.5) and 1.3 % (0.3), F_T
    0.1 %, approach 0.05 %; tolerances 0.5 % and 2 %, 0.5 %, 0.2 %."""
    tau = 0.01
    hz = hertz_from_load(W, SEED_RADIUS, G, 0.5)
    material = Material.zener(G, G / 10, tau, nu)
    pb, _ = _rolling(64, material=material, speed=hz.radius / tau, widths=16, half_width=3 * 10 ** (1 / 3))
    pb = replace(pb, time=replace(pb.time, scheme="linear"))
    last = list(simulate(pb))[-1]
    steady = solve_steady_rolling(pb)
    assert last.friction_force == pytest.approx(steady.friction_force, rel=5e-3 if nu == 0.5 else 2e-2)
    assert last.hysteresis_force == pytest.approx(steady.hysteresis_force, rel=5e-3)
    assert last.delta_z == pytest.approx(steady.delta_z, rel=2e-3)


def test_a_checkpoint_of_a_rolling_state_resumes_bit_exact(tmp_path):
    """The state carries rolling's convected u_x and the last rigid creep: a run resumed from a
    checkpoint after step 5 under a held force repeats the uninterrupted one bit for bit."""
    from viscontact.io.checkpoint import load_checkpoint, save_checkpoint
    from viscontact.solvers.transient import steps

    pb, _ = _rolling(16, creepage=None, force=0.3 * MU * W, widths=2)
    run = list(steps(pb))
    save_checkpoint(tmp_path / "c.npz", pb, run[5][0])
    state, _ = load_checkpoint(tmp_path / "c.npz", pb)
    assert state.displacement_x is not None and state.rigid_x == run[5][0].rigid_x
    resumed = list(steps(pb, state=state))
    assert len(resumed) == len(run) - 6
    for (_, ours), (_, want) in zip(resumed, run[6:]):
        np.testing.assert_array_equal(ours.shear_x, want.shear_x)
        assert ours.creepage == want.creepage


def test_coupled_rolling_in_full_slip_is_steady_gross_sliding():
    """nu = 0.3, elastic: at a creepage far beyond the creep region every point slips, q_x = mu_f p
    (braking), so the coupled steady rolling state (the tangential and normal problems alternated) is
    the steady gross sliding one, which the sliding solver finds with the coupling inside its operator
    (K_zz + mu_f K_zx, another algorithm): the pressure shifted by the coupling as in sliding."""
    from viscontact.solvers.steady import solve_steady

    pb, _ = _rolling(32, material=Material.elastic(G, 0.3))
    rolling = solve_steady_rolling(pb, creepage=-0.2)
    sliding = solve_steady(replace(pb, tangential=TangentialLoading("gross_sliding", MU, sliding_speed=V)))
    frictionless = solve_steady(replace(pb, tangential=TangentialLoading("frictionless_sliding", sliding_speed=V)))
    assert rolling.stick_ratio == 0.0
    assert rolling.friction_force == pytest.approx(MU * W, rel=1e-9)
    peak = sliding.pressure.max()
    assert np.abs(rolling.pressure - sliding.pressure).max() < 1e-6 * peak
    assert rolling.delta_z == pytest.approx(sliding.delta_z, rel=1e-6)
    assert np.abs(sliding.pressure - frictionless.pressure).max() > 1e-3 * peak  # the coupling shifts it
