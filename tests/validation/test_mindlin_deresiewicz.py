"""Partial slip of a growing contact against Mindlin-Deresiewicz: ``tangential.slip = "incremental"``.

The seed's stick condition (Eqs. 9, 11, ``slip = "total"``) asks s_x = u_x - delta_x = 0 of every
stuck point at every step, without memory: exact while the contact keeps its points and the loading
is monotonic (a held approach: Cattaneo-Mindlin, tests/validation/test_cattaneo_mindlin.py), but a
point entering a growing contact is forced to u_x = delta_x as if it had stuck since t = 0. The
incremental condition keeps each stuck point's s_x (its change over a step is zero) and lets a
point enter the contact where it is.

Truth (Mindlin & Deresiewicz 1953; Johnson, Contact Mechanics, Sec. 7.4), exact for nu = 0.5 (no
normal/tangential coupling): while W(t) and delta_x(t) both increase with
lambda = dQ/dW = (8 G a / (2 - nu)) d delta_x / dW < mu_f, nothing slips (stick ratio 1) and
Q(t) = int 8 G a(s) / (2 - nu) d delta_x(s), a the Hertz radius of W(s). Viscoelastic, under a held
load (creep grows the contact; the correspondence principle for a growing contact, Graham's
condition, holds for each increment): Q(t) = int_0^t G(t - s) (16 a(s) / 3) d delta_x(s), with
a(s)^3 = 3 R W J(s) / 16 (nu = 0.5), while lambda < mu_f.
"""
import dataclasses

import numpy as np
import pytest

from viscontact.errors import ViscontactWarning
from viscontact.physics.materials import Material
from viscontact.problem.problem import PHASE_PARTIAL_SLIP, PiecewiseLinear
from viscontact.running.loop import simulate

from vc_testing import SEED_RADIUS as R, sphere_problem

MU, RATE = 0.5, 5e-4  # friction coefficient, d delta_x / dt [m/s]


def _run(problem, slip: str):
    problem = dataclasses.replace(problem, tangential=dataclasses.replace(problem.tangential, slip=slip))
    return list(simulate(problem))


def _partial_slip(material, n, half_width, dt, t_end, **normal):
    speed = 2 * half_width / n / dt  # one cell per step once sliding (it does not slide here)
    return sphere_problem(material, n, half_width, mode="partial_slip", friction=MU, rate=RATE, speed=speed,
                          t_end=t_end, dt=dt, scheme="linear", **normal)


# --- elastic, rising load ---------------------------------------------------------------------------

G, W0, W1, T = 1e6, 0.05, 0.2, 0.02


def mindlin_deresiewicz_force(t: np.ndarray) -> np.ndarray:
    """Q(t) = int_0^t 8 G a(s) / (2 - nu) RATE ds, W = W0 + (W1 - W0) s / T, a = (3 W R / (4 E*))^(1/3),
    E* = 4 G (nu = 0.5): int W^(1/3) ds = 3/4 (W(t)^(4/3) - W0^(4/3)) / (dW/dt)."""
    w = W0 + (W1 - W0) * t / T
    c = (3 * R / (16 * G)) ** (1 / 3)  # a = c W^(1/3)
    return 8 * G * c / 1.5 * RATE * 0.75 * (w ** (4 / 3) - W0 ** (4 / 3)) / ((W1 - W0) / T)


def test_rising_load_sticks_everywhere_and_follows_mindlin_deresiewicz():
    """Elastic, G = 1 MPa, nu = 0.5, R = 10 mm, mu_f = 0.5, W from 0.05 to 0.2 N over 20 ms (a from
    24 to 38 cells at n = 128), delta_x at 0.5 mm/s: lambda <= 0.26 < mu_f, so nothing slips in
    truth.

    Incremental: Q within 1 % of the integral at every step, stick ratio >= 0.97. The error is the
    time step's: a point entering the contact during a step sticks at its position at the step's
    start, dragged by that step's delta_x increment (first order; the points that slip are such
    entering ones, at the edge). Measured at 20 ms (4 / 10 ms): n = 64, 128, 256 at dt = 1 ms
    +0.64 %, +0.62 %, +0.64 % (+1.2 / +0.9 %); dt = 0.5 ms +0.31 % at n = 128 (here; +0.57 / +0.45 %,
    stick >= 0.98); dt = 0.25 ms +0.17 % at n = 128 and 256 (+0.32 / +0.24 %). On a grid too coarse
    for the contact's growth (n = 64, dt = 0.25 ms: a ring of points enters every 10 steps, the
    discrete contact radius lagging the Hertz one) it is -4 %.

    Total (the seed's, the default): each entering point forced to u_x = delta_x, the contact too
    stiff: here Q +4.8 / +8.3 / +10.7 % at 4 / 10 / 20 ms and stick ratio 0.91 / 0.82 / 0.74
    (n = 64, dt = 1 ms: +4.9 / +7.5 / +10.7 %, the error grid-independent); and the run warns that
    the contact grew under the total slip."""
    problem = _partial_slip(Material.elastic(G, 0.5), 128, 1.2e-3, 5e-4, T, value=PiecewiseLinear((0.0, T), (W0, W1)))
    incremental = _run(problem, "incremental")
    with pytest.warns(ViscontactWarning, match="contact grew by .* tangential.slip = \"incremental\""):
        total = _run(problem, "total")
    t = np.array([r.t for r in incremental])
    truth = mindlin_deresiewicz_force(t)
    assert all(r.phase == PHASE_PARTIAL_SLIP for r in incremental + total)
    q_inc = np.array([r.friction_force for r in incremental])
    q_tot = np.array([r.friction_force for r in total])
    later = t >= 1e-3
    assert np.max(np.abs(q_inc[later] / truth[later] - 1)) < 0.01
    assert min(r.stick_ratio for r in incremental) >= 0.97
    # the seed's total slip, for the record: too stiff, and slipping where nothing slips
    assert q_tot[-1] / truth[-1] - 1 > 0.08 and total[-1].stick_ratio < 0.8


# --- viscoelastic, held approach: nothing enters the contact ----------------------------------------

G0, GINF, TAU_RET = 1e6, 0.25e6, 0.01  # Zener: G(0), G(inf), retardation time [s]


def test_held_approach_incremental_equals_total():
    """Zener, nu = 0.5, held approach (a = 0.6 mm for all t: nothing enters the contact, the slip
    zone spreads inwards under a monotonic delta_x), partial slip over 30 ms: the two conditions pose
    the same problem at every step (a stuck point has s_x = 0 in both; the incremental one adds the
    previous s_x, 0 where stuck, and the slip points' s_x, which the bounds make irrelevant), so they
    agree to the solver's tolerance (solver.tolerance = 1e-8; measured 1.0e-9 on Q and 1.1e-8 mu_f
    max p on the shear, the CGs starting from right-hand sides that differ by round-off): 1e-7."""
    a = 0.6e-3
    material = Material.zener(G0, GINF, TAU_RET, 0.5)
    problem = _partial_slip(material, 64, 1.2e-3, 2.5e-4, 0.03, control="displacement", value=a * a / R)
    incremental, total = _run(problem, "incremental"), _run(problem, "total")
    assert sum(r.phase == PHASE_PARTIAL_SLIP for r in total) > 100 and total[-1].stick_ratio < 0.6
    for ours, want in zip(incremental, total):
        assert ours.phase == want.phase and ours.contact_area == want.contact_area
        assert ours.friction_force == pytest.approx(want.friction_force, rel=1e-7, abs=1e-14)
        np.testing.assert_allclose(ours.shear_x, want.shear_x, rtol=0, atol=1e-7 * MU * want.pressure.max())


# --- viscoelastic, held load: creep grows the contact -----------------------------------------------

def test_creep_under_a_held_load_follows_the_correspondence_integral():
    """Zener (G(0) = 1 MPa, G(inf) = 0.25 MPa, retardation 10 ms), nu = 0.5, W = 0.1152 N held, delta_x
    at 0.5 mm/s for 18 ms: a grows by 52 % (J(t)^(1/3)), lambda = dQ/dW along the creep stays
    < 0.43 < mu_f: no slip in truth. Q(t) = int_0^t G(t - s) (16 a(s) / 3) RATE ds.

    Incremental: within 1.5 % of it from 1 ms on (measured +0.94 % at 2 ms falling to +0.12 % at
    18 ms, n = 64, dt = 0.25 ms: the entering points' one-step drag as in the elastic test), stick
    ratio >= 0.95. Total: +6.6 % at 2 ms, up to +10.7 % at 6 ms, and stick ratio 0.87-0.94."""
    from scipy.integrate import quad

    W = 0.1152
    material = Material.zener(G0, GINF, TAU_RET, 0.5)
    problem = _partial_slip(material, 64, 1.6e-3, 2.5e-4, 0.018, value=W)
    incremental = _run(problem, "incremental")
    with pytest.warns(ViscontactWarning, match="contact grew"):
        total = _run(problem, "total")

    def radius(s):
        return (3 * R * W * float(material.creep_compliance(s)) / 16) ** (1 / 3)

    def truth(t):
        return quad(lambda s: float(material.relaxation_modulus(t - s)) * 16 * radius(s) * RATE / 3, 0, t,
                    limit=200)[0]

    later = [(i, r) for i, r in enumerate(incremental) if r.t >= 1e-3]
    errors = np.array([r.friction_force / truth(r.t) - 1 for _, r in later])
    assert np.max(np.abs(errors)) < 0.015, errors
    assert min(r.stick_ratio for r in incremental) >= 0.95
    assert incremental[-1].contact_area > 2.2 * incremental[0].contact_area  # (1.52)^2: the contact grew
    worst = max(total[i].friction_force / truth(r.t) - 1 for i, r in later)
    assert worst > 0.08
