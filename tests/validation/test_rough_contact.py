"""Elastic contact on a periodic domain: rough surfaces against ContactMechanics, the wavy surface
against Westergaard, and a topography file against the same heights in a .npy.

* ContactMechanics (Pastewka and co-workers, PyPI) solves the same surface and load with its own
  substrate (pixel point forces, stiffness E*|q|/2, no cell footprint) and its own constrained
  conjugate gradients. The two discretisations differ by the cell footprint, 1 - (q dx)^2/24 in the
  stiffness: 2.6 % at the surface's short cut-off (8 cells), less below. So the real contact areas
  and the pressure fields must agree to 2 %, and every contact point of ours is one of theirs.
* Westergaard (1939; Johnson, Contact Mechanics, Sec. 13.2): a rigid surface h0 cos(2 pi x/lambda)
  on an elastic half-space under the mean pressure p_mean is in contact over |x| < a with
  p_mean = p* sin^2(pi a / lambda), p* = pi E* h0 / lambda. Counting contact cells quantises the
  half-width to dx/2, so |a_num - a| <= 0.75 dx (half a cell of quantisation plus the sub-cell
  discretisation error of the edge).
* The same heights read by SurfaceTopography from a NetCDF file in mm and from a .npy in m give
  the same contact (round-off).
"""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.numerics.grid import Grid
from viscontact.problem.roughness import roughness_metrics
from viscontact.problem.topography import gap_from_heights, read_heights, self_affine_heights
from vc_testing import periodic_elastic_contact

ST = pytest.importorskip("SurfaceTopography")
CM = pytest.importorskip("ContactMechanics")

NU, G = 0.3, 1.0e6
E_STAR = 2 * G / (1 - NU)


def test_rough_contact_area_against_contactmechanics():
    grid = Grid(128, 0.5e-3)
    period = 2 * grid.half_width
    heights = self_affine_heights(grid, hurst=0.8, rms_slope=0.1, short_cutoff=period / 16, seed=1)
    gap = gap_from_heights(heights)
    load = 0.05 * E_STAR * 0.1 * period**2  # mean pressure 0.05 E* h'_rms: about 11 % in contact
    p, delta, u_z, _ = periodic_elastic_contact(grid, gap, G, NU, load)
    ours = roughness_metrics(p, gap + u_z - delta, periodic=True)

    from ContactMechanics import PeriodicFFTElasticHalfSpace, make_system
    substrate = PeriodicFFTElasticHalfSpace((grid.n, grid.n), E_STAR, (period, period))  # nu = 0: E' = E*
    system = make_system(substrate=substrate, surface=ST.Topography(heights.T.copy(), (period, period), periodic=True))
    result = system.minimize_proxy(external_force=load, pentol=1e-12)
    forces = np.abs(result.jac).T  # their [x, y] -> our [y, x]
    theirs = forces / grid.cell_area
    assert forces.sum() == pytest.approx(load, rel=1e-9)
    area_theirs = (theirs > 0).mean()
    assert 0.05 < ours.contact_fraction < 0.2
    assert ours.contact_fraction == pytest.approx(area_theirs, rel=0.02)
    assert np.abs(p - theirs).sum() <= 0.02 * p.sum()
    assert np.all(theirs[p > 0] > 0)


@pytest.mark.parametrize("a_over_lambda", [0.1, 0.2, 0.3, 0.4])
def test_westergaard_contact_width(a_over_lambda):
    wavelength, h0 = 1e-3, 1e-6
    grid = Grid(128, wavelength / 2)
    x, _ = grid.mesh()
    gap = h0 * (1 - np.cos(2 * np.pi * x / wavelength))
    p_star = np.pi * E_STAR * h0 / wavelength
    p_mean = p_star * np.sin(np.pi * a_over_lambda) ** 2
    p, _, _, _ = periodic_elastic_contact(grid, gap, G, NU, p_mean * wavelength**2)
    assert np.array_equal(p, np.broadcast_to(p[:1], p.shape))  # uniform along y
    half_width = 0.5 * (p[0] > 0).sum() * grid.spacing
    assert abs(half_width - a_over_lambda * wavelength) <= 0.75 * grid.spacing


def test_topography_file_gives_the_npy_answer(tmp_path):
    grid = Grid(32, 0.25e-3)
    period = 2 * grid.half_width
    heights = self_affine_heights(grid, hurst=0.6, rms_height=0.5e-6, seed=7)
    np.save(tmp_path / "heights.npy", heights)
    ST.Topography(heights.T * 1e3, (period * 1e3, period * 1e3), unit="mm", periodic=True).to_netcdf(
        str(tmp_path / "heights.nc"))
    from_npy = gap_from_heights(np.load(tmp_path / "heights.npy"))
    from_file = gap_from_heights(read_heights(tmp_path / "heights.nc", grid))
    np.testing.assert_allclose(from_file, from_npy, rtol=0, atol=1e-12 * from_npy.max())
    load = 0.02 * E_STAR * 0.5e-6 / period * period**2
    p_npy, d_npy, _, _ = periodic_elastic_contact(grid, from_npy, G, NU, load)
    p_file, d_file, _, _ = periodic_elastic_contact(grid, from_file, G, NU, load)
    assert 0 < (p_npy > 0).mean() < 1
    np.testing.assert_allclose(p_file, p_npy, rtol=0, atol=1e-9 * p_npy.max())
    assert d_file == pytest.approx(d_npy, rel=1e-9)
