"""Rough line contacts (``grid.dimension = 1``): self-affine profiles and measured line scans.

* The generated profile (a 1-D Fourier synthesis by SurfaceTopography): its rms height or slope
  exactly as asked, its periodogram's slope -(1 + 2H) over the self-affine band (a profile's PSD,
  C(q) ~ q^(-1-2H)), one seed one profile at every grid that holds its short cut-off.
* A line scan read by SurfaceTopography (NetCDF, in mm) lands on the grid as the same heights in m,
  and a case reading it solves the same contact as a .npy gap of shape (1, n) holding them.
* A rough periodic line contact through the case file against ContactMechanics (Pastewka and
  co-workers; its 1-D periodic substrate, stiffness E*|q|/2, pixel point forces and no cell
  footprint: the two differ by 1 - (q dx)^2/24 in stiffness, 2.6 % at the profile's short cut-off of
  8 cells, less below). The contact fractions and the pressures agree to 2 %, every contact point of
  ours is one of theirs, and the load is the sum of the pressure over the cells (N/m).
"""
import os

import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.io.case import Case
from viscontact.numerics.grid import Grid
from viscontact.problem.topography import gap_from_heights, read_heights, self_affine_heights
from viscontact.running.loop import simulate

ST = pytest.importorskip("SurfaceTopography")

G, NU = 1.0e6, 0.3
E_STAR = 2 * G / (1 - NU)
PERIOD = 1e-3
LINE = Grid(256, PERIOD / 2, periodic=True, dimension=1)


def test_line_profile_rms_height_and_slope():
    h = self_affine_heights(LINE, hurst=0.8, rms_height=1e-6, seed=3)
    assert h.shape == (1, 256)
    assert np.sqrt(np.mean((h - h.mean()) ** 2)) == pytest.approx(1e-6, rel=1e-12)
    s = self_affine_heights(LINE, hurst=0.8, rms_slope=0.05, seed=3)
    slope = np.sqrt(np.mean((np.roll(s, -1, axis=1) - s) ** 2)) / LINE.spacing
    assert slope == pytest.approx(0.05, rel=1e-12)


def test_line_profile_power_spectrum_is_self_affine():
    """The periodogram averaged over 40 seeds falls as q^(-1-2H) between 4 and 100 wavelengths per
    period (least squares in log-log): H = 0.8 and 0.5 within 0.05 in the exponent."""
    grid = Grid(1024, PERIOD / 2, periodic=True, dimension=1)
    modes = np.arange(4, 101)
    for hurst in (0.8, 0.5):
        power = np.mean([np.abs(np.fft.rfft(self_affine_heights(grid, hurst=hurst, rms_height=1e-6, seed=s)[0])) ** 2
                         for s in range(40)], axis=0)
        exponent = np.polyfit(np.log(modes), np.log(power[modes]), 1)[0]
        assert exponent == pytest.approx(-1 - 2 * hurst, abs=0.05)


def test_line_profile_is_refined_not_redrawn():
    """With a short cut-off the same seed gives the same profile at n and 2n (the Fourier series of
    the draw on the coarsest grid that holds it)."""
    keys = {"hurst": 0.8, "rms_height": 1e-6, "short_cutoff": PERIOD / 10, "seed": 3}
    coarse = self_affine_heights(LINE, **keys)
    fine = self_affine_heights(LINE.refined(), **keys)
    np.testing.assert_allclose(fine[:, ::2], coarse, rtol=0, atol=1e-12 * 1e-6)
    assert not np.allclose(fine[:, 1::2], coarse)


def _case(data_indenter: dict, n: int = 256, load: float = 0.2) -> Case:
    return Case.from_dict({
        "title": "rough line", "material": {"type": "elastic", "shear_modulus": G, "poisson_ratio": NU},
        "indenter": data_indenter, "grid": {"n": n, "half_width": PERIOD / 2, "dimension": 1, "periodic": True},
        "normal": {"control": "load", "value": load}, "tangential": {"mode": "none"},
        "time": {"t_end": 1e-3, "dt": 1e-3}})


def test_line_scan_round_trip(tmp_path):
    """A line scan in mm (NetCDF) read onto the line grid: the heights in m; a 'topography' case of it
    solves the contact of the .npy gap (1, n) of the same heights to round-off."""
    h = self_affine_heights(LINE, hurst=0.8, rms_height=1e-6, short_cutoff=PERIOD / 16, seed=5)
    nc = os.path.join(tmp_path, "scan.nc")
    ST.UniformLineScan(h[0] * 1e3, (PERIOD * 1e3,), periodic=True, unit="mm").to_netcdf(nc)
    read = read_heights(nc, LINE)
    np.testing.assert_allclose(read, h, rtol=1e-12, atol=1e-12 * 1e-6)
    npy = os.path.join(tmp_path, "gap.npy")
    np.save(npy, gap_from_heights(h))
    from_scan = list(simulate(_case({"shape": "topography", "file": nc}).to_problem()))[-1]
    from_gap = list(simulate(_case({"shape": "surface", "file": npy}).to_problem()))[-1]
    assert 0 < from_scan.contact_fraction < 1
    np.testing.assert_allclose(from_scan.pressure, from_gap.pressure, rtol=0, atol=1e-9 * from_gap.pressure.max())
    with pytest.raises(ParameterError, match="line scan") as err:  # a line scan is no map
        read_heights(nc, Grid(256, PERIOD / 2, periodic=True))
    assert "\n" not in str(err.value)


def test_a_map_is_refused_on_a_line(tmp_path):
    nc = os.path.join(tmp_path, "map.nc")
    ST.Topography(np.zeros((8, 8)), (1.0, 1.0), periodic=True, unit="mm").to_netcdf(nc)
    with pytest.raises(ParameterError, match="needs a line scan") as err:
        _case({"shape": "topography", "file": nc}).to_problem()
    assert err.value.key == "indenter.file" and "\n" not in str(err.value)


def test_rough_line_contact_against_contactmechanics():
    """A self-affine profile (H = 0.8, rms slope 0.1, short cut-off 8 cells) under a mean pressure of
    0.05 E* h'_rms: about 17 % in contact. Measured: contact fractions 0.174 and 0.176, pressures
    0.3 % apart (L1)."""
    from ContactMechanics import PeriodicFFTElasticHalfSpace, make_system

    grid = Grid(512, PERIOD / 2, periodic=True, dimension=1)
    keys = {"hurst": 0.8, "rms_slope": 0.1, "short_cutoff": PERIOD / 16, "seed": 1}
    load = 0.05 * E_STAR * 0.1 * PERIOD  # N/m
    problem = _case({"shape": "self_affine", **keys}, n=512, load=load).to_problem()
    ours = list(simulate(problem))[-1]
    p = ours.pressure[0]
    assert ours.load == pytest.approx(load, rel=1e-10)
    assert p.sum() * grid.spacing == pytest.approx(load, rel=1e-10)

    heights = self_affine_heights(grid, **keys)[0]
    substrate = PeriodicFFTElasticHalfSpace((grid.n,), E_STAR, (PERIOD,))  # nu = 0: E' = E*
    system = make_system(substrate=substrate, surface=ST.UniformLineScan(heights.copy(), (PERIOD,), periodic=True))
    result = system.minimize_proxy(external_force=load, pentol=1e-12)
    theirs = np.abs(result.jac) / grid.spacing
    assert np.abs(result.jac).sum() == pytest.approx(load, rel=1e-9)
    assert 0.1 < ours.contact_fraction < 0.25
    assert ours.contact_fraction == pytest.approx((theirs > 0).mean(), rel=0.02)
    assert np.abs(p - theirs).sum() <= 0.02 * p.sum()
    assert np.all(theirs[p > 0] > 0)
