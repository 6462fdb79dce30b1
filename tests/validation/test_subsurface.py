"""Subsurface stresses (viscontact.subsurface) against closed-form half-space solutions.

* Hertz pressure: sigma_z, sigma_r on the axis (Johnson Eq. 3.45) and the principal shear maximum
  0.31 p0 at 0.48 a for nu = 0.3 (Johnson sec. 3.4). Tolerance 2e-3 p0: the pressure is sampled at
  cell centres (a = 21.5 cells; the edge of the square-root profile costs ~5e-4 p0) and the padded
  transform adds the field of periodic images of the load (~6e-4 p0 at z = 1.5 a with padding 4,
  ~4e-3 with padding 2 at z = 2 a: checked in ``test_images_shrink_with_padding``).
* Point forces (Boussinesq, Cerruti; Johnson Eqs. 3.20, 3.87): far from a one-cell load
  (rho >= 12 dx) the field is that of a point force to O((dx/rho)^2); tolerance 1.5 % of the local
  magnitude. This pins the signs of the tangential (q_x) part.
"""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.grid import Grid
from viscontact.reference import hertz_axis_stresses
from viscontact.subsurface import section_stresses

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
