"""The line grid (``grid.dimension = 1``, plane strain) and what generalises over the grid's shape:
the 1-D DC-FFT, the plane-strain strip kernels, the results' layout, the refusals."""
import math

import numpy as np
import pytest
import scipy.integrate

from viscontact.errors import ParameterError
from viscontact.io.case import Case
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.numerics.fftbackends import ZeroBlockTransforms
from viscontact.numerics.grid import Grid
from viscontact.numerics.history import PronyHistory
from viscontact.physics.kernels import influence_coefficients, rectangle_influence, strip_influence


def test_line_grid_layout():
    g = Grid(8, 2.0, dimension=1)
    assert g.shape == (1, 8) and g.rows == 1
    assert g.cell_area == pytest.approx(0.5)  # dx [m] per unit length
    x, y = g.mesh()
    assert x.shape == (1, 8) and np.all(y == 0)
    assert g.refined().shape == (1, 16) and g.coarsened().shape == (1, 4)
    field = np.arange(8.0)[None, :]
    np.testing.assert_array_equal(g.block_mean(field), [[0.5, 2.5, 4.5, 6.5]])
    np.testing.assert_array_equal(g.spread_blocks(g.block_mean(field)), [[0.5, 0.5, 2.5, 2.5, 4.5, 4.5, 6.5, 6.5]])
    np.testing.assert_array_equal(g.edge_values(field), [0.0, 7.0])
    assert Grid(8, 2.0).shape == (8, 8) and Grid(8, 2.0).cell_area == 0.25
    with pytest.raises(ParameterError, match="grid.dimension"):
        Grid(8, 2.0, dimension=3)
    assert PronyHistory.zeros(3, g.shape).internal.shape == (3, 1, 8)


def test_one_dimensional_dcfft_is_the_direct_sum():
    """The (1, n) convolver (padded to (1, 2n), rfft) against the literal sum over cells, for the four
    plane-strain kernels, in double and single precision, and its sparse action."""
    g = Grid(37, 1e-3, dimension=1)
    ics = influence_coefficients(g, 0.3)
    conv = Convolver.from_kernels(g.n, ics)
    assert conv.shape == (1, 37)
    rng = np.random.default_rng(1)
    field = rng.random((1, g.n))
    i = np.arange(g.n)
    for name, kernel in ics.items():
        direct = np.array([np.sum(kernel[0, (k - i) % (2 * g.n)] * field[0]) for k in i])
        np.testing.assert_allclose(conv.apply(name, field)[0], direct, rtol=1e-12, atol=1e-12 * np.abs(direct).max())
        np.testing.assert_allclose(conv.apply(name, field, single=True)[0], direct, rtol=0, atol=1e-5 * np.abs(direct).max())
    sparse = np.zeros((1, g.n))
    sparse[0, [3, 20]] = [1.0, -2.0]
    np.testing.assert_allclose(conv.apply_sparse("zz", sparse, 2.0), 2.0 * conv.apply("zz", sparse), atol=1e-18)
    terms = conv.displacements([("z", "zz", field), ("x", "xz", field)], ("z", "x"))
    np.testing.assert_allclose(terms["x"], conv.apply("xz", field), atol=1e-18)
    # the transforms of a single row: numpy's zero-padded FFT
    tr = ZeroBlockTransforms(g.n, rows=1)
    np.testing.assert_allclose(tr.forward(field), np.fft.rfft(np.pad(field, ((0, 0), (0, g.n))), axis=1), atol=1e-13)
    precond = FourierPreconditioner.for_kernel(ics["zz"])
    assert precond.inverse_symbol.shape == (1, g.n // 2 + 1)


def test_strip_kernels_integrate_the_line_load_solution():
    """The strip integrals against quadrature of Johnson's Eqs. 2.19-2.20 (the line load at G = 1,
    datum b) and against the 3-D rectangle kernels of a long strip along y (plane strain is the limit of
    a load uniform along y: the sign terms equal the 3-D coupling ones; the log terms differ from them by
    a constant only)."""
    nu, h, b = 0.27, 0.5e-3, 7e-3
    d = np.array([0.0, 0.3e-3, 1.0e-3, 2.5e-3, -4e-3])
    strip = strip_influence(d, h, nu, b)
    for k, dk in enumerate(d):
        at = [dk] if abs(dk) < h else None
        log = scipy.integrate.quad(lambda s, dk=dk: math.log(abs(dk - s) / b), -h, h, points=at)[0]
        sgn = scipy.integrate.quad(lambda s, dk=dk: math.copysign(1.0, dk - s), -h, h, points=at)[0]
        assert strip["zz"][k] == pytest.approx(-(1 - nu) / math.pi * log, rel=1e-10)
        assert strip["xx"][k] == pytest.approx(strip["zz"][k], rel=1e-14)
        assert strip["xz"][k] == pytest.approx(-(1 - 2 * nu) / 4 * sgn, abs=1e-15)
        assert strip["zx"][k] == pytest.approx(-strip["xz"][k], abs=1e-15)
    long = rectangle_influence(d, 0.0, h, 1e4, nu)  # a strip 20 km long along y, at its middle
    np.testing.assert_allclose(long["xz"], strip["xz"], rtol=1e-6, atol=1e-12)
    for name in ("zz", "xx"):
        np.testing.assert_allclose(long[name] - long[name][0], strip[name] - strip[name][0], rtol=1e-6, atol=1e-12)


def _line_case(**grid) -> dict:
    return {"title": "line", "material": {"type": "elastic", "shear_modulus": 1e6, "poisson_ratio": 0.4},
            "indenter": {"shape": "cylinder", "radius": 0.01},
            "grid": {"n": 64, "half_width": 1e-3, "dimension": 1, **grid},
            "normal": {"control": "load", "value": 10.0}, "tangential": {"mode": "none"},
            "time": {"t_end": 2e-3, "dt": 1e-3}}


@pytest.mark.parametrize("change, key", [
    ({"indenter": {"shape": "sphere"}}, "indenter.shape"),
    ({"indenter": {"shape": "cylinder", "length": 0.02}}, "indenter.shape"),
    ({"indenter": {"shape": "cone", "half_angle": 70.3}}, "indenter.shape"),
])
def test_line_contact_refuses_in_one_line(change, key):
    data = _line_case()
    for section, values in change.items():
        data[section] = {**data.get(section, {}), **values}
    if data["indenter"]["shape"] in ("self_affine", "cone"):
        del data["indenter"]["radius"]
    with pytest.raises(ParameterError) as err:
        Case.from_dict(data).to_problem()
    assert err.value.key == key and "line contact" in str(err.value) and "\n" not in str(err.value)


def test_line_result_layout_and_units():
    """A line contact's result: fields (t, 1, n) with y = 0, the per-unit-length units (N/m, m), the
    grid_dimension attribute; a 2-D result has none of these."""
    from viscontact.io.results import to_dataset
    from viscontact.running.loop import simulate

    pb = Case.from_dict(_line_case()).to_problem()
    ds = to_dataset(list(simulate(pb)), pb)
    assert ds["pressure"].shape == (pb.time.n_steps, 1, 64) and ds["y"].values.tolist() == [0.0]
    assert ds["load"].attrs["units"] == "N/m" and ds["contact_area"].attrs["units"] == "m"
    assert ds["friction_force"].attrs["units"] == "N/m" and ds["delta_z"].attrs["units"] == "m"
    assert ds.attrs["grid_dimension"] == 1
    data = _line_case()
    data["grid"], data["normal"]["value"] = {"n": 32, "half_width": 1e-3}, 0.01
    data["indenter"]["shape"] = "sphere"
    pb2 = Case.from_dict(data).to_problem()
    ds2 = to_dataset(list(simulate(pb2)), pb2)
    assert ds2["load"].attrs["units"] == "N" and "grid_dimension" not in ds2.attrs


def test_line_summary_says_per_unit_length(tmp_path):
    """The headline numbers of a line result: the load in N/m, the half-width A/2 (not sqrt(A/pi))."""
    from viscontact.io.results import to_dataset
    from viscontact.running.loop import simulate
    from viscontact.running.summary import format_summary, summary

    pb = Case.from_dict(_line_case()).to_problem()
    ds = to_dataset(list(simulate(pb)), pb)
    s = summary(ds)
    assert s["units"]["load"] == "N/m"
    assert s["values"]["contact_radius"] == pytest.approx(float(ds["contact_area"][-1]) / 2)
    text = format_summary(s)
    assert "contact half-width A/2" in text and "10 N/m" in text


def test_the_guards_estimate_a_line_by_hertz_line_contact():
    """The contact-size guard of a line uses Hertz's line contact, a = sqrt(4 W R / (pi E*)) (here
    0.391 mm at 40 N/m): a domain of +-0.3 mm is refused in one line naming grid.half_width."""
    from viscontact.running.guards import check_problem, contact_estimate

    data = _line_case(half_width=0.3e-3)
    data["normal"]["value"] = 40.0
    pb = Case.from_dict(data).to_problem()
    est = contact_estimate(pb)
    e_star = 2 * 1e6 / (1 - 0.4)
    assert est.smallest == pytest.approx(math.sqrt(4 * 40.0 * 0.01 / (math.pi * e_star)), rel=1e-12)
    assert "Hertz, line contact" in est.model
    with pytest.raises(ParameterError) as err:
        check_problem(pb)
    assert err.value.key == "grid.half_width" and "line contact" in str(err.value)


def test_a_line_with_a_bulk_modulus_is_the_constant_nu_line_when_incompressible():
    """nu(t) on a line (the bulk-elastic body's kernels split at nu = 0 and 1, affine in nu in plane
    strain as in 3-D): with K = 1e6 G(0) nu stays 0.5 to 1e-6, and the run is the constant-nu one to
    that order (creep under a held load, 3 steps)."""
    from viscontact.running.loop import simulate

    zener = {"type": "zener", "shear_modulus_instantaneous": 1e6, "shear_modulus_long_term": 1e5,
             "retardation_time": 1e-3}
    data = _line_case(half_width=2e-3)
    data["material"] = {**zener, "poisson_ratio": 0.5}
    data["time"] = {"t_end": 3e-3, "dt": 1e-3}
    constant = list(simulate(Case.from_dict(data).to_problem()))
    data["material"] = {**zener, "bulk_modulus": 1e12}
    bulk = list(simulate(Case.from_dict(data).to_problem()))
    for a, b in zip(constant, bulk):
        assert b.delta_z == pytest.approx(a.delta_z, rel=1e-5)
        np.testing.assert_allclose(b.pressure, a.pressure, atol=1e-5 * a.pressure.max())
    assert bulk[-1].delta_z > 2 * bulk[0].delta_z  # it crept
