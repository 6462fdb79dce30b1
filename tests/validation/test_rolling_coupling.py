"""The normal-tangential coupling in rolling with partial slip (nu < 0.5), in line contact.

A rigid cylinder rolls on an elastic half-plane with nu = 0.3 at a braking creepage that leaves a stick
zone (xi = -0.02: 68 % of the contact sticks). In plane strain a line traction Q' on the body displaces
the surface normally by u_z = +(1 - 2 nu)/(4 G) Q' sgn(x) (Johnson 1985, Eq. 2.20): with the braking
traction q_x > 0 the surface ahead of the load is pushed in and that behind it lifted, so the pressure
moves backward (towards -x), as in partial slip (the sliding test of the coupling,
``test_cattaneo_mindlin.test_coupling_shifts_pressure_against_the_shear``). The coupling also changes
the traction itself (its own creep, Bentall & Johnson 1967): 396 N/m coupled against 600 N/m
uncoupled at this creepage.

Independent truth: the same discrete problem solved here in plain numpy by another algorithm: the
plane-strain strip influence coefficients written from Johnson's Eqs. 2.19-2.20 (with the grid's
datum), the pressure, the traction and the approach of every point in one dense monolithic system
(no alternation of the normal and tangential problems), solved directly (no Krylov), inside a
primal-dual active set on the contact and stick sets. Measured at 128 cells on [-2a, 2a]: pressure
8.9e-10 and traction 2.7e-10 of the peak pressure apart, the same stick map; the contact shift
-0.0535 a coupled, 1e-15 a uncoupled. The transient from standstill equals the steady state after
four contact widths to 3e-7 (traction) and 7e-7 of the peak pressure.
"""
import numpy as np
import pytest

from viscontact.physics.reference import carter
from viscontact.running.loop import simulate
from viscontact.solvers.steady_rolling import solve_steady_rolling
from vc_testing import rolling_cylinder_case

G, W, R, MU, V, NU, XI = 20e6, 2000.0, 0.01, 0.3, 0.1, 0.3, -0.02  # Pa, N/m, m, -, m/s, -, -
A = carter(W, R, MU, G, 0.5).half_width  # Hertz half-width [m] with nu = 0.5, the domain's scale


def _problem(n: int, coupling: bool = True, widths: float = 1.0):
    return rolling_cylinder_case(n, shear_modulus=G, poisson_ratio=NU, radius=R, load=W, speed=V, friction=MU,
                                 half_width=2.0 * A, held=f"creepage = {XI!r}", t_end=widths * 2 * A / V,
                                 extra=f"[solver]\ncoupling = {str(coupling).lower()}\n").to_problem()


def _dense_rolling(x: np.ndarray, gap: np.ndarray, datum: float, creep: float):
    """Steady coupled rolling on the line grid x [m] (cell centres) with the gap h0 [m], by a dense
    monolithic active set: returns (p [Pa], q_x [Pa], delta [m], stick)."""
    n, dx = x.size, x[1] - x[0]
    d, h = x[:, None] - x[None, :], dx / 2

    def log_primitive(s):  # int ln(|s|/b) ds
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(s == 0, 0.0, s * np.log(np.abs(s) / datum) - s)

    log_strip = log_primitive(d + h) - log_primitive(d - h)
    sign_strip = np.abs(d + h) - np.abs(d - h)
    k_zz = k_xx = -(1 - NU) / (np.pi * G) * log_strip  # Johnson Eq. 2.19 over a strip
    k_zx = (1 - 2 * NU) / (4 * G) * sign_strip          # Eq. 2.20: u_z of q_x ...
    k_xz = -k_zx                                        # ... and u_x of p
    diff = np.eye(n) - np.eye(n, k=1)                   # u(x) - u(x + dx), 0 at the leading edge
    diff[-1, -1] = 0.0
    slip_q, slip_p = diff @ k_xx, diff @ k_xz
    contact = gap < gap.min() + 0.3 * np.ptp(gap)
    stick, side = contact.copy(), np.zeros(n)
    for _ in range(50):
        c = np.flatnonzero(contact)
        m = c.size
        system, rhs = np.zeros((2 * m + 1, 2 * m + 1)), np.zeros(2 * m + 1)
        system[:m, :m], system[:m, m:2 * m], system[:m, 2 * m] = k_zz[np.ix_(c, c)], k_zx[np.ix_(c, c)], -1.0
        rhs[:m] = -gap[c]                                       # h0 + u_z - delta = 0 in contact
        for r, i in enumerate(c):
            if stick[i]:                                        # s = D u_x + creep = 0
                system[m + r, :m], system[m + r, m:2 * m] = slip_p[i, c], slip_q[i, c]
                rhs[m + r] = -creep
            else:                                               # q = -mu p sgn(s)
                system[m + r, m + r], system[m + r, r] = 1.0, MU * side[i]
        system[2 * m, :m] = dx
        rhs[2 * m] = W
        sol = np.linalg.solve(system, rhs)
        p, q = np.zeros(n), np.zeros(n)
        p[c], q[c], delta = sol[:m], sol[m:2 * m], sol[2 * m]
        opening = gap + k_zz @ p + k_zx @ q - delta
        slip = slip_q @ q + slip_p @ p + creep
        new_contact = (contact & (p > 0)) | (~contact & (opening < 0))
        leave, join = stick & (np.abs(q) > MU * p), contact & ~stick & (side * slip < 0)
        new_stick = ((stick & ~leave) | join) & new_contact
        entering = new_contact & ~contact                       # enters slipping as it slips now
        side = np.where(leave, -np.sign(q), np.where(entering, np.sign(slip), np.where(new_stick, 0.0, side)))
        if np.array_equal(new_contact, contact) and np.array_equal(new_stick, stick):
            return p, q, delta, stick
        contact, stick = new_contact, new_stick
    raise AssertionError("the dense active set did not settle")


def test_coupled_partial_slip_rolling_shifts_the_pressure_backward_as_the_dense_solve():
    pb = _problem(128)
    steady = solve_steady_rolling(pb)
    p, q, delta, stick = _dense_rolling(pb.grid.x, pb.gap[0], pb.grid.datum_distance, XI * pb.grid.spacing)
    peak = p.max()
    assert 0.3 < steady.stick_ratio < 0.9 and steady.friction_force > 0  # partial slip, braking
    np.testing.assert_array_equal(steady.stick[0], stick)
    assert np.abs(steady.pressure[0] - p).max() < 1e-8 * peak
    assert np.abs(steady.shear_x[0] - q).max() < 1e-8 * peak
    assert steady.delta_z == pytest.approx(delta, rel=1e-9)
    x = pb.grid.x
    assert steady.contact_shift == pytest.approx(float((x * p).sum() / p.sum()), abs=1e-8 * A)
    uncoupled = solve_steady_rolling(_problem(128, coupling=False))
    assert abs(uncoupled.contact_shift) < 1e-9 * A
    assert -0.1 * A < steady.contact_shift < -0.02 * A  # backward, against the braking traction
    assert steady.friction_force < 0.8 * uncoupled.friction_force  # the coupling's own creep


def test_coupled_line_rolling_transient_equals_the_steady_state():
    pb = _problem(128, widths=4)
    last = list(simulate(pb))[-1]
    steady = solve_steady_rolling(pb)
    assert last.friction_force == pytest.approx(steady.friction_force, rel=2e-6)
    assert np.abs(last.pressure - steady.pressure).max() < 5e-6 * steady.pressure.max()
    assert last.contact_shift == pytest.approx(steady.contact_shift, rel=2e-6)
    np.testing.assert_array_equal(last.stick, steady.stick)
