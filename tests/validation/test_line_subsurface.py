"""Subsurface stresses of a line contact (``grid.dimension = 1``, plane strain) against McEwen's (1949)
closed form of the field under Hertz's line pressure p0 sqrt(1 - x^2/a^2) (Johnson, *Contact
Mechanics*, 1985, Eq. 4.49, written here independently of the package):

    sigma_x = -(p0/a) [m (1 + (z^2 + n^2)/(m^2 + n^2)) - 2z],   sigma_z = -(p0/a) m (1 - (z^2 + n^2)/(m^2 + n^2)),
    tau_xz = -(p0/a) n (m^2 - z^2)/(m^2 + n^2),   sigma_y = nu (sigma_x + sigma_z),
    m^2, n^2 = ([(a^2 - x^2 + z^2)^2 + 4 x^2 z^2]^(1/2) +- (a^2 - x^2 + z^2))/2, sign(n) = sign(x)

(tension positive; tau_xz with the package's sign, that of the traction q_x on the solid). On the
axis the maximum shear is 0.300 p0 at z = 0.78 a. Measured at n = 512 over +-3a with the transform
padded 16-fold: every component within 9.9e-4 p0 at depths 0.1a to 1.5a (2.8e-3 at n = 256: the
cells that cut the pressure's square-root edge), the axis's maximum shear at 0.78 a within 5e-4 of
its value.
"""
import numpy as np
import pytest

from viscontact.io.case import Case
from viscontact.numerics.grid import Grid
from viscontact.physics.subsurface import section_stresses
from viscontact.running.api import run

A, P0, NU = 1e-3, 1e6, 0.3


def mcewen(x: np.ndarray, z: float, a: float, p0: float, nu: float) -> dict[str, np.ndarray]:
    b = a * a - x * x + z * z
    r = np.sqrt(b * b + 4 * x * x * z * z)
    m = np.sqrt(0.5 * (r + b))
    n = np.sign(x) * np.sqrt(np.maximum(0.5 * (r - b), 0.0))
    q = (z * z + n * n) / (m * m + n * n)
    sx = -(p0 / a) * (m * (1 + q) - 2 * z)
    sz = -(p0 / a) * m * (1 - q)
    return {"xx": sx, "zz": sz, "xz": -(p0 / a) * n * (m * m - z * z) / (m * m + n * n), "yy": nu * (sx + sz)}


def test_mcewen_hertz_line_field():
    grid = Grid(512, 3 * A, dimension=1)
    x = grid.x
    pressure = P0 * np.sqrt(np.clip(1 - (x / A) ** 2, 0, None))[None, :]
    depths = np.array([0.1, 0.25, 0.5, 0.78, 1.5]) * A
    section = section_stresses(grid, NU, depths, pressure, padding=16)
    for i, z in enumerate(depths):
        reference = mcewen(x, z, A, P0, NU)
        for c, ref in reference.items():
            assert np.abs(section.stress[c][i] - ref).max() < 1.5e-3 * P0, (c, z / A)
        assert not section.stress["xy"][i].any() and not section.stress["yz"][i].any()
    axis = int(np.argmin(np.abs(x)))
    on_axis = mcewen(np.zeros(1), 0.78 * A, A, P0, NU)
    tau = 0.5 * float(on_axis["xx"][0] - on_axis["zz"][0])
    assert tau == pytest.approx(0.300 * P0, rel=2e-3)
    assert section.max_shear[3, axis] == pytest.approx(tau, rel=5e-4)


def test_a_line_run_writes_its_plane_strain_stresses():
    """Through a case (n = 256, a = 38 cells, z = 0.67 a): the stresses of Hertz's line contact,
    measured within 5.9e-5 p0 (the transform padded to 60 x max(z, half_width), whose images'
    sigma_xx, (pi^2/3) a z / D^2 of p0, cost 1.4 % of p0 at the 2-D grid's padding of 2)."""
    from viscontact.physics.reference import hertz_line_from_load

    case = Case.from_dict({
        "title": "line stresses", "material": {"type": "elastic", "shear_modulus": 1e6, "poisson_ratio": NU},
        "indenter": {"shape": "cylinder", "radius": 0.01}, "grid": {"n": 256, "half_width": 1e-3, "dimension": 1},
        "normal": {"control": "load", "value": 20.0}, "tangential": {"mode": "none"},
        "time": {"t_end": 1e-3, "dt": 1e-3}, "output": {"subsurface_depths": [2e-4]}})
    ds = run(case)
    assert ds["stress_zz"].dims == ("t_sub", "z", "x") and ds["stress_zz"].shape == (1, 1, 256)
    hz = hertz_line_from_load(20.0, 0.01, 1e6, NU, 1e-3)
    reference = mcewen(ds["x"].values, 2e-4, hz.radius, hz.peak_pressure, NU)
    for c in ("xx", "zz", "xz", "yy"):
        assert np.abs(ds[f"stress_{c}"].values[-1, 0] - reference[c]).max() < 3e-4 * hz.peak_pressure
