"""Hunter's (1961) isolated rigid cylinder on a standard linear solid, steady, against the package.

The reference, :func:`viscontact.physics.reference.hunter_cylinder`, is Hunter's problem in closed form
(Chebyshev coefficients from modified Bessel functions) with one numerical root, the contact's
half-width; it shares no code with the grid solver. Here it is checked on its own (the hereditary
slope condition by direct quadrature, the load, the elastic limits), then the steady line-contact
solver (``grid.dimension = 1``, ``shape = "cylinder"``, frictionless sliding on a Zener body, through
the public case API) is held to it at v tau / a0 = 0.1, 1, 10, 100.

Conventions: tau is the retardation (creep) time, a0 the Hertz line-contact half-width with G(0) (the
results' a0), G(0)/G(inf) = 10, nu = 0.5, so the relaxed half-width is sqrt(10) a0. The cylinder moves
towards +x; mu_app = int p x dx / (R W) > 0, the contact edges (-b, a') with a' the leading edge.

"The default resolution" is the shipped roller case's: a0 spans 36 cells (n = 1024 on +-8 mm there;
here n = 512 on +-2.2 relaxed half-widths, dx = 0.0272 a0). The package's contact is a set of cells,
so its edges (the outer faces of the first and last cell in contact) are known to within a cell: they
are held to a cell (dx) and to 1 % of the contact width; mu_app to 1e-3 (measured 6e-4 at worst).
"""
import itertools
import math

import numpy as np
import pytest
import scipy.integrate

import viscontact as vc
from viscontact.io.case import Case
from viscontact.physics.reference import hertz_line_from_load, hunter_cylinder
from viscontact.solvers.steady import solve_steady

G0, G_INF, TAU, NU, R = 1.0e6, 1.0e5, 0.01, 0.5, 0.01
LOAD = 20.0  # N/m
A0 = hertz_line_from_load(LOAD, R, G0, NU, 1.0).radius  # m, Hertz with G(0)
A_INF = A0 * math.sqrt(G0 / G_INF)
HALF_WIDTH = 2.2 * A_INF
DEBORAHS = [0.1, 1.0, 10.0, 100.0]


def _hunter(deborah: float):
    return hunter_cylinder(LOAD, R, G0, G_INF, TAU, NU, deborah * A0 / TAU)


def _steady(n: int, deborah: float):
    """The package's steady state: (mu_app, (trailing, leading) edge [m], dx [m])."""
    case = Case.from_dict({
        "title": "hunter", "indenter": {"shape": "cylinder", "radius": R},
        "material": {"type": "zener", "shear_modulus_instantaneous": G0, "shear_modulus_long_term": G_INF,
                     "retardation_time": TAU, "poisson_ratio": NU},
        "grid": {"n": n, "half_width": HALF_WIDTH, "dimension": 1},
        "normal": {"control": "load", "value": LOAD},
        "tangential": {"mode": "frictionless_sliding", "sliding_speed": deborah * A0 / TAU},
        "time": {"t_end": 0.05}})
    pb = case.to_problem()
    rec = solve_steady(pb)
    x, dx = pb.grid.x, pb.grid.spacing
    on = np.flatnonzero(rec.pressure[0] > 0)
    return rec.mu_app, (x[on[0]] - dx / 2, x[on[-1]] + dx / 2), dx


# --- the reference on its own --------------------------------------------------------------------

@pytest.mark.parametrize("deborah", [1.0, 10.0])
def test_hunter_pressure_satisfies_the_hereditary_slope_condition(deborah):
    """The reference's pressure put back into the steady hereditary integral, by direct quadrature
    (no Chebyshev or Bessel algebra): w'(x) = -(1 - nu) [J0 H(x) + (J_inf - J0) int_0^inf e^-u
    H(x + L u) du], H = (1/pi) PV int p(s)/(x - s) ds (Cauchy-weighted quad), is -x/R at a point
    inside the contact (measured 1e-15 of a'/R); the pressure integrates to W and is >= 0 throughout."""
    ref = _hunter(deborah)
    lo, hi, length = ref.trailing_edge, ref.leading_edge, deborah * A0

    def hilbert(x: float) -> float:
        if lo < x < hi:
            val = scipy.integrate.quad(lambda s: float(ref.pressure(np.array([s]))[0]), lo, hi, weight="cauchy",
                                       wvar=x, limit=400, epsabs=0, epsrel=1e-10)[0]
            return -val / np.pi  # quad's Cauchy weight is 1/(s - x)
        return scipy.integrate.quad(lambda s: float(ref.pressure(np.array([s]))[0]) / (x - s), lo, hi, limit=400,
                                    epsabs=0, epsrel=1e-10)[0] / np.pi

    def ahead(x: float) -> float:
        """int_0^inf e^-u H(x + L u) du, split where x + L u leaves the contact (a sqrt cusp of H)."""
        u_edge = (hi - x) / length
        inner = scipy.integrate.quad(lambda u: math.exp(-u) * hilbert(x + length * u), 0, u_edge, limit=200,
                                     epsabs=0, epsrel=1e-9)[0]
        outer = scipy.integrate.quad(lambda s: 2 * s * math.exp(-(u_edge + s * s)) * hilbert(hi + length * s * s),
                                     0, np.inf, limit=200, epsabs=0, epsrel=1e-9)[0]
        return inner + outer

    def slope(x: float) -> float:
        return -(1 - NU) * (hilbert(x) / G0 + (1 / G_INF - 1 / G0) * ahead(x))

    x = lo + 0.6 * (hi - lo)
    assert slope(x) == pytest.approx(-x / R, abs=1e-10 * hi / R)
    load = scipy.integrate.quad(lambda s: float(ref.pressure(np.array([s]))[0]), lo, hi, limit=200)[0]
    assert load == pytest.approx(LOAD, rel=1e-9)
    assert ref.pressure(np.linspace(lo, hi, 2001)).min() >= 0.0


def test_hunter_tends_to_hertz_in_the_slow_and_fast_limits():
    """v tau / a0 = 1e-3: Hertz's line contact with G(inf) (edges +-a_inf within 3e-4, mu_app 2e-5);
    1e4: with G(0) (edges +-a0 within 5e-3, mu_app 1e-4). In between the contact shifts ahead."""
    slow, fast = _hunter(1e-3), _hunter(1e4)
    assert (slow.trailing_edge, slow.leading_edge) == pytest.approx((-A_INF, A_INF), rel=5e-4)
    assert (fast.trailing_edge, fast.leading_edge) == pytest.approx((-A0, A0), rel=6e-3)
    assert 0 < slow.mu_app < 3e-5 and 0 < fast.mu_app < 2e-4
    mid = _hunter(3.0)
    assert mid.centre > 0.9 * A0 and mid.mu_app > 0.03


def test_hunter_depends_on_the_dimensionless_groups_alone():
    """Another load, radius, moduli and time with the same G(0)/G(inf) and v tau / a0 (the shipped
    roller's W, R, G, tau): the same mu_app R / a0 and edges / a0 (measured 4e-16); mu_app R / a0 peaks
    at 1.527 near v tau / a0 = 4.27 (between its values at 3 and 6)."""
    load, radius, g0, tau = 2000.0, 0.02, 2.0e7, 1.0e-3
    a0 = hertz_line_from_load(load, radius, g0, NU, 1.0).radius
    for deborah in (0.5, 4.27):
        ref, other = _hunter(deborah), hunter_cylinder(load, radius, g0, g0 * G_INF / G0, tau, NU, deborah * a0 / tau)
        assert other.mu_app * radius / a0 == pytest.approx(ref.mu_app * R / A0, rel=1e-8)
        assert (other.trailing_edge / a0, other.leading_edge / a0) == pytest.approx(
            (ref.trailing_edge / A0, ref.leading_edge / A0), rel=1e-8)
    peak = _hunter(4.27).mu_app
    assert peak * R / A0 == pytest.approx(1.5274, abs=1e-4)
    assert peak > max(_hunter(3.0).mu_app, _hunter(6.0).mu_app)


# --- the package's steady line-contact solver against it ------------------------------------------

@pytest.mark.parametrize("deborah", DEBORAHS)
def test_steady_cylinder_on_zener_against_hunter(deborah):
    """At the default resolution (a0 = 36 cells): mu_app within 1e-3 (measured at most 6.2e-4, at
    v tau / a0 = 0.1), each edge within a cell and within 1 % of the contact width (measured at most
    0.66 dx, 0.45 % of the width)."""
    ref = _hunter(deborah)
    mu, (lo, hi), dx = _steady(512, deborah)
    width = ref.leading_edge - ref.trailing_edge
    assert mu == pytest.approx(ref.mu_app, rel=1e-3)
    for edge, exact in ((lo, ref.trailing_edge), (hi, ref.leading_edge)):
        assert abs(edge - exact) < dx
        assert abs(edge - exact) < 0.01 * width


@pytest.mark.parametrize("deborah", DEBORAHS)
def test_steady_cylinder_converges_to_hunter(deborah):
    """mu_app's error against Hunter falls at each halving of dx (n = 256 to 2048, a0 = 18 to 147
    cells) and by more than 10 over the three (measured 30 to 77); the edges stay within a cell at
    each n, and their error at n = 2048 is under a third of that at 256 (measured 6 to 17
    times smaller)."""
    ref = _hunter(deborah)
    mu_errors, edge_errors = [], []
    for n in (256, 512, 1024, 2048):
        mu, (lo, hi), dx = _steady(n, deborah)
        mu_errors.append(abs(mu / ref.mu_app - 1))
        edge_errors.append(max(abs(lo - ref.trailing_edge), abs(hi - ref.leading_edge)))
        assert edge_errors[-1] < dx
    assert all(fine < coarse for coarse, fine in itertools.pairwise(mu_errors)), mu_errors
    assert mu_errors[-1] < mu_errors[0] / 10, mu_errors
    assert edge_errors[-1] < edge_errors[0] / 3, edge_errors


def test_shipped_roller_case_steady_state_is_hunters():
    """The shipped case ``polymer_roller_line_contact`` (v tau / a0 = 0.89, n = 1024 on +-8 mm, a0 =
    36 cells), its steady state by ``run_steady``: mu_app within 1e-3 of Hunter's (measured 1.8e-4),
    the contact width within a cell (measured 0.14 dx)."""
    case = vc.load_case(vc.shipped_case("polymer_roller_line_contact"))
    steady = vc.run_steady(case)
    m = case.material
    ref = hunter_cylinder(case.normal.value, case.indenter.radius, m.shear_modulus_instantaneous,
                          m.shear_modulus_long_term, m.retardation_time, m.poisson_ratio, case.tangential.sliding_speed)
    dx = 2 * case.grid.half_width / case.grid.n
    assert float(steady["mu_app"][0]) == pytest.approx(ref.mu_app, rel=1e-3)
    assert float(steady["contact_area"][0]) == pytest.approx(2 * ref.half_width, abs=dx)
