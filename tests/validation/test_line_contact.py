"""Line contacts (``grid.dimension = 1``, plane strain) against independent truth.

* Hertz line contact (Johnson, *Contact Mechanics*, §4.3): half-width a = sqrt(4 W R / (pi E*)),
  peak p0 = 2 W / (pi a) per unit length, and the approach relative to the datum at b = half_width
  from each line load, delta = (2 W / (pi E*)) (ln(2b/a) + 1/2), whose constant is checked here by
  quadrature (:func:`viscontact.physics.reference.line_approach`).
* A rigid cylinder sliding frictionless at a steady speed on a standard linear solid (Hunter 1961's
  problem: the isolated cylinder, no images) against an independent 1-D solver written here in plain
  numpy: the steady kernel in closed form (exponential integrals: for a line load under one retardation
  mode the memory integral of ln|d + xi| against exp(-xi/L)/L is ln|d| - exp(d/L) Ei(-d/L)),
  integrated over each cell by adaptive quadrature (scipy.integrate.quad), a dense matrix and a plain
  active-set solve, at v tau / a from 0.1 to 100; the package's steady state converges with the grid
  and tends to Hertz with G(inf) and G(0) in the slow and fast limits; the transient tends to it.
* Cattaneo's 2-D analogue of partial slip (Johnson §7.1): c/a = sqrt(1 - Q/(mu W)) at nu = 0.5.
"""
import math

import numpy as np
import pytest
import scipy.integrate
import scipy.special

from viscontact.io.case import Case
from viscontact.physics.reference import (
    StripPunch,
    hertz_line_from_approach,
    hertz_line_from_load,
    line_approach,
    line_cattaneo,
)
from viscontact.running.loop import simulate
from viscontact.solvers.steady import solve_steady

G0, G_INF, TAU, NU, R = 1.0e6, 1.0e5, 0.01, 0.5, 0.01
LOAD = 20.0  # N/m


def _case(n: int, half_width: float, *, material=None, mode="frictionless_sliding", speed=0.05, t_end=0.05,
          value=LOAD, nu=NU, **more) -> Case:
    material = material or {"type": "zener", "shear_modulus_instantaneous": G0, "shear_modulus_long_term": G_INF,
                            "retardation_time": TAU, "poisson_ratio": nu}
    data = {"title": "line", "material": material, "indenter": {"shape": "cylinder", "radius": R},
            "grid": {"n": n, "half_width": half_width, "dimension": 1},
            "normal": {"control": "load", "value": value},
            "tangential": {"mode": mode, **({"sliding_speed": speed} if mode != "none" else {})},
            "time": {"t_end": t_end}}
    for key, value_ in more.items():
        section, name = key.split("__")
        data.setdefault(section, {})[name] = value_
    return Case.from_dict(data)


# --- Hertz line contact ------------------------------------------------------------------------------

def test_line_approach_constant_by_quadrature():
    """int_-1^1 sqrt(1 - t^2) ln|t| dt = -(pi/2)(ln 2 + 1/2) behind the approach's closed form: the
    approach is u_z(0) of the Hertz pressure, computed here by quadrature of the line load's
    displacement -(2/(pi E*)) ln(|s|/b)."""
    a, b, w = 0.7e-3, 3e-3, 25.0
    e_star = 2 * G0 / (1 - 0.3)
    p0 = 2 * w / (np.pi * a)
    integral = 2 * scipy.integrate.quad(lambda s: p0 * math.sqrt(1 - (s / a) ** 2) * math.log(s / b), 0, a,
                                        points=[0.0], limit=200)[0]
    radius = np.pi * a**2 * e_star / (4 * w)  # the cylinder of this a and W
    assert -2 / (np.pi * e_star) * integral == pytest.approx(line_approach(a, radius, b), rel=1e-10)


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_hertz_line_contact(nu):
    """An elastic half-space under a rigid cylinder: half-width, peak pressure, approach (with the
    datum at half_width) and the pressure profile. Measured at n = 512 (a = 65 to 76 cells): a within
    0.6 cell (a count of cells), p0 3e-5, delta 7e-6, the profile within 1.3e-4 p0 inside 0.9 a (the
    square-root edge's cells err by up to 1.6 %)."""
    half_width = 1e-3
    case = _case(512, half_width, material={"type": "elastic", "shear_modulus": G0, "poisson_ratio": nu},
                 mode="none", t_end=1e-3, value=LOAD, time__dt=1e-3)
    pb = case.to_problem()
    rec = list(simulate(pb))[-1]
    hz = hertz_line_from_load(LOAD, R, G0, nu, half_width)
    dx, x = pb.grid.spacing, pb.grid.x
    assert rec.pressure.shape == (1, 512)
    assert rec.load == pytest.approx(LOAD, rel=1e-9)
    assert rec.contact_area / 2 == pytest.approx(hz.radius, abs=dx)
    assert rec.pressure.max() == pytest.approx(hz.peak_pressure, rel=2e-4)
    assert rec.delta_z == pytest.approx(hz.approach, rel=5e-5)
    inner = np.abs(x) < 0.9 * hz.radius
    np.testing.assert_allclose(rec.pressure[0][inner], hz.pressure(x)[inner], atol=7e-4 * hz.peak_pressure)


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_hertz_line_contact_under_displacement_control(nu):
    """The approach relative to the datum prescribed: the load per unit length that Hertz's line contact
    gives for it (:func:`~viscontact.physics.reference.hertz_line_from_approach`). Measured at n = 512:
    W within 8e-6, a within a cell."""
    half_width = 1e-3
    approach = hertz_line_from_load(LOAD, R, G0, nu, half_width).approach
    case = _case(512, half_width, material={"type": "elastic", "shear_modulus": G0, "poisson_ratio": nu},
                 mode="none", t_end=1e-3, value=approach, time__dt=1e-3, normal__control="displacement")
    pb = case.to_problem()
    rec = list(simulate(pb))[-1]
    hz = hertz_line_from_approach(approach, R, G0, nu, half_width)
    assert hz.load == pytest.approx(LOAD, rel=1e-12)
    assert rec.load == pytest.approx(hz.load, rel=5e-5)
    assert rec.contact_area / 2 == pytest.approx(hz.radius, abs=pb.grid.spacing)


# --- the strip punch (a flat punch in line contact) --------------------------------------------------

def _strip(n: int, material: dict, control: str, value: float, t_end: float = 1e-3, dt: float = 1e-3):
    return Case.from_dict({"title": "strip", "material": material, "indenter": {"shape": "flat_punch", "radius": 0.5e-3},
                           "grid": {"n": n, "half_width": 2e-3, "dimension": 1},
                           "normal": {"control": control, "value": value}, "tangential": {"mode": "none"},
                           "time": {"t_end": t_end, "dt": dt}}).to_problem()


def test_strip_punch_reference_is_consistent():
    """The strip's pressure integrates to W (quadrature), and its approach and load invert each other."""
    ref = StripPunch.from_load(30.0, 0.5e-3, 3e6, 2e-3)
    total = scipy.integrate.quad(lambda x: float(ref.pressure(x)), -0.5e-3, 0.5e-3, limit=400)[0]
    assert total == pytest.approx(30.0, rel=1e-6)
    assert StripPunch.from_approach(ref.approach, 0.5e-3, 3e6, 2e-3).load == pytest.approx(30.0, rel=1e-14)


def test_strip_punch_load_and_pressure_converge():
    """An elastic half-space under a rigid strip pushed to 10 um (relative to the datum at half_width):
    the load against delta = (2 W / (pi E*)) ln(2b/a) (Johnson §2.8) and the pressure inside 0.8 a against
    W / (pi sqrt(a^2 - x^2)), both converging at first order (the edges' singular pressure). Measured:
    load -0.26 %, -0.13 % at a/dx = 32, 64; pressure 1.9 %, 0.93 % of the centre's; the face the contact."""
    errors = []
    for n in (256, 512):
        pb = _strip(n, {"type": "elastic", "shear_modulus": G0, "poisson_ratio": 0.3}, "displacement", 10e-6)
        rec = list(simulate(pb))[-1]
        ref = StripPunch.from_approach(10e-6, 0.5e-3, 2 * G0 / 0.7, 2e-3)
        x = pb.grid.x
        inner = np.abs(x) < 0.8 * ref.half_width
        assert rec.contact_area == pytest.approx(2 * ref.half_width, abs=1e-12)
        errors.append((abs(rec.load / ref.load - 1),
                       np.abs(rec.pressure[0] - ref.pressure(x))[inner].max() / float(ref.pressure(0.0))))
    assert errors[0][0] < 4e-3 and errors[0][1] < 0.025
    assert errors[1][0] < 0.6 * errors[0][0] and errors[1][1] < 0.6 * errors[0][1]


def test_strip_punch_creeps_as_the_creep_compliance():
    """A strip under a held load on a Zener body: its face stays the contact, so delta(t)/delta(0) =
    J(t)/J(0) (measured 3e-9); the result's a0, p0 are the strip's half-width and centre pressure W/(pi a)."""
    from viscontact.problem.scales import hertz_scale

    material = {"type": "zener", "shear_modulus_instantaneous": G0, "shear_modulus_long_term": G_INF,
                "retardation_time": 1e-3, "poisson_ratio": 0.5}
    pb = _strip(512, material, "load", 20.0, t_end=5e-3, dt=2.5e-4)
    records = list(simulate(pb))
    t = np.array([r.t for r in records])
    creep = pb.material.creep_compliance(t)
    approach = np.array([r.delta_z for r in records])
    np.testing.assert_allclose(approach / approach[0], creep / creep[0], rtol=1e-7)
    assert hertz_scale(pb) == pytest.approx((0.5e-3, 20.0 / (np.pi * 0.5e-3)), rel=1e-14)


# --- the independent steady solver --------------------------------------------------------------------

def _memory_log(d: np.ndarray, length: float) -> np.ndarray:
    """int_0^inf exp(-xi/L)/L ln|d + xi| dxi = ln|d| - exp(d/L) Ei(-d/L) (d != 0; for large |d|/L the
    asymptotic series of exp(y) E1(y))."""
    y = np.asarray(d, dtype=float) / length
    out = np.empty_like(y)
    big = np.abs(y) > 40
    small = ~big
    out[small] = np.log(np.abs(d[small])) - np.exp(y[small]) * scipy.special.expi(-y[small])
    yb = y[big]
    series = sum(((-1) ** k * math.factorial(k)) / yb ** (k + 1) for k in range(12))  # exp(y) E1(y)
    out[big] = np.log(np.abs(d[big])) + series
    return out


def _independent_steady(n: int, half_width: float, speed: float, load: float):
    """Steady frictionless sliding of the rigid cylinder at ``speed`` on the Zener body, plane strain,
    nu = 0.5: (pressure (n,), x (n,), dx). Cell j carries p_j on [x_j - dx/2, x_j + dx/2]; the surface
    displacement at x_i is sum_j A_ij p_j with
    A_ij = -(1 - nu)/pi int_cell [ J0 ln|x_i - s| + (J_inf - J0) M(x_i - s) ] ds, M = :func:`_memory_log`
    (the material at x came from x + xi, a time xi / v ago). The constant datum drops out under load
    control (it shifts the approach only). Active set: solve on the contact set with sum p dx = W, drop
    p < 0, add gap < 0, until it settles."""
    dx = 2 * half_width / n
    x = -half_width + (np.arange(n) + 0.5) * dx
    j0, j_inf = 1 / G0, 1 / G_INF
    length = speed * TAU
    coef = -(1 - NU) / np.pi

    def column(offset: float) -> float:
        def f(s: float) -> float:
            return j0 * math.log(abs(offset - s)) + (j_inf - j0) * float(_memory_log(np.array([offset - s]), length)[0])

        lo, hi = -dx / 2, dx / 2
        pts = [p for p in (offset,) if lo < p < hi]
        return coef * scipy.integrate.quad(f, lo, hi, points=pts or None, limit=200, epsabs=0, epsrel=1e-12)[0]

    offsets = dx * np.arange(-(n - 1), n)
    table = np.array([column(o) for o in offsets])
    idx = np.arange(n)
    a_mat = table[(idx[:, None] - idx[None, :]) + n - 1]
    h0 = x**2 / (2 * R)
    active = np.abs(x) < 0.5 * half_width
    for _ in range(100):
        ia = np.flatnonzero(active)
        # [A_aa  -1] [p]   [-h0_a]
        # [dx    0 ] [d] = [W]
        m = np.zeros((ia.size + 1, ia.size + 1))
        m[:-1, :-1] = a_mat[np.ix_(ia, ia)]
        m[:-1, -1] = -1.0
        m[-1, :-1] = dx
        rhs = np.concatenate([-h0[ia], [load]])
        sol = np.linalg.solve(m, rhs)
        p = np.zeros(n)
        p[ia] = sol[:-1]
        gap = h0 - sol[-1] + a_mat @ p
        new = (active & (p > 0)) | (~active & (gap < 0))
        if np.array_equal(new, active):
            return p, x, dx
        active = new
    raise AssertionError("the independent active set did not settle")


def _edges(p: np.ndarray, x: np.ndarray, dx: float) -> tuple[float, float]:
    on = np.flatnonzero(p > 0)
    return x[on[0]] - dx / 2, x[on[-1]] + dx / 2


@pytest.mark.parametrize("deborah", [0.1, 1.0, 10.0, 100.0])
def test_steady_cylinder_on_zener_against_independent_solver(deborah):
    """mu_app = int p x dx / (R W) (the pressure on the cylinder's slope) and the contact edges of the
    package's steady state against the independent dense solve on the same cells, at v tau / a from 0.1
    to 100 (a the Hertz half-width with G(0)). The two share the cells only: kernels and solver differ."""
    n = 128
    a0 = hertz_line_from_load(LOAD, R, G0, NU, 1.0).radius
    a_inf = a0 * math.sqrt(G0 / G_INF)
    half_width = 2.2 * a_inf
    speed = deborah * a0 / TAU
    pb = _case(n, half_width, speed=speed).to_problem()
    rec = solve_steady(pb)
    p_ref, x, dx = _independent_steady(n, half_width, speed, LOAD)
    p = rec.pressure[0]
    np.testing.assert_allclose(p, p_ref, atol=1e-6 * p_ref.max())
    mu_ref = float(np.sum(p_ref * x) * dx / (R * LOAD))
    assert np.sum(p * x) * dx / (R * LOAD) == pytest.approx(mu_ref, rel=1e-5, abs=1e-7)
    assert rec.mu_app == pytest.approx(mu_ref, rel=0.02, abs=2e-4)  # F_T by finite differences of u_z
    assert _edges(p, x, dx) == pytest.approx(_edges(p_ref, x, dx), abs=1e-12)


@pytest.mark.parametrize("deborah", [0.1, 1.0, 10.0, 100.0])
def test_steady_line_contact_is_converged_at_a_modest_grid(deborah):
    """mu_app and the contact edges at n = 512 (a0 = 36 cells) against n = 4096 on the same domain,
    v tau / a0 from 0.1 to 100: measured mu_app within 5.8e-4 (relative), the edges within 0.017 a0
    (under a cell of the coarse grid, 0.027 a0)."""
    a0 = hertz_line_from_load(LOAD, R, G0, NU, 1.0).radius
    half_width = 2.2 * a0 * math.sqrt(G0 / G_INF)
    out = []
    for n in (512, 4096):
        pb = _case(n, half_width, speed=deborah * a0 / TAU).to_problem()
        rec = solve_steady(pb)
        out.append((rec.mu_app, _edges(rec.pressure[0], pb.grid.x, pb.grid.spacing)))
    (mu, edges), (mu_fine, edges_fine) = out
    assert mu == pytest.approx(mu_fine, rel=1e-3)
    assert edges == pytest.approx(edges_fine, abs=0.03 * a0)


def test_steady_line_contact_converges_and_has_the_elastic_limits():
    """mu_app converges with the grid (differences shrinking by at least 1.8 per halving of dx), and
    the slow and fast limits are Hertz's with G(inf) and G(0): the contact half-widths within 1.5 cells,
    mu_app -> 0."""
    a0 = hertz_line_from_load(LOAD, R, G0, NU, 1.0).radius
    a_inf = a0 * math.sqrt(G0 / G_INF)
    half_width = 2.2 * a_inf
    speed = 1.0 * a0 / TAU
    mus = []
    for n in (128, 256, 512, 1024):
        rec = solve_steady(_case(n, half_width, speed=speed).to_problem())
        mus.append(rec.mu_app)
    diffs = np.abs(np.diff(mus))
    assert diffs[1] < diffs[0] / 1.8 and diffs[2] < diffs[1] / 1.8, mus
    for deborah, a_expected in ((1e-4, a_inf), (1e4, a0)):
        pb = _case(512, half_width, speed=deborah * a0 / TAU).to_problem()
        rec = solve_steady(pb)
        assert rec.contact_area / 2 == pytest.approx(a_expected, abs=1.5 * pb.grid.spacing)
        assert abs(rec.mu_app) < 2e-3


def test_transient_sliding_tends_to_the_steady_state():
    """Sliding from rest at v tau / a0 = 1 for 12 retardation times: the last step's mu_app, contact
    width and centroid are the steady state's, and its peak pressure tends to the steady one as the
    grid (and with it the time step, one cell of sliding) refines. Measured: mu_app within 2e-4, the
    same cells in contact, the centroid within 1e-3 cell, the peak 1.4 % then 0.38 % off at n = 512 and
    1024 (the transient's first-order time scheme). The domain, 6 relaxed half-widths each side,
    keeps the wake (wake_loss 0)."""
    a0 = hertz_line_from_load(LOAD, R, G0, NU, 1.0).radius
    half_width = 6 * a0 * math.sqrt(G0 / G_INF)
    peak_error = []
    for n in (512, 1024):
        pb = _case(n, half_width, speed=a0 / TAU, t_end=12 * TAU).to_problem()
        last = list(simulate(pb))[-1]
        steady = solve_steady(pb)
        dx = pb.grid.spacing
        assert last.wake_loss < 1e-3
        assert last.mu_app == pytest.approx(steady.mu_app, rel=1e-3)
        assert last.contact_area == pytest.approx(steady.contact_area, abs=dx)
        assert last.contact_shift - last.frame_offset == pytest.approx(steady.contact_shift, abs=0.05 * dx)
        peak_error.append(abs(last.pressure.max() / steady.pressure.max() - 1))
    assert peak_error[0] < 0.02 and peak_error[1] < peak_error[0] / 2.5


def test_gross_sliding_with_the_coupling_tends_to_its_steady_state():
    """Gross sliding (mu_f = 0.5) at nu = 0.3 on the Zener body, the normal-tangential coupling of plane
    strain (u_z of q_x ~ (1 - 2 nu) sgn) included in both the transient and the steady kernel: the same
    mu_app after 12 tau (measured 4e-5) and contact width; the coupling matters (mu_app 0.0109 with,
    0.0223 without it)."""
    nu = 0.3
    a0 = hertz_line_from_load(LOAD, R, G0, nu, 1.0).radius
    half_width = 6 * a0 * math.sqrt(G0 / G_INF)
    more = dict(mode="gross_sliding", speed=a0 / TAU, t_end=12 * TAU, nu=nu, tangential__friction_coefficient=0.5)
    pb = _case(512, half_width, **more).to_problem()
    last = list(simulate(pb))[-1]
    steady = solve_steady(pb)
    assert last.mu_app == pytest.approx(steady.mu_app, rel=3e-4)
    assert last.contact_area == pytest.approx(steady.contact_area, abs=pb.grid.spacing)
    uncoupled = solve_steady(_case(512, half_width, solver__coupling=False, **more).to_problem())
    assert abs(uncoupled.mu_app - steady.mu_app) > 0.5 * steady.mu_app


# --- Cattaneo's partial slip in line contact -----------------------------------------------------------

def test_line_cattaneo_partial_slip():
    """An elastic half-space, nu = 0.5 (no coupling), held load and a growing tangential displacement:
    the force-displacement curve (relative to the datum) and the stick half-width c/a = sqrt(1 - Q/(mu W))
    against Cattaneo's line contact (Johnson §7.1). Measured at n = 512 (a = 43 cells): delta_x(Q)
    within 1.4e-4, c within 0.7 cell (a count of cells)."""
    mu, half_width, n = 0.3, 1.5e-3, 512
    ref = line_cattaneo(LOAD, R, mu, G0, 0.5, half_width)
    dstar = float(ref.displacement(mu * LOAD))
    steps = 40
    case = _case(n, half_width, material={"type": "elastic", "shear_modulus": G0, "poisson_ratio": 0.5},
                 mode="partial_slip", t_end=1.0, speed=2 * half_width / n * steps, time__dt=1.0 / steps,
                 tangential__friction_coefficient=mu, tangential__displacement_rate=0.9 * dstar)
    pb = case.to_problem()
    records = list(simulate(pb))
    dx = pb.grid.spacing
    checked = 0
    for rec in records[5:]:
        q = rec.friction_force
        assert float(ref.displacement(q)) == pytest.approx(rec.delta_x, rel=1e-3)
        stick = np.flatnonzero(rec.stick[0])
        if stick.size:
            c = (pb.grid.x[stick[-1]] - pb.grid.x[stick[0]] + dx) / 2
            assert c == pytest.approx(float(ref.stick_ratio_from_force(q)) * ref.contact_half_width, abs=dx)
            checked += 1
    assert checked > 20
