"""The analytic indenter shapes (viscontact.problem.shapes): their case keys, accepted and refused in one
line each; their gaps on the grid (the sphere's bit for bit as before, a line grid's profile through
the axis); the problem's shape and radius kept one description; the guards' shape-aware estimates."""
from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import pytest
from vc_testing import sphere_problem

from viscontact.errors import ParameterError, ViscontactWarning
from viscontact.io.case import Case
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.problem.shapes import SHAPES, Cone, Cylinder, Ellipsoid, FlatPunch, Sphere
from viscontact.running import guards

CASE = """
[material]
type = "elastic"
shear_modulus = 1e6
poisson_ratio = 0.3
[grid]
n = 64
half_width = 2e-3
[normal]
control = "displacement"
value = 5e-6
[time]
t_end = 1e-3
dt = 1e-3
[indenter]
"""
KEYS = {"sphere": 'radius = 0.01', "cylinder": 'radius = 0.01\nlength = 2e-3\nedge_radius = 2e-4',
        "ellipsoid": 'radius_x = 0.02\nradius_y = 0.01', "flat_punch": 'radius = 5e-4', "cone": 'half_angle = 70.3'}


def _case(shape: str, keys: str) -> Case:
    return Case.from_toml_text(CASE + f'shape = "{shape}"\n{keys}\n', ".")


def test_every_shape_is_registered_and_accepted_with_its_keys():
    assert set(SHAPES) == set(KEYS)
    for name, keys in KEYS.items():
        problem = _case(name, keys).to_problem()
        assert problem.shape.name == name
        assert problem.gap[31:33, 31:33].max() == problem.gap.min() >= 0  # lowest about the origin


@pytest.mark.parametrize(("shape", "keys", "key"), [
    ("cone", "", "indenter.half_angle"),                                   # required
    ("ellipsoid", "radius_x = 0.02", "indenter.radius_y"),                 # required
    ("cylinder", "length = 2e-3", "indenter.radius"),                      # required
    ("flat_punch", "", "indenter.radius"),                                 # required
    ("sphere", "radius = 0.01\nhalf_angle = 70.0", "indenter.half_angle"),  # another shape's key
    ("flat_punch", "radius = 5e-4\nlength = 1e-3", "indenter.length"),     # the cylinder's
    ("cone", "half_angle = 70.0\nradius = 0.01", "indenter.radius"),       # a cone has no radius
    ("cone", "half_angle = 90.0", "indenter.half_angle"),                  # (0, 90) degrees
    ("cone", "half_angle = 0.0", "indenter.half_angle"),
    ("cone", "half_angle = 1.2", "indenter.half_angle"),                   # radians for degrees: slope 48
    ("cylinder", "radius = 0.01\nlength = 1e-3\nedge_radius = 6e-4", "indenter.edge_radius"),  # > length / 2
    ("flat_punch", "radius = 5e-4\nedge_radius = -1e-5", "indenter.edge_radius"),              # >= 0 m
    ("ellipsoid", "radius_x = 0.02\nradius_y = 0.0", "indenter.radius_y"),                    # > 0 m
])
def test_refused_keys_name_the_key_in_one_line(shape, keys, key):
    with pytest.raises(ParameterError) as refused:
        _case(shape, keys)
    assert refused.value.key == key and "\n" not in str(refused.value), str(refused.value)


def test_a_steep_cone_warns_once_and_roughness_goes_on_any_shape():
    steep = _case("cone", "half_angle = 30.0").to_problem()  # no warning at load
    with pytest.warns(ViscontactWarning, match="small-slope theory") as caught:
        guards.check_problem(replace(steep, normal=replace(steep.normal, history=type(steep.normal.history)
                                                           .constant(1e-3))))
    assert sum("small-slope" in str(w.message) for w in caught) == 1
    rough = _case("cone", "half_angle = 70.3\n[indenter.roughness]\nhurst = 0.8\nrms_height = 1e-8").to_problem()
    assert rough.surface_topography and rough.shape == Cone(70.3)


@pytest.mark.parametrize(("build", "key"), [(lambda: Sphere(-1.0), "indenter.radius"),
                                            (lambda: Cone(float("nan")), "indenter.half_angle"),
                                            (lambda: FlatPunch(1e-3, -1e-4), "indenter.edge_radius"),
                                            (lambda: Ellipsoid(0.01, "0.01"), "indenter.radius_y")])
def test_a_shape_built_in_python_checks_its_values(build, key):
    with pytest.raises(ParameterError) as refused:
        build()
    assert refused.value.key == key


def test_an_infinite_cylinder_is_refused_on_a_2d_grid():
    problem = _case("cylinder", KEYS["cylinder"]).to_problem()
    with pytest.raises(ParameterError, match="indenter.length: required for shape = 'cylinder' on a 2-D grid"):
        guards.check_problem(replace(problem, shape=Cylinder(0.01)))


def test_the_sphere_is_as_before_bit_for_bit_and_mirrors_the_radius():
    problem = _case("sphere", "radius = 0.01").to_problem()
    x, y = problem.grid.mesh()
    assert np.array_equal(problem.gap, (x**2 + y**2) / (2.0 * 0.01))
    assert problem.radius == 0.01 and problem.shape == Sphere(0.01)
    assert replace(problem, radius=None).shape is None       # a plain gap, as replace always made it
    assert replace(problem, radius=0.02).shape == Sphere(0.02)
    with pytest.raises(ParameterError, match="indenter.radius: is a sphere's radius; the indenter is a cone"):
        replace(problem, shape=Cone(70.0))


class _LineGrid:
    """A grid whose mesh is one row at y = 0 (the line contact's): what a shape's gap is built from."""

    def __init__(self, n: int, half_width: float):
        self.grid = Grid(n, half_width)

    def mesh(self):
        x = self.grid.x[None, :]
        return x, np.zeros_like(x)


def test_on_a_line_grid_the_profiles_are_those_through_the_axis():
    line = _LineGrid(64, 2e-3)
    x = line.grid.x[None, :]
    assert np.array_equal(Cylinder(0.01, 2e-3, 2e-4).gap(line), x**2 / (2 * 0.01))
    assert np.array_equal(Cylinder(0.01).gap(line), x**2 / (2 * 0.01))
    punch = FlatPunch(5e-4).gap(line)
    assert np.array_equal(punch == 0, np.abs(x) <= 5e-4) and punch.max() == FlatPunch(5e-4).wall
    assert np.allclose(Ellipsoid(0.02, 0.01).gap(line), x**2 / 0.04, rtol=1e-15)
    assert np.allclose(Cone(60.0).gap(line), np.abs(x) / math.tan(math.radians(60.0)), rtol=1e-15)


def test_a_rollers_ends_and_a_rounded_punch():
    grid = Grid(64, 2e-3)
    x, y = grid.mesh()
    roller = Cylinder(0.01, 2e-3, 2e-4).gap(grid)
    middle = np.abs(y) <= 0.8e-3
    assert np.array_equal(roller[middle], (x**2 / 0.02)[middle])
    assert np.all(roller[np.abs(y) > 1e-3] >= 0.01)          # end walls: one roller radius high
    ends = (np.abs(y) > 0.8e-3) & (np.abs(y) <= 1e-3)
    assert np.allclose(roller[ends], (x**2 / 0.02 + (np.abs(y) - 0.8e-3) ** 2 / 4e-4)[ends], rtol=1e-14)
    r = np.hypot(x, y)
    rounded = FlatPunch(5e-4, 1e-4).gap(grid)
    assert np.all(rounded[r <= 5e-4] == 0)
    assert np.allclose(rounded[r > 5e-4], np.minimum((r - 5e-4) ** 2 / 2e-4, 5e-4)[r > 5e-4], rtol=1e-15)


def test_results_carry_the_shape():
    from viscontact.io.results import global_attrs

    attrs = global_attrs(_case("cone", "half_angle = 70.3").to_problem())
    assert attrs["indenter_shape"] == "cone" and attrs["indenter_half_angle"] == 70.3
    assert math.isnan(attrs["radius"])
    sphere = global_attrs(_case("sphere", "radius = 0.01").to_problem())
    assert "indenter_shape" not in sphere and sphere["radius"] == 0.01


def test_a_cone_too_coarse_is_refused_naming_its_singular_tip():
    """A cone of 70.3 degrees pressed 5 um: a = 2 delta tan(alpha)/pi = 8.9 um, 0.14 cells of 62.5 um."""
    with pytest.raises(ParameterError, match=r"grid\.n: .*0\.14 cells.*the load at a given approach.*tip is "
                       r"singular.*use grid\.half_width = 0\.002 m and grid\.n = 1024"):
        guards.check_problem(_case("cone", "half_angle = 70.3").to_problem())


def test_a_flat_punch_estimates_its_face_and_not_a_sphere():
    """The face of 0.5 mm at any load; its reach with a rounded rim, a + edge_radius; no small-strain
    check (no curvature); a coarse face warns of its load error with the punch's rim named."""
    material = Material.elastic(1e6, 0.3)
    problem = replace(sphere_problem(material, 64, 2e-3, value=0.01), radius=None, shape=FlatPunch(5e-4, 2e-4),
                      gap=FlatPunch(5e-4, 2e-4).gap(Grid(64, 2e-3)))
    est = guards.contact_estimate(problem)
    assert est.smallest == 5e-4 and est.largest == pytest.approx(7e-4, rel=1e-12) and math.isnan(est.strain_ratio)
    coarse = replace(problem, grid=Grid(16, 2e-3), gap=FlatPunch(5e-4).gap(Grid(16, 2e-3)), shape=FlatPunch(5e-4))
    with pytest.warns(ViscontactWarning, match=r"2 cells across the contact radius.*load at a given approach may be "
                      r"off by about 6 %.*rim is singular"):
        guards.check_problem(coarse)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ViscontactWarning)
        guards.check_problem(problem)


def test_a_rounding_narrower_than_two_cells_is_said_to_act_as_sharp():
    grid = Grid(64, 2e-3)  # dx = 62.5 um
    (said,) = FlatPunch(5e-4, 1e-4).caveats(grid)
    assert "1.6 cells" in said and "punch's rounded rim acts as a sharp one" in said
    assert FlatPunch(5e-4, 2e-4).caveats(grid) == [] and FlatPunch(5e-4).caveats(grid) == []
    assert "roller's rounded end" in Cylinder(0.01, 2e-3, 1e-4).caveats(grid)[0]
