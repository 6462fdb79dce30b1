"""Subsurface stresses (viscontact.physics.subsurface) against closed-form half-space solutions.

* Hertz pressure: sigma_z, sigma_r on the axis (Johnson Eq. 3.45) and the principal shear maximum
  0.31 p0 at 0.48 a for nu = 0.3 (Johnson sec. 3.4). Tolerance 2e-3 p0: the pressure is sampled at
  cell centres (a = 21.5 cells; the edge of the square-root profile costs ~5e-4 p0) and the padded
  transform adds the field of periodic images of the load (~6e-4 p0 at z = 1.5 a with padding 4,
  ~4e-3 with padding 2 at z = 2 a: checked in ``test_images_shrink_with_padding``).
* Point forces (Boussinesq, Cerruti; Johnson Eqs. 3.20, 3.87): far from a one-cell load
  (rho >= 12 dx) the field is that of a point force to O((dx/rho)^2); tolerance 1.5 % of the local
  magnitude. This pins the signs of the tangential (q_x) part.
* Periodic grid (the stresses of one period of a periodic traction): the exact plane-strain fields of
  the Fourier modes p1 cos(kx) and q1 cos(kx) (q along x) from the Airy function
  phi = (A + B k z) exp(-kz) {cos, sin}(kx) / k^2 (sigma_xx = phi_zz, sigma_zz = phi_xx,
  sigma_xz = -phi_xz; Johnson sec. 2.6, Barber ch. 5), E = exp(-kz):

      p1 cos(kx): sigma_zz = -p1 (1 + kz) E cos kx,  sigma_xx = -p1 (1 - kz) E cos kx,
                  sigma_xz = -p1 kz E sin kx
      q1 cos(kx): sigma_zz = -q1 kz E sin kx,        sigma_xx = -q1 (2 - kz) E sin kx,
                  sigma_xz = -q1 (1 - kz) E cos kx
      sigma_yy = nu (sigma_xx + sigma_zz) (plane strain)

  a mode p2 cos(k y) the same rotated (on y = 0: sigma_yy = -p2 (1 - kz) E, sigma_xx = -2 nu p2 E),
  and the means (periodic displacements, no mean in-plane strain): sigma_zz = -mean p, sigma_xx =
  sigma_yy = -nu/(1 - nu) mean p (uniaxial strain), sigma_xz = -mean q_x, sigma_yz = -mean q_y (simple
  shear), at every depth. The tractions are uniform over each cell: a mode sampled at the cell
  centres has the amplitude sinc(k dx/2) in its fundamental; its harmonics beyond the grid's
  Nyquist wavenumber decay as exp(-2 pi z/dx) < 4e-6 at z >= 2 dx: tolerance 1e-5 of the largest
  traction. And the zero-mean part of a random periodic traction against the padded (isolated)
  formula on a 15 x 15 tiling of the period, central period, z >= 0.1 L: within 1e-3 of the largest
  stress (the tiling's edges: 9 x 9 tiles leave 3e-3). Before the fix the periodic section was
  zero-padded: one isolated period (sigma_zz at depth -> 0, not -mean p).
"""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.numerics.grid import Grid
from viscontact.physics.reference import hertz_axis_stresses
from viscontact.physics.subsurface import section_stresses

NU, A, P0 = 0.3, 1e-3, 1e6


def hertz_section(n: int, depths, padding: int = 4, nu: float = NU):
    grid = Grid(n, 3 * A)
    x, y = grid.mesh()
    p = P0 * np.sqrt(np.clip(1 - (x**2 + y**2) / A**2, 0, None))
    return grid, section_stresses(grid, nu, depths, p, padding=padding)


def test_hertz_axis_stresses():
    z = np.array([0.1, 0.3, 0.5, 0.8, 1.1, 1.5]) * A
    grid, st = hertz_section(129, z)
    axis = grid.n // 2
    assert grid.x[axis] == pytest.approx(0.0, abs=1e-15)
    sr, sz = hertz_axis_stresses(z, A, P0, NU)
    np.testing.assert_allclose(st.stress["zz"][:, axis], sz, atol=2e-3 * P0)
    np.testing.assert_allclose(st.stress["xx"][:, axis], sr, atol=2e-3 * P0)
    np.testing.assert_allclose(st.stress["yy"][:, axis], sr, atol=2e-3 * P0)
    for c in ("xz", "yz", "xy"):  # the axis of a symmetric normal load carries no shear
        assert np.max(np.abs(st.stress[c][:, axis])) < 1e-9 * P0


def test_hertz_maximum_shear():
    """Johnson sec. 3.4: max principal shear 0.31 p0 at z = 0.48 a below the centre (nu = 0.3)."""
    zs = np.linspace(0.40, 0.56, 9) * A
    _, st = hertz_section(129, zs, padding=2)
    tresca = st.max_shear
    i, j = np.unravel_index(np.argmax(tresca), tresca.shape)
    assert st.x[j] == pytest.approx(0.0, abs=1e-15)
    assert zs[i] / A == pytest.approx(0.48, abs=0.021)
    assert tresca.max() / P0 == pytest.approx(0.31, abs=0.003)
    # the analytic reference says the same
    zz = np.linspace(0.3, 0.7, 4001)
    sr, sz = hertz_axis_stresses(zz * A, A, P0, NU)
    assert zz[np.argmax(np.abs(sz - sr))] == pytest.approx(0.48, abs=0.005)
    assert np.max(np.abs(sz - sr)) / 2 / P0 == pytest.approx(0.31, abs=0.001)
    # von Mises on the axis: |sigma_z - sigma_r| (two equal principal stresses)
    assert np.allclose(st.von_mises[:, j], 2 * tresca[:, j], rtol=1e-12)


def test_images_shrink_with_padding():
    z = np.array([2.0]) * A
    sr, _ = hertz_axis_stresses(z, A, P0, NU)
    errors = []
    for padding in (2, 4):
        grid, st = hertz_section(65, z, padding=padding)
        errors.append(abs(st.stress["xx"][0, grid.n // 2] - sr[0]))
    assert errors[1] < 0.25 * errors[0]


def point_force_fields(x: np.ndarray, z: float, force: float, direction: str) -> dict[str, np.ndarray]:
    """sigma_z, sigma_xz at (x, 0, z) of a point force at the origin (Johnson Eqs. 3.20, 3.87)."""
    rho5 = (x**2 + z**2) ** 2.5
    if direction == "z":
        return {"zz": -3 * force * z**3 / (2 * np.pi * rho5), "xz": -3 * force * x * z**2 / (2 * np.pi * rho5)}
    return {"zz": -3 * force * x * z**2 / (2 * np.pi * rho5), "xz": -3 * force * x**2 * z / (2 * np.pi * rho5)}


@pytest.mark.parametrize("direction", ["z", "x"])
def test_point_forces(direction):
    n = 65
    grid = Grid(n, 1e-3)
    traction = np.zeros((n, n))
    traction[n // 2, n // 2] = 1e6
    force = 1e6 * grid.cell_area
    z = 14 * grid.spacing
    kwargs = {"pressure": traction} if direction == "z" else {"pressure": np.zeros((n, n)), "shear_x": traction}
    st = section_stresses(grid, NU, [z], padding=4, **kwargs)
    ref = point_force_fields(grid.x, z, force, direction)
    near = np.abs(grid.x) < 20 * grid.spacing
    for c in ("zz", "xz"):
        scale = np.max(np.abs(ref[c][near]))
        np.testing.assert_allclose(st.stress[c][0, near], ref[c][near], atol=0.015 * scale, err_msg=c)
    assert np.max(np.abs(st.stress["yz"])) < 1e-12 * force / z**2


def test_rejects_negative_depth():
    with pytest.raises(ValueError, match="depths"):
        section_stresses(Grid(8, 1e-3), NU, [-1e-4], np.zeros((8, 8)))


PERIOD = 2e-3


def test_periodic_fourier_modes_and_means_are_exact():
    n, nu = 64, NU
    grid = Grid(n, PERIOD / 2, periodic=True)
    x, y = grid.mesh()
    dx = grid.spacing
    k1, k2 = 2 * np.pi * 2 / PERIOD, 2 * np.pi / PERIOD
    p_mean, p1, p2, qx_mean, q1, qy_mean = 1e4, 4e3, 3e3, 2e3, 1.5e3, -1e3
    pressure = p_mean + p1 * np.cos(k1 * x) + p2 * np.cos(k2 * y)
    shear_x = qx_mean + q1 * np.cos(k1 * x)
    shear_y = np.full((n, n), qy_mean)
    depths = np.array([2 * dx, 0.05 * PERIOD, 0.2 * PERIOD, 0.5 * PERIOD, PERIOD])
    st = section_stresses(grid, nu, depths, pressure, shear_x, shear_y)
    z, xs = depths[:, None], grid.x[None, :]
    a1, b1, a2 = (np.sinc(k * dx / (2 * np.pi)) * amp for k, amp in ((k1, p1), (k1, q1), (k2, p2)))
    e1, e2, kz1, kz2 = np.exp(-k1 * z), np.exp(-k2 * z), k1 * z, k2 * z
    c, s = np.cos(k1 * xs), np.sin(k1 * xs)
    zz = -a1 * (1 + kz1) * e1 * c - b1 * kz1 * e1 * s - a2 * (1 + kz2) * e2 - p_mean
    xx_plane = -a1 * (1 - kz1) * e1 * c - b1 * (2 - kz1) * e1 * s        # the x modes' sigma_xx
    zz_plane = -a1 * (1 + kz1) * e1 * c - b1 * kz1 * e1 * s
    expected = {
        "zz": zz,
        "xx": xx_plane - 2 * nu * a2 * e2 - nu / (1 - nu) * p_mean,
        "yy": nu * (xx_plane + zz_plane) - a2 * (1 - kz2) * e2 - nu / (1 - nu) * p_mean,
        "xz": -a1 * kz1 * e1 * s - b1 * (1 - kz1) * e1 * c - qx_mean,
        "yz": np.full_like(zz, -qy_mean),
        "xy": np.zeros_like(zz),
    }
    for comp, value in expected.items():
        np.testing.assert_allclose(st.stress[comp], value, atol=1e-5 * p_mean, err_msg=comp)


def test_periodic_section_is_that_of_the_tiled_surface():
    n, nu, tiles = 16, NU, 15
    grid = Grid(n, PERIOD / 2, periodic=True)
    x, y = grid.mesh()
    rng = np.random.default_rng(3)
    k = 2 * np.pi / PERIOD
    fields = []
    for _ in range(3):   # a few low modes, random amplitudes; zero mean, no first moments (even)
        f = sum(rng.normal() * np.cos(k * (i * x + j * y))
                for i in range(-2, 3) for j in range(-2, 3) if (i, j) != (0, 0))
        fields.append(1e4 * f)
    depths = np.array([0.1, 0.2, 0.5]) * PERIOD
    periodic = section_stresses(grid, nu, depths, *fields)
    big = Grid(tiles * n, tiles * PERIOD / 2)
    tiled = section_stresses(big, nu, depths, *(np.tile(f, (tiles, tiles)) for f in fields), padding=2)
    middle = slice(tiles // 2 * n, tiles // 2 * n + n)
    np.testing.assert_allclose(big.x[middle], grid.x, atol=1e-15)
    for comp in periodic.stress:
        for i in range(depths.size):
            scale = max(np.max(np.abs(tiled.stress[c][i][middle])) for c in periodic.stress)
            np.testing.assert_allclose(periodic.stress[comp][i], tiled.stress[comp][i][middle], atol=1e-3 * scale,
                                       err_msg=f"{comp} at z = {depths[i]}")


def test_periodic_grid_takes_no_padding():
    with pytest.raises(ValueError, match="padding"):
        section_stresses(Grid(8, 1e-3, periodic=True), NU, [1e-4], np.zeros((8, 8)), padding=2)


def test_default_padding_keeps_the_load_images_out_of_deep_stresses():
    """Hertz tractions, a = 0.4 half_width, n = 128, on the axis against Johnson Eq. 3.45 (red team):
    at z = 2 a sigma_xx is +0.0055 p0; padding 2 gave -0.0019 p0 (the wrong sign) and the maximum
    shear 0.0992 p0 for 0.1027 (-3.4 %). The default padding (the padded period 20 x the deepest depth:
    8 here) leaves 2e-4 p0 and 0.15 %; tolerances 5e-4 p0 and 0.3 %."""
    a, n = 1.0, 128
    grid = Grid(n, 2.5 * a)
    x, y = grid.mesh()
    p = np.sqrt(np.clip(1 - (x**2 + y**2) / a**2, 0, None))
    depths = np.array([0.48, 1.0, 2.0]) * a
    sr, sz = hertz_axis_stresses(depths, a, 1.0, NU)
    axis = np.argmin(np.abs(grid.x))
    st = section_stresses(grid, NU, depths, p)
    np.testing.assert_allclose(st.stress["xx"][:, axis], sr, atol=5e-4)
    np.testing.assert_allclose(st.stress["zz"][:, axis], sz, atol=5e-4)
    np.testing.assert_allclose(st.max_shear[:, axis], 0.5 * np.abs(sz - sr), rtol=3e-3)
    assert st.stress["xx"][-1, axis] > 0
    two = section_stresses(grid, NU, depths, p, padding=2)
    assert two.stress["xx"][-1, axis] < 0 and two.max_shear[-1, axis] < 0.97 * 0.5 * abs(sz[-1] - sr[-1])


def test_automatic_padding_is_capped_with_a_warning():
    from viscontact.errors import ViscontactWarning
    from viscontact.physics.subsurface import automatic_padding

    grid = Grid(64, 1e-3)
    assert automatic_padding(grid, 0.0) == 2 and automatic_padding(grid, 0.3e-3) == 3
    with pytest.warns(ViscontactWarning, match="capped at 64 x the domain"):
        assert automatic_padding(grid, 0.1) == 64


def _hertz_tractions(n: int, periodic: bool = False):
    grid = Grid(n, 2e-3, periodic=periodic)
    x, y = grid.mesh()
    p = 2e5 * np.sqrt(np.clip(1 - (x**2 + y**2) / 0.6e-3**2, 0, None))
    return grid, p, 0.3 * p * x / 0.6e-3   # a shear q_x of both signs


@pytest.mark.parametrize("periodic", [False, True])
def test_a_missing_shear_is_a_zero_one_to_the_bit(periodic):
    """A shear left out (``None``: neither transformed nor carried through the terms) gives the stresses
    of a zero array through the full formulas, to the bit: q_y missing with a q_x, and both missing."""
    grid, p, qx = _hertz_tractions(32, periodic)
    depths = [0.0, 0.2e-3, 1e-3]
    zero = np.zeros_like(p)
    for given, zeros in (((p, qx, None), (p, qx, zero)), ((p, None, None), (p, zero, zero))):
        lean, full = (section_stresses(grid, NU, depths, *t) for t in (given, zeros))
        for c in full.stress:
            np.testing.assert_array_equal(lean.stress[c], full.stress[c], err_msg=c)
    assert np.max(np.abs(lean.stress["zz"])) > 1e4


@pytest.mark.parametrize("with_shear", [False, True])
def test_working_bytes_is_the_traced_peak_and_a_missing_shear_saves_its_spectrum(with_shear):
    """``working_bytes`` of 1 (pressure) or 2 (with q_x) tractions against the peak traced by
    ``tracemalloc`` (the shipped creep_subsurface_stress case's depths, padding 5): within 5 %; and
    leaving the zero q_y (and q_x) out lowers the traced peak by at least the spectra not made."""
    import tracemalloc

    from viscontact.physics.subsurface import working_bytes

    grid, p, qx = _hertz_tractions(64)
    depths = np.linspace(0.0, 1e-3, 13)
    shear = qx if with_shear else None
    peaks = []
    for tractions in ((p, shear, None), (p, qx if with_shear else np.zeros_like(p), np.zeros_like(p))):
        tracemalloc.start()
        section_stresses(grid, NU, depths, *tractions, workers=1)
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    count = 2 if with_shear else 1
    assert working_bytes(grid, depths[-1], count) == pytest.approx(peaks[0], rel=0.05)
    spectrum = 16 * 320 * 161   # padding 5: m = 320
    assert peaks[1] - peaks[0] > (3 - count) * spectrum * 0.9
