"""Topographies through SurfaceTopography (viscontact.problem.topography).

Truths: surfaces written by SurfaceTopography's own writers from arrays we index ourselves ([x, y]
there, [y, x] here) and read back, units converted (um -> m); the generated surface's rms (exact by
construction) and its power-spectrum exponent -2 - 2H measured with our own FFT; cubic resampling
of a sinusoid against the sinusoid (error bound of cubic spline interpolation, 5/384 (k s)^4 times
the amplitude).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid
from viscontact.errors import ViscontactWarning
from viscontact.problem.topography import (check_surface, gap_from_heights, read_heights, self_affine_heights,
                                   sphere_heights)

ST = pytest.importorskip("SurfaceTopography")

GRID = Grid(16, 0.5e-3)  # period 1 mm


def _ridge_topography(nx: int, ny: int, size: tuple[float, float], unit: str = "um", periodic: bool = False):
    """A surface that varies along x only, heights[x, y] = 2 + sin(2 pi x / Lx) in ``unit``."""
    x = np.arange(nx) * size[0] / nx
    heights_xy = np.repeat((2.0 + np.sin(2 * np.pi * x / size[0]))[:, None], ny, axis=1)
    return ST.Topography(heights_xy, size, unit=unit, periodic=periodic), x


@pytest.mark.parametrize("writer", ["to_netcdf", "to_matrix"])
def test_read_orientation_and_units(tmp_path, writer):
    topo, x = _ridge_topography(16, 16, (1000.0, 1000.0), unit="um")  # 1 mm in um
    path = tmp_path / ("surface.nc" if writer == "to_netcdf" else "surface.txt")
    getattr(topo, writer)(str(path))
    h = read_heights(path, GRID)
    assert h.shape == (16, 16)
    expected = (2.0 + np.sin(2 * np.pi * x / 1000.0)) * 1e-6  # m, along x = our axis 1
    np.testing.assert_allclose(h, np.broadcast_to(expected[None, :], (16, 16)), rtol=1e-12, atol=1e-18)


def test_mismatch_is_one_line_naming_both(tmp_path):
    topo, _ = _ridge_topography(12, 16, (1000.0, 1000.0))
    path = tmp_path / "s.nc"
    topo.to_netcdf(str(path))
    with pytest.raises(ParameterError) as err:
        read_heights(path, GRID)
    msg = str(err.value)
    assert err.value.key == "indenter.file" and "\n" not in msg
    assert "12 x 16 points" in msg and "16 x 16 points" in msg and "resample = true" in msg
    topo, _ = _ridge_topography(16, 16, (900.0, 1000.0))
    topo.to_netcdf(str(path))
    with pytest.raises(ParameterError, match="0.0009 m x 0.001 m"):
        read_heights(path, GRID)


def test_unreadable_and_missing_files(tmp_path):
    with pytest.raises(ParameterError, match="no such file"):
        read_heights(tmp_path / "absent.nc", GRID)
    bad = tmp_path / "bad.txt"
    bad.write_text("this is not a topography\n")
    with pytest.raises(ParameterError) as err:
        read_heights(bad, GRID)
    assert "cannot read" in str(err.value) and "\n" not in str(err.value)
    plain = tmp_path / "plain.txt"  # a bare matrix: no physical size in it
    np.savetxt(plain, np.ones((16, 16)))
    with pytest.raises(ParameterError, match="cannot read"):
        read_heights(plain, GRID)
    h = read_heights(plain, GRID, physical_sizes=(1e-3, 1e-3), unit="m")
    np.testing.assert_allclose(h, 1.0)


def test_resample_periodic_sinusoid(tmp_path):
    period = 1e-3
    grid = Grid(64, period / 2)
    topo, x = _ridge_topography(40, 40, (period, period), unit="m", periodic=True)
    path = tmp_path / "s.nc"
    topo.to_netcdf(str(path))
    # the file's periodic flag is not kept by every format: resample what read_topography gives
    h = read_heights(path, grid, resample=True)
    s = period / 40
    # file sample i sits at i s; the grid cell centres are put on the same centre (module doc)
    x_file = grid.x + (period - s) / 2
    exact = 2.0 + np.sin(2 * np.pi * x_file / period)
    bound = 5 / 384 * (2 * np.pi * s / period) ** 4
    assert np.abs(h - exact[None, :]).max() <= bound


def test_resample_needs_coverage_when_not_periodic(tmp_path):
    topo, _ = _ridge_topography(40, 40, (0.8e-3, 0.8e-3), unit="m", periodic=False)
    path = tmp_path / "small.nc"
    topo.to_netcdf(str(path))
    # samples at 0 .. 0.78 mm around the grid's centre: cell centres up to 0.36 mm from it fit in
    with pytest.raises(ParameterError, match=r"do not reach the grid's outermost cell centres; "
                                             r"grid.half_width <= 0.000416 m keeps them inside"):
        read_heights(path, GRID, resample=True)
    big, _ = _ridge_topography(80, 80, (2e-3, 2e-3), unit="m", periodic=False)
    big.to_netcdf(str(path))
    h = read_heights(path, GRID, resample=True)
    assert h.shape == (16, 16) and np.all(np.isfinite(h))


def test_self_affine_rms_and_spectrum():
    grid = Grid(256, 0.5e-3)
    hurst = 0.7
    h = self_affine_heights(grid, hurst=hurst, rms_height=1e-6, seed=3)
    assert np.sqrt(np.mean((h - h.mean()) ** 2)) == pytest.approx(1e-6, rel=1e-9)
    assert np.array_equal(h, self_affine_heights(grid, hurst=hurst, rms_height=1e-6, seed=3))
    assert not np.allclose(h, self_affine_heights(grid, hurst=hurst, rms_height=1e-6, seed=4))
    # radially averaged PSD ~ q^(-2 - 2H) between the largest and the smallest wavelengths
    spectrum = np.abs(np.fft.fft2(h)) ** 2
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(256), np.fft.fftfreq(256)))
    bins = np.geomspace(4 / 256, 0.3, 12)
    idx = np.digitize(q, bins)
    centres = [q[idx == b].mean() for b in range(1, len(bins))]
    power = [spectrum[idx == b].mean() for b in range(1, len(bins))]
    slope = np.polyfit(np.log(centres), np.log(power), 1)[0]
    assert slope == pytest.approx(-2 - 2 * hurst, abs=0.15)


def test_self_affine_rms_slope_and_errors():
    grid = Grid(64, 0.5e-3)
    h = self_affine_heights(grid, hurst=0.8, rms_slope=0.1, short_cutoff=8 * grid.spacing, seed=1)
    gx = (np.roll(h, -1, axis=1) - h) / grid.spacing  # forward differences, periodic
    gy = (np.roll(h, -1, axis=0) - h) / grid.spacing
    assert np.sqrt(np.mean(gx**2 + gy**2)) == pytest.approx(0.1, rel=1e-6)
    for kwargs, key in (({"hurst": 1.5, "rms_height": 1e-6}, "indenter.hurst"),
                        ({"hurst": 0.8}, "indenter.rms_height"),
                        ({"hurst": 0.8, "rms_height": 1e-6, "rms_slope": 0.1}, "indenter.rms_height"),
                        ({"hurst": 0.8, "rms_slope": -0.1}, "indenter.rms_slope"),
                        ({"hurst": 0.8, "rms_slope": 0.1, "short_cutoff": grid.spacing}, "indenter.short_cutoff"),
                        ({"hurst": 0.8, "rms_slope": 0.1, "long_cutoff": grid.spacing}, "indenter.long_cutoff")):
        with pytest.raises(ParameterError) as err:
            self_affine_heights(grid, **kwargs)
        assert err.value.key == key


def test_rough_sphere_gap():
    grid = Grid(32, 0.5e-3)
    sphere = sphere_heights(grid, 0.01)
    rough = self_affine_heights(grid, hurst=0.8, rms_height=0.2e-6, seed=0)
    gap = gap_from_heights(sphere + rough)
    assert gap.min() == 0.0
    smooth = gap_from_heights(sphere)
    x, y = grid.mesh()
    np.testing.assert_allclose(smooth, (x**2 + y**2) / 0.02 - ((x**2 + y**2) / 0.02).min(), atol=1e-20)


def _waves(grid: Grid, periods_across: float, amplitude: float) -> np.ndarray:
    """A gap [m] of waves along x and y with ``periods_across`` wavelengths over the grid's width."""
    x, y = grid.mesh()
    k = 2 * np.pi * periods_across / (2 * grid.half_width)
    return amplitude * (2 + np.sin(k * x) + np.cos(k * y))


def test_a_map_that_is_not_periodic_over_a_periodic_grid_is_warned():
    periodic = Grid(64, 0.5e-3, periodic=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_surface(_waves(periodic, 3, 1e-6), periodic, "indenter.file")  # whole periods: edges meet
        check_surface(_waves(Grid(64, 0.5e-3), 3.5, 1e-6), Grid(64, 0.5e-3), "indenter.file")  # not periodic: no seam
    with pytest.warns(ViscontactWarning, match=r"not periodic over the grid's period: its steps across the period's "
                                               r"edges are \d+(\.\d+)? x"):
        check_surface(_waves(periodic, 3.5, 1e-6), periodic, "indenter.file")  # half a wave short: a cliff


def test_slopes_of_a_unit_slip_are_refused_and_steep_ones_warned():
    grid = Grid(32, 0.5e-3, periodic=True)
    gap = _waves(grid, 3, 1e-6)  # rms slope about 0.02
    with pytest.raises(ParameterError, match=r"indenter.file: the surface's rms slope is \d+(\.\d+)? on this grid: "
                                             "heights in the wrong unit"):
        check_surface(gap * 1e3, grid, "indenter.file")  # um read as mm
    with pytest.warns(ViscontactWarning, match="beyond the small-slope theory"):
        check_surface(gap * 1e2, grid, "indenter.file")


def test_punch_walls_are_warned_with_their_remedy():
    """The rms slope is the whole surface's (the unit-slip check): a 0.5 mm punch's walls of 1 mm read
    2.0 at 64^2 (11.3 at 2048^2, refused). Walls out of contact do not enter the solution
    (tests/validation/test_flat_punch.py): the messages say so."""
    grid = Grid(64, 2e-3)
    x, y = grid.mesh()
    punch = np.where(x**2 + y**2 <= 0.5e-3**2, 0.0, 1e-3)
    with pytest.warns(ViscontactWarning, match=r"rms slope is 2\.02, .* a flat punch's wall counts at its full "
                                               "height: walls that stay out of contact can be lowered"):
        check_surface(punch, grid, "indenter.file")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_surface(punch / 50, grid, "indenter.file")  # walls of 20 um: 0.04


def test_a_map_without_its_height_is_one_line(tmp_path):
    path = tmp_path / "width_only.txt"
    rows = "\n".join(" ".join(f"{2 + np.sin(i + j):.6f}" for j in range(16)) for i in range(16))
    path.write_text("# Width: 1 mm\n# Value units: um\n" + rows + "\n")
    with pytest.raises(ParameterError, match="gives one physical size .* '# Height:'"):
        read_heights(path, GRID)


def test_resampling_far_from_the_grids_spacing_is_warned(tmp_path):
    topo, _ = _ridge_topography(16, 16, (1.0, 1.0), unit="m", periodic=True)  # 1 m where 1 mm was meant
    path = tmp_path / "wide.nc"
    topo.to_netcdf(str(path))
    with pytest.warns(ViscontactWarning, match="resampling changes the point spacing 1e\\+03-fold"):
        read_heights(path, GRID, resample=True)


def test_one_seed_is_one_surface_at_every_grid_size():
    """With a short cut-off the surface does not depend on grid.n: its Fourier modes at 32^2 and 128^2
    are the same (they were redrawn: the shipped rough case had an rms height of 11.2 um at 64^2 and
    7.0 um at 128^2, its common modes correlated at 0.31)."""
    keys = dict(hurst=0.8, rms_height=5e-6, short_cutoff=125e-6, seed=1)
    coarse, fine = (self_affine_heights(Grid(n, 0.5e-3, periodic=True), **keys) for n in (32, 128))
    modes = np.r_[0:9, -8:0]  # all modes inside the cut-off (the period over 125 um is 8)
    c, f = (np.fft.fft2(h)[np.ix_(modes, modes)] / h.size for h in (coarse, fine))
    np.testing.assert_allclose(f, c, rtol=0, atol=1e-12 * np.abs(c).max())
    np.testing.assert_allclose(fine[::4, ::4].std(), coarse.std(), rtol=0.05)  # the same relief, sampled
