"""Rolling in line contact (``grid.dimension = 1``, plane strain) against Carter's exact solution
(:class:`viscontact.physics.reference.Carter`: a rigid cylinder on an elastic half-plane, nu = 0.5 so
that the normal and tangential problems decouple). Measured at n = 256 on [-2a, 2a] (a over 64 cells):
the traction at a held creepage +0.27 % (and +0.07 % at n = 1024: first order in the cell), the stick
zone [a - 2c, a] at the leading edge within two cells, the traction within 1.1-1.9 % of mu_f p0 (its
kink at the stick zone's trailing edge); the transient after six contact widths equals the steady state
to 1e-4; the creepage found under a held force is Carter's within 0.33 %. Tolerances: 0.5 % on forces
and creepages, 2.5 % of mu_f p0 on the traction, two cells on the zone."""
import numpy as np
import pytest

from viscontact.io.case import Case
from viscontact.physics.reference import carter
from viscontact.running.api import run_steady
from viscontact.running.loop import simulate
from vc_testing import rolling_cylinder_case

G, W, R, MU, V = 20e6, 2000.0, 0.01, 0.3, 0.1  # Pa, N/m, m, -, m/s
REF = carter(W, R, MU, G, 0.5)


def _case(n: int, held: str, widths: float = 1.0) -> Case:
    return rolling_cylinder_case(n, shear_modulus=G, poisson_ratio=0.5, radius=R, load=W, speed=V, friction=MU,
                                 half_width=2.0 * REF.half_width, held=held, t_end=widths * 2 * REF.half_width / V)


@pytest.mark.parametrize("share", [0.3, 0.7, -0.5])
def test_steady_rolling_is_carters(share):
    force = share * MU * W
    xi = float(REF.creepage(force))
    ds = run_steady(_case(256, f"creepage = {xi!r}"))
    x = ds["x"].values
    dx, a, c = x[1] - x[0], REF.half_width, REF.stick_half_width(force)
    assert float(ds["friction_force"][0]) == pytest.approx(force, rel=5e-3)
    stuck = x[ds["stick"][0, 0].values]
    assert abs(stuck.min() - (a - 2 * c)) < 2 * dx and abs(stuck.max() - a) < 2 * dx  # at the leading edge
    error = np.abs(ds["shear_x"][0, 0].values - REF.shear_traction(x, force)).max()
    assert error < 0.025 * MU * REF.peak_pressure


def test_carter_grid_convergence_and_force_control():
    force = 0.5 * MU * W
    xi = float(REF.creepage(force))
    errors = [abs(float(run_steady(_case(n, f"creepage = {xi!r}"))["friction_force"][0]) / force - 1)
              for n in (256, 1024)]
    assert errors[1] < 0.5 * errors[0]
    found = run_steady(_case(256, f"tangential_force = {force!r}"))
    assert float(found["creepage"][0]) == pytest.approx(xi, rel=5e-3)


def test_the_line_transient_tends_to_carter():
    force = 0.5 * MU * W
    xi = float(REF.creepage(force))
    case = _case(256, f"creepage = {xi!r}", widths=6)
    last = list(simulate(case.to_problem()))[-1]
    steady = run_steady(case)
    assert last.friction_force == pytest.approx(float(steady["friction_force"][0]), rel=1e-4)
    assert last.friction_force == pytest.approx(force, rel=5e-3)
