"""Rolling on a rough surface (a periodic grid, a held creepage): the roller's asperities carried
through the contact at its circumferential speed V (1 + xi), its smooth shape fixed in the frame.

Checked against independent truths:

* the Fourier shift of the roughness against analytic sinusoids and :func:`numpy.roll`;
* elastic (nu = 0.5), frictionless: each step's contact is an elastic contact, so step k's is the
  static elastic contact of the smooth sphere plus the roughness moved by k (1 + xi) cells, solved
  from scratch on that surface (measured: 3e-13 of the peak pressure; a rough line contact 1.7e-13);
* with friction: the friction force is sum q_x dA, Coulomb's |q_x| <= mu p holds everywhere and the
  stuck cells carry |q_x| < mu p;
* zero roughness takes the rough path and gives the smooth rolling bit for bit; a checkpointed run
  resumes bit for bit.
"""
from dataclasses import replace

import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid, shifted_periodic_x
from viscontact.physics.materials import Material
from viscontact.physics.reference import hertz_from_load
from viscontact.problem.problem import TangentialLoading, TimeStepping
from viscontact.running.loop import simulate
from viscontact.solvers.steady_rolling import solve_steady_rolling

from vc_testing import SEED_G0, SEED_LOAD, SEED_RADIUS, seed_material, sphere_problem

G, W, MU = SEED_G0, SEED_LOAD, 0.3
HERTZ = hertz_from_load(W, SEED_RADIUS, G, 0.5)
N = 32


def _roughness(grid: Grid, amplitude: float) -> np.ndarray:
    """A periodic roughness [m]: three sinusoids of the grid's period, amplitude ``amplitude`` each."""
    x, y = grid.mesh()
    k = 2.0 * np.pi / (2.0 * grid.half_width)
    return amplitude * (np.cos(3 * k * x + 0.4) * np.cos(2 * k * y) + np.sin(5 * k * x - 1.1)
                        + np.cos(4 * k * x + 7 * k * y))


def _rolling(material: Material, roughness_amplitude: float, *, friction: float, creepage: float, steps: int,
             speed: float = 0.1):
    """A sphere with a roughness rolling on ``material`` at ``speed`` [m/s] on a periodic 32^2 grid of
    [-2a, 2a]^2: the problem, its smooth gap [m] and its roughness [m]."""
    pb = sphere_problem(material, N, 2 * HERTZ.radius, t_end=1.0, dt=1.0)
    grid = Grid(N, 2 * HERTZ.radius, periodic=True)
    dx = grid.spacing
    smooth = pb.shape.gap(grid)
    rough = _roughness(grid, roughness_amplitude)
    rolling = replace(pb, grid=grid, gap=smooth + rough, surface_topography=True,
                      tangential=TangentialLoading("rolling", friction, rolling_speed=speed, creepage=creepage),
                      time=TimeStepping((steps - 1) * dx / speed, dx / speed))
    return rolling, smooth, rough


def test_the_fourier_shift_moves_a_sinusoid_exactly_and_whole_cells_as_a_roll():
    grid = Grid(16, 1e-3, periodic=True)
    x, y = grid.mesh()
    k = 2.0 * np.pi * 3 / (2.0 * grid.half_width)
    field = np.sin(k * x + 0.3) * np.cos(2 * k * y / 3)
    for cells in (0.37, -1.25, 2.5):
        expected = np.sin(k * (x + cells * grid.spacing) + 0.3) * np.cos(2 * k * y / 3)
        np.testing.assert_allclose(shifted_periodic_x(field, cells), expected, rtol=0, atol=1e-14)
    noise = np.random.default_rng(1).standard_normal((16, 16))
    np.testing.assert_array_equal(shifted_periodic_x(noise, 3.0), np.roll(noise, -3, axis=1))
    np.testing.assert_array_equal(shifted_periodic_x(noise, -2.0), np.roll(noise, 2, axis=1))


@pytest.mark.parametrize("creepage,cells_per_step", [(0.0, 1), (1.0, 2), (-0.5, 0.5)])
def test_frictionless_elastic_rough_rolling_is_the_static_contact_of_the_moved_surface(creepage, cells_per_step):
    """Elastic, frictionless: no memory, so step k is the static contact of the smooth sphere plus the
    roughness moved by k (1 + xi) cells towards -x, solved from scratch."""
    material = Material.elastic(G, 0.5)
    pb, smooth, rough = _rolling(material, 0.05 * HERTZ.approach, friction=0.0, creepage=creepage, steps=5)
    pb = replace(pb, solver=replace(pb.solver, tolerance=1e-12))  # both solves to near round-off
    records = list(simulate(pb))
    assert len(records) == 5
    moved_any = False
    for k, record in enumerate(records):
        cells = k * cells_per_step
        if cells != int(cells):
            continue
        surface = smooth + np.roll(rough, -int(cells), axis=1)
        moved_any |= k > 0 and not np.array_equal(surface, pb.gap)
        static = replace(pb, gap=surface, surface_topography=False, tangential=TangentialLoading(),
                         time=TimeStepping(0.0, pb.time.dt))
        truth = list(simulate(static))[-1]
        peak = truth.pressure.max()
        assert np.abs(record.pressure - truth.pressure).max() < 1e-9 * peak, k
        assert abs(record.delta_z - truth.delta_z) < 1e-9 * truth.delta_z
    assert moved_any
    # the pressure field moves with the asperities: step 0 and the last differ well beyond the tolerance
    assert np.abs(records[-1].pressure - records[0].pressure).max() > 1e-2 * records[0].pressure.max()


def test_rough_rolling_with_friction_keeps_coulomb_and_the_force_balance():
    pb, _, _ = _rolling(seed_material(), 0.05 * HERTZ.approach, friction=MU, creepage=-2e-3, steps=6)
    records = list(simulate(pb))
    for record in records[1:]:
        p, q = record.pressure, record.shear_x
        np.testing.assert_allclose(record.friction_force, q.sum() * pb.grid.cell_area, rtol=1e-12)
        assert np.all(np.abs(q) <= MU * p * (1 + 1e-6) + 1e-9 * p.max())
        stick = record.stick
        assert stick.any() and not stick.all()
        assert np.all(np.abs(q[stick]) < MU * p[stick])


def test_zero_roughness_on_the_rough_path_is_the_smooth_rolling_bit_for_bit():
    rough, smooth_gap, _ = _rolling(seed_material(), 0.0, friction=MU, creepage=-2e-3, steps=4)
    smooth = replace(rough, gap=smooth_gap, surface_topography=False)
    assert rough.rolls_rough and not smooth.rolls_rough
    for a, b in zip(simulate(rough), simulate(smooth), strict=True):
        np.testing.assert_array_equal(a.pressure, b.pressure)
        np.testing.assert_array_equal(a.shear_x, b.shear_x)
        assert a.friction_force == b.friction_force and a.delta_z == b.delta_z


def test_rough_rolling_refuses_what_is_missing_in_one_line():
    pb, _, _ = _rolling(seed_material(), 0.05 * HERTZ.approach, friction=MU, creepage=-2e-3, steps=3)
    with pytest.raises(ParameterError, match="grid.periodic"):
        replace(pb, grid=Grid(N, pb.grid.half_width))
    held_force = replace(pb.tangential, creepage=None, tangential_force=0.1 * MU * W)
    with pytest.raises(ParameterError, match="creepage"):
        replace(pb, tangential=held_force)
    with pytest.raises(ParameterError, match="steady"):
        solve_steady_rolling(pb)


def test_a_checkpoint_of_rough_rolling_resumes_bit_exact(tmp_path):
    """The roughness's position follows from the step's index alone (no state): a run resumed from a
    checkpoint after step 3 repeats the uninterrupted one bit for bit."""
    from viscontact.io.checkpoint import load_checkpoint, save_checkpoint
    from viscontact.solvers.transient import steps

    pb, _, _ = _rolling(seed_material(), 0.05 * HERTZ.approach, friction=MU, creepage=-0.3, steps=7)
    run = list(steps(pb))
    save_checkpoint(tmp_path / "c.npz", pb, run[3][0])
    state, _ = load_checkpoint(tmp_path / "c.npz", pb)
    resumed = list(steps(pb, state=state))
    assert len(resumed) == len(run) - 4
    for (_, ours), (_, want) in zip(resumed, run[4:], strict=True):
        np.testing.assert_array_equal(ours.pressure, want.pressure)
        np.testing.assert_array_equal(ours.shear_x, want.shear_x)


def test_a_rough_line_rolls_as_the_static_contacts_of_its_moved_profile():
    """A line contact (plane strain, a periodic line of cells): a cylinder with a self-affine roughness
    ([indenter.roughness]) rolling frictionless on an elastic body (nu = 0.5, xi = 0) is, at each step,
    the static contact of its profile with the roughness moved by k cells."""
    from viscontact.io.case import Case

    case = Case.from_toml_text("""
[material]
type = "elastic"
shear_modulus = 20e6
poisson_ratio = 0.5
[indenter]
shape = "cylinder"
radius = 0.01
[indenter.roughness]
hurst = 0.8
rms_height = 2e-7
seed = 4
[grid]
dimension = 1
periodic = true
n = 128
half_width = 1e-3
[normal]
control = "load"
value = 2000.0
[tangential]
mode = "rolling"
rolling_speed = 0.1
creepage = 0.0
friction_coefficient = 0.0
[solver]
tolerance = 1e-12
[time]
t_end = 6.25e-4
""")
    pb = case.to_problem()
    assert pb.rolls_rough and pb.grid.dimension == 1
    smooth = pb.shape.gap(pb.grid)
    rough = pb.gap - smooth
    records = list(simulate(pb))
    assert len(records) == 5
    for k, record in enumerate(records):
        static = replace(pb, gap=smooth + np.roll(rough, -k, axis=1), surface_topography=False,
                         tangential=TangentialLoading(), time=TimeStepping(0.0, pb.time.dt))
        truth = list(simulate(static))[-1]
        assert 0 < truth.contact_fraction < 1
        assert np.abs(record.pressure - truth.pressure).max() < 1e-9 * truth.pressure.max(), k
    assert np.abs(records[-1].pressure - records[0].pressure).max() > 1e-2 * records[0].pressure.max()
