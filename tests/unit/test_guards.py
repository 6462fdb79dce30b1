"""Guards against silent wrong answers (viscontact.running.guards): resolution, domain, small strain, time step.

Each crafted case is one that used to run to exit 0 with a wrong answer (issue 14 item 3); the
estimates are checked against independent truth: the Hertz and Lee & Radok solutions, runs of the
solver itself and the convergence orders of the time schemes.
"""
from __future__ import annotations

import glob
import math
import os
import tempfile
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from viscontact import cli
from viscontact.running import guards
from viscontact.numerics.hereditary import hereditary_integral
from viscontact.solvers.time_step_error import time_step_error
from viscontact.io.case import load_case
from viscontact.errors import ParameterError, ViscontactWarning
from viscontact.physics.materials import Material
from viscontact.problem.problem import PiecewiseLinear, TimeStepping
from viscontact.physics.reference import hertz_from_load
from viscontact.running.loop import simulate

from vc_testing import dry_run, seed_material, sphere_problem, observed_order

ROOT = Path(__file__).resolve().parents[2]
CREEP = ROOT / "cases" / "creep_indentation.toml"
RELAXATION = ROOT / "cases" / "relaxation_indentation.toml"
ELASTIC = {"material.type": "elastic", "material.shear_modulus": 1.93e6, "material.shear_modulus_instantaneous": None,
           "material.shear_modulus_long_term": None, "material.retardation_time": None}


def _dry_run(capsys, case: Path, *sets: str) -> tuple[int, list[str]]:
    return dry_run(capsys, case, *sets)


def _problem(path: Path, **overrides):
    return load_case(path).with_overrides(overrides).to_problem()


def _check_quietly(problem) -> list[str]:
    """check_problem's warnings (raises its errors)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        guards.check_problem(problem)
    return [str(w.message) for w in caught if issubclass(w.category, ViscontactWarning)]


# --- the shipped cases pass ----------------------------------------------------------------------
#: the seed's cases under a held approach with the seed's first-order scheme at the seed's dt: the
#: relaxation is missed by 10-13 % over the first relaxation times (measured against the exact
#: held-approach load in test_held_approach_estimate_is_the_measured_local_error), which is warned
SEED_SCHEME_RELAXATION = {"seed_table2_ratio10_displacement", "seed_table3_case1", "seed_table3_case2",
                          "seed_table3_case3", "seed_table3_case4"}


@pytest.mark.parametrize("path", sorted(glob.glob(str(ROOT / "cases" / "*.toml"))), ids=lambda p: Path(p).stem)
def test_shipped_cases_pass_every_guard_without_a_warning(path):
    found = _check_quietly(load_case(path).to_problem())
    if Path(path).stem in SEED_SCHEME_RELAXATION:
        assert len(found) == 1 and "the constant scheme misses the relaxation by about 1" in found[0], found
        assert 'time.scheme = "linear"' in found[0]
    else:
        assert found == []


@pytest.mark.parametrize("name, over", [("seed_table3_case1", {"time.t_end": 0.004, "time.dt": 0.0001999}),
                                        ("pmma_master_curve", {"time.t_end": 60.0, "time.dt": 4.8828125,
                                                               "normal.history": None, "normal.value": 1e-6})])
def test_held_approach_estimate_is_the_measured_local_error(name, over):
    """Under a held approach delta on a sphere the contact radius stays sqrt(R delta), so the exact load
    is W(t) = (4/3) sqrt(R) delta^1.5 2 G(t) / (1 - nu). The estimate is the largest error of a step
    relative to that step's exact value: seed Table 3's first-order scheme misses it by 10.2 % at
    t = 2 ms (the estimate relative to the first, largest load said 4 %, no warning), PMMA held at once
    by 10 % at the first step. Estimate and measured error agree to a fifth (n = 32)."""
    problem = _problem(ROOT / "cases" / f"{name}.toml", **{"grid.n": 32, "tangential.mode": "none", **over})
    mat, radius, delta = problem.material, problem.radius, problem.normal.history.reference
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)
        records = list(simulate(problem))
    times = np.array([r.t for r in records])
    relaxation = mat.g_inf + sum(g * np.exp(-times / tau) for g, tau in zip(mat.g, mat.tau))
    exact = 4 / 3 * math.sqrt(radius) * delta**1.5 * 2 * relaxation / (1 - mat.poisson_ratio)
    measured = float(np.max(np.abs(np.array([r.load for r in records]) / exact - 1)))
    assert measured > 0.09 and time_step_error(problem) == pytest.approx(measured, rel=0.2)


# --- resolution and domain -----------------------------------------------------------------------
def test_peak_pressure_estimate_bounds_measured_hertz_errors():
    """Elastic Hertz (seed material, 0.15 N) at 2, 3, 4 cells across a0: the estimate is at least the
    measured peak error and at most twice it (measured 3.9 %, 2.6 %, 1.5 % when written)."""
    material = Material.elastic(1.93e6, 0.3)
    hertz = hertz_from_load(0.15, 0.01, 1.93e6, 0.3)
    for cells in (2, 3, 4):
        n = 4 * cells
        pb = sphere_problem(material, n, 2 * hertz.radius, t_end=0.0, dt=1.0)
        peak = list(simulate(pb))[-1].pressure.max()
        measured = abs(peak / hertz.peak_pressure - 1)
        estimate = guards.peak_pressure_error(hertz.radius / pb.grid.spacing)
        assert measured <= estimate <= 2.0 * measured + 0.005, (cells, measured, estimate)


def test_coarse_grid_is_refused_with_a_grid_that_works(capsys):
    # grid.n = 8 on the elastic seed case: contact radius 1.2 cells, peak -27 % (issue 14)
    code, err = _dry_run(capsys, CREEP, "grid.n=8", "material.type=\"elastic\"", "material.shear_modulus=1.93e6",
                         "material.shear_modulus_instantaneous=", "material.shear_modulus_long_term=",
                         "material.retardation_time=")
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: grid.n:")
    n = int(err[0].split("grid.n = ")[-1].split()[0].rstrip(".;)"))
    half_width = float(err[0].split("grid.half_width = ")[-1].split()[0])
    assert _check_quietly(_problem(CREEP, **ELASTIC, **{"grid.n": n, "grid.half_width": half_width})) == []


def test_domain_smaller_than_the_contact_is_refused_with_a_domain_that_works(capsys):
    # half_width = 0.1 mm on a 0.6 mm contact: peak -98 %, delta +617 % (issue 14)
    code, err = _dry_run(capsys, CREEP, "grid.half_width=1e-4")
    assert code == 2 and len(err) == 1 and "grid.half_width" in err[0]
    half_width = float(err[0].split("grid.half_width = ")[-1].split()[0])
    n = int(err[0].split("grid.n = ")[-1].split()[0].rstrip(".;)"))
    assert half_width > 1.268e-3  # holds the long-term contact (Lee & Radok: a0 10^(1/3))
    assert _check_quietly(_problem(CREEP, **{"grid.n": n, "grid.half_width": half_width})) == []


def test_displacement_control_on_a_huge_domain_is_refused(capsys):
    # used to give zero load, zero contact and complete = 1
    code, err = _dry_run(capsys, RELAXATION, "grid.half_width=0.1")
    assert code == 2 and len(err) == 1 and "grid.n" in err[0]


def test_huge_load_beyond_small_strain_is_refused(capsys):
    code, err = _dry_run(capsys, CREEP, "normal.value=1e6")  # a/R = 13.8 at G(0) (issue 14)
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: normal.value:")
    assert "indenter radius" in err[0]


def test_marginal_small_strain_is_a_warning():
    # a(G(inf)) = a(G(0)) 10^(1/3); a/R = 0.3 needs W = 0.15 N (0.3 / 0.127)^3
    messages = _check_quietly(_problem(CREEP, **{"normal.value": 0.15 * (0.3 / 0.1268) ** 3, "grid.half_width": 4.5e-3,
                                                 "grid.n": 256}))
    assert any("indenter radius" in m for m in messages)


def test_rough_period_is_not_judged_as_one_asperity():
    """On a rough periodic cell the load spreads over many asperities: the Hertz estimate from the
    curvature at the lowest point (0.42 R at 32^2, a refusal at 16^2 when written) is no estimate of
    the contact, so no contact-size warning or refusal. A sphere on a periodic grid is still judged."""
    rough = ROOT / "cases" / "rough_periodic_sliding.toml"
    for n in (16, 32):
        problem = _problem(rough, **{"grid.n": n})
        assert guards.contact_estimate(problem) is None
        assert not any("contact radius" in m for m in _check_quietly(problem))
    sphere = _problem(CREEP, **{"grid.periodic": True, "grid.n": 8})
    assert guards.contact_estimate(sphere) is not None
    with pytest.raises(ParameterError, match="grid.n"):
        guards.check_problem(sphere)


# --- the time step -------------------------------------------------------------------------------
def test_hereditary_integral_against_quadrature():
    mat = seed_material()
    history = PiecewiseLinear((0.0, 0.004, 0.01), (1.0, 3.0, 2.0))
    h = 1e-4
    t = np.arange(201) * h
    f = np.array([history(x) for x in t])
    y = hereditary_integral(mat.g_inf, np.array(mat.g), np.array(mat.tau), f, h)
    for k in (0, 7, 40, 73, 200):
        tk = t[k]
        exact = mat.relaxation_modulus(tk) * history(0.0)
        for (a, fa), (b, fb) in zip(zip(history.times, history.values), list(zip(history.times, history.values))[1:]):
            if tk > a:
                exact += quad(lambda s: float(mat.relaxation_modulus(tk - s)) * (fb - fa) / (b - a), a, min(b, tk))[0]
        assert y[k] == pytest.approx(exact, rel=1e-10)


def test_time_step_estimate_matches_the_solver_on_the_relaxation_case():
    """The seed scheme at dt = 1 ms on the relaxation case: W/W0 = 0.14 against G(t)/G(0) = 0.43 at
    t = dt, 67 % low. The one-point estimate predicts the solver's error, each step's against its own
    exact value (held approach: exact correspondence)."""
    pb = _problem(RELAXATION, **{"grid.n": 32, "time.dt": 1e-3, "time.t_end": 3e-3, "time.scheme": "constant"})
    loads = np.array([r.load for r in simulate(replace(pb, output=replace(pb.output, fields=("pressure",))))])
    exact = pb.material.relaxation_modulus(np.arange(4) * 1e-3) / pb.material.shear_modulus_instantaneous
    error = np.max(np.abs(loads / loads[0] / exact - 1))
    assert loads[1] / loads[0] == pytest.approx(0.1435, abs=0.01) and exact[1] == pytest.approx(0.431, abs=1e-3)
    assert time_step_error(pb) == pytest.approx(error, rel=0.05)


def test_time_step_refused_and_warned(capsys):
    code, err = _dry_run(capsys, RELAXATION, "time.dt=1e-3", "time.scheme=\"constant\"")
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: time.dt:") and "67 %" in err[0]
    code, err = _dry_run(capsys, RELAXATION, "time.dt=2.5e-4", "time.scheme=\"constant\"")
    assert code == 0 and len(err) == 1 and err[0].startswith("viscontact: warning: time.dt") and "%" in err[0]
    code, err = _dry_run(capsys, RELAXATION, "time.dt=1e-3", "time.scheme=\"linear\"")  # dt = the relaxation time
    assert code == 0 and len(err) == 1 and "the linear scheme misses the relaxation by about 8.8 %" in err[0]
    code, err = _dry_run(capsys, RELAXATION, "time.dt=5e-4", "time.scheme=\"linear\"")
    assert code == 0 and err == []


@pytest.mark.parametrize("scheme, order", [("constant", 1.0), ("linear", 2.0)])
def test_time_step_estimate_converges_at_the_order_of_the_scheme(scheme, order):
    for path in (CREEP, RELAXATION):
        pb = _problem(path, **{"time.scheme": scheme})
        dts = [2.5e-4, 1.25e-4, 6.25e-5]  # asymptotic: dt << the relaxation time 1 ms
        errors = [time_step_error(replace(pb, time=TimeStepping(0.02, dt, scheme))) for dt in dts]
        assert observed_order(dts, errors) == pytest.approx(order, abs=0.25), (path.stem, errors)


def test_elastic_material_has_no_time_step_error():
    pb = sphere_problem(Material.elastic(1e6, 0.3), 32, 2e-3, t_end=1.0, dt=0.5)
    assert time_step_error(pb) == 0.0


# --- the material ----------------------------------------------------------------------------------
@pytest.mark.parametrize("sets", [("material.shear_modulus_long_term=1e-300", "time.scheme=\"linear\""),
                                  ("material.shear_modulus_long_term=1e-300",)])
def test_extreme_moduli_are_one_line(capsys, sets):
    code, err = _dry_run(capsys, CREEP, *sets)
    assert code == 2 and len(err) == 1 and "material.shear_modulus_long_term" in err[0]


def test_guard_runs_for_api_users_too():
    with pytest.raises(ParameterError, match="grid.n"):
        from viscontact.running import api

        api.prepare(load_case(CREEP).with_overrides({"grid.n": 8, "grid.half_width": 5e-3}))
    assert math.isfinite(guards.contact_estimate(_problem(CREEP)).largest)


def test_sliding_time_step_suggestion_passes(capsys):
    """Sliding ties dt to the grid (dt = dx / (v k)): the seed's Table 2 relaxation case previewed at
    n = 64 misses the relaxation by 29 %; the suggested steps_per_cell passes."""
    case = ROOT / "cases" / "seed_table2_ratio10_displacement.toml"
    code, err = _dry_run(capsys, case, "grid.n=64")
    assert code == 2 and len(err) == 1 and err[0].startswith("viscontact: error: tangential.steps_per_cell:")
    k = int(err[0].split("steps_per_cell = ")[-1].split()[0])
    assert _check_quietly(_problem(case, **{"grid.n": 64, "tangential.steps_per_cell": k})) == []


def test_equivalent_radius_of_a_measured_rough_sphere():
    """A height file of a 10 mm sphere with 1 um rms of roughness (slope 0.02) was refused: the
    curvature at its lowest cell, the roughness's, gave R = 0.2 mm and a/R = 0.76. The fitted
    paraboloid gives the sphere's radius (truth: 10 mm; exact for the smooth paraboloid), the case
    passes the checks and a0 is Hertz's; a tilted plane has none."""
    from viscontact.problem.scales import equivalent_radius, hertz_scale

    smooth = sphere_problem(Material.elastic(1.93e6, 0.3), 64, 1.2e-3, t_end=1e-3, dt=5e-4)
    noise = np.random.default_rng(3).standard_normal(smooth.gap.shape) * 1e-6
    rough = replace(smooth, gap=smooth.gap + noise - (smooth.gap + noise).min(), radius=None)
    assert equivalent_radius(replace(smooth, radius=None)) == pytest.approx(0.01, rel=1e-9)
    assert equivalent_radius(rough) == pytest.approx(0.01, rel=0.03)
    guards.check_problem(rough)
    assert hertz_scale(rough)[0] == pytest.approx(hertz_scale(smooth)[0], rel=0.01)
    x, y = smooth.grid.mesh()
    # planes, whose fitted curvature is round-off of either sign (R = 9e14 m on one CPU)
    for slope, angle in ((1e-3, 0.0), (1e-3, 0.3), (0.05, 1.0), (2.0, 2.0), (1e-6, 4.0)):
        plane = slope * (np.cos(angle) * x + np.sin(angle) * y)
        assert math.isnan(equivalent_radius(replace(smooth, gap=plane - plane.min(), radius=None))), (slope, angle)


def test_equivalent_radius_is_measured_on_the_scale_of_the_contact():
    """Two asperities: a 2 mm sphere and, 3 mm away and 10 um higher, a 20 mm one. On a stiff body
    (G = 50 MPa, 0.15 N) the first alone touches (Hertz: delta = 6.7 um < 10 um, a = 0.12 mm), so
    the truth is 2 mm; the first fit, over half the half-width (1.5 mm), reaches the other asperity
    and gives about 3.9 mm. Refitted over two contact radii it gives the 2 mm."""
    from viscontact.problem.scales import equivalent_radius

    pb = sphere_problem(Material.elastic(50e6, 0.3), 128, 3e-3, t_end=1e-3, dt=5e-4)
    x, y = pb.grid.mesh()
    near = ((x + 1.5e-3) ** 2 + y**2) / (2 * 2e-3)
    far = ((x - 1.5e-3) ** 2 + y**2) / (2 * 20e-3) + 10e-6
    assert equivalent_radius(replace(pb, gap=np.minimum(near, far), radius=None)) == pytest.approx(2e-3, rel=1e-6)


def _punch(n: int, wall: float, control: str = "displacement", value: float = 3.5e-6, noise: float = 0.0):
    """A flat punch of radius 0.5 mm (gap 0 on its face, ``wall`` [m] about it, plus white noise of rms
    ``noise`` [m]) on an elastic body (G = 1 MPa), n x n cells on +-2 mm; 3.5 um of approach (W = 10 mN)."""
    pb = sphere_problem(Material.elastic(1e6, 0.3), n, 2e-3, control=control, value=value, t_end=1e-3, dt=1e-3)
    x, y = pb.grid.mesh()
    gap = np.where(x**2 + y**2 <= 0.5e-3**2, 0.0, wall) + noise * np.random.default_rng(1).standard_normal(x.shape)
    return replace(pb, gap=gap - gap.min(), radius=None)


def test_a_flat_punch_has_no_equivalent_radius():
    """A flat punch's contact is its face at any load: no sphere's Hertz scale describes it. Its
    lowest point was the first of the tied cells, on the rim, and the fit there took in the walls:
    R = 64 mm, 9.3 mm, 0.56 mm for walls of 20 um, 100 um, 1 mm at n = 64 under load (a0 = 0.55 to
    0.11 mm), which the guards then took for the contact's scale. NaN now for every wall, grid and
    control, and with noise of 10 nm or 0.1 um rms on it (walls of 100 um): no a0, p0, no estimate."""
    from viscontact.problem.scales import equivalent_radius, hertz_scale

    for n in (64, 128):
        for control, value in (("load", 0.01), ("displacement", 3.5e-6)):
            for wall in (2e-5, 1e-4, 3e-4, 1e-3):
                pb = _punch(n, wall, control, value)
                assert math.isnan(equivalent_radius(pb)), (n, control, wall)
                assert all(math.isnan(v) for v in hertz_scale(pb)) and guards.contact_estimate(pb) is None
    for noise in (1e-8, 1e-7):
        assert math.isnan(equivalent_radius(_punch(128, 1e-4, noise=noise))), noise


def test_equivalent_radius_of_lines_offset_spheres_flat_tips_and_quantised_heights():
    """A cylinder's minima are a line (its contact a strip across the domain): the fit gave 2 R, its
    laplacian's, now NaN, along x and at 0.3 rad. What keeps its radius: a sphere centred between
    nodes, an ellipsoid of 1 : 10 (its laplacian's 2 R1 R2 / (R1 + R2)), and, within 3 %, a 10 mm
    sphere whose tip is a flat of 0.1 mm radius (against a contact of 0.59 mm) or whose heights are
    rounded to 0.1 um (a bottom level 63 um across)."""
    from viscontact.problem.scales import equivalent_radius

    pb = sphere_problem(Material.elastic(1.93e6, 0.3), 128, 1.2e-3, t_end=1e-3, dt=5e-4)
    x, y = pb.grid.mesh()

    def radius(gap):
        return equivalent_radius(replace(pb, gap=gap - gap.min(), radius=None))

    for angle in (0.0, 0.3):
        assert math.isnan(radius((np.cos(angle) * x + np.sin(angle) * y) ** 2 / 0.02)), angle
    half = pb.grid.spacing / 2
    assert radius(((x - half) ** 2 + (y - half) ** 2) / 0.02) == pytest.approx(0.01, rel=1e-9)
    assert radius(x**2 / 2e-3 + y**2 / 0.02) == pytest.approx(2 * 1e-3 * 0.01 / 0.011, rel=1e-9)
    assert radius(np.maximum(x**2 + y**2 - 1e-4**2, 0.0) / 0.02) == pytest.approx(0.01, rel=0.03)
    assert radius(np.round(pb.gap / 1e-7) * 1e-7) == pytest.approx(0.01, rel=0.03)


@pytest.mark.parametrize("n", [64, 128])
def test_a_flat_punch_under_displacement_control_passes_the_checks(tmp_path, n):
    """The red team's punch (0.5 mm, 3.5 um of approach, a gap file): refused at every grid with
    advice that could not work (n = 64: 0.71 cells across the contact, use n = 256; n = 128: use
    n = 1024; n = 256, 512: a/R = 0.55, 0.74), all from the fit about its rim. It passes now, warned
    of nothing with walls of 100 um; with walls of 1 mm only of their rms slope (2.0 at n = 64)."""
    from viscontact.running.api import prepare
    from viscontact.io.case import Case

    x = -2e-3 + (np.arange(n) + 0.5) * 4e-3 / n
    inside = np.add.outer(x**2, x**2) <= 0.5e-3**2
    for wall in (1e-4, 1e-3):
        np.save(tmp_path / "gap.npy", np.where(inside, 0.0, wall))
        case = Case.from_toml_text(f"""
[material]
type = "elastic"
shear_modulus = 1e6
poisson_ratio = 0.3
[indenter]
shape = "surface"
file = "gap.npy"
[grid]
n = {n}
half_width = 2e-3
[normal]
control = "displacement"
value = 3.5e-6
[time]
t_end = 1e-3
dt = 1e-3
""", tmp_path)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            problem, _ = prepare(case)
        said = [str(w.message) for w in caught if issubclass(w.category, ViscontactWarning)]
        assert said == [] if wall == 1e-4 else (len(said) == 1 and "rms slope is" in said[0]), said
        assert guards.contact_estimate(problem) is None


def test_the_dry_run_of_a_result_without_fields_says_so(capsys):
    """``output.fields = []`` was described as ``(161 records of )``."""
    out = Path(tempfile.gettempdir()) / f"viscontact-dry-run-{os.getpid()}" / "r.nc"
    assert cli.main(["run", str(CREEP), "--out", str(out), "--dry-run", "--set", "grid.n=32",
                     "--set", "output.fields=[]"]) == 0
    said = capsys.readouterr().out
    assert "records of the histories only (output.fields = [])" in said and "records of )" not in said


def _fretting_problem(points, dt, t_end):
    """An elastic sphere (16^2) under the seed's load, partial slip under the displacement history
    ``points`` ([(t, delta_x), ...]) at ``dt``."""
    history = PiecewiseLinear(tuple(float(t) for t, _ in points), tuple(float(d) for _, d in points))
    return sphere_problem(Material.elastic(1.93e6, 0.5), 16, 1e-3, mode="partial_slip", friction=0.3, t_end=t_end,
                          dt=dt, scheme="linear", displacement_history=history)


def test_a_time_step_that_misses_a_turning_point_of_the_displacement_history_is_refused():
    """The run's delta_x is the history at the steps t = k dt: a reversal between two steps is cut to
    the nearer one, and a cycle faster than dt is aliased into another. Before, both ran silently:
    +-8 um reversing every 0.2 ms at dt = 0.25 ms turned at 0, +-4 and +-8 um in turn (and stopped
    at 'the amplitude exceeds gross slip' for a jump of 12 um in one step); a turning point at
    2.6 ms at dt = 0.25 ms turned at 7.69 um instead of 8 (-3.8 %). Refused above 1 % of the largest
    |delta_x| (keyed time.dt, naming the turning point and a dt that meets it); turning points on
    steps, at a plateau holding a step, beyond the run, or missed by under 1 % pass."""
    amp = 8e-6
    fast = [(0.0, 0.0)] + [(1e-4 * (2 * k + 1), amp * (-1) ** k) for k in range(20)]
    with pytest.raises(ParameterError, match=r"^time.dt: 0.00025 s misses the turning point of "
                       r"tangential.displacement_history at t = 0.0001 s \(delta_x = 8e-06 m\) by 8e-06 m .*"
                       r"use time.dt = 0.0001 s"):
        guards.check_problem(_fretting_problem(fast, 2.5e-4, 4e-3))
    guards.check_problem(_fretting_problem(fast, 1e-4, 4e-3))
    late = [(0.0, 0.0), (2.6e-3, amp), (7.6e-3, -amp)]
    with pytest.raises(ParameterError, match=r"at t = 0.0026 s .* by 3.08e-07 m \(3.8 % .* turn at 7.692e-06 m; "
                       r"use time.dt = (?P<dt>[0-9.e-]+) s") as info:
        guards.check_problem(_fretting_problem(late, 2.5e-4, 1e-2))
    suggested = float(info.value.message.split("use time.dt = ")[1].split(" s")[0])
    assert suggested < 2.5e-4
    assert guards.turning_point_miss(_fretting_problem(late, suggested, 1e-2))[0] < 0.01 * amp
    # passes: a plateau holding a step, the turning point after the run's last step, a miss under 1 %
    guards.check_problem(_fretting_problem([(0.0, 0.0), (2.5e-3, amp), (2.6e-3, amp), (7.6e-3, -amp)], 2.5e-4, 1e-2))
    guards.check_problem(_fretting_problem(late, 2.5e-4, 2.5e-3))
    assert guards.turning_point_miss(_fretting_problem([(0.0, 0.0), (2.51e-3, amp), (7.5e-3, -amp)], 2.5e-4, 1e-2)) \
        == pytest.approx((amp * 0.01 / 2.51, 2.51e-3, amp, amp * 2.5 / 2.51))
    guards.check_problem(_fretting_problem([(0.0, 0.0), (2.51e-3, amp), (7.5e-3, -amp)], 2.5e-4, 1e-2))


def test_a_time_step_that_misses_the_peak_of_a_load_history_is_refused():
    """The steps sample ``normal.history`` as they sample the displacement history: a load that
    rises to 0.15 N at 2.6 ms and falls again was cut to 0.144 N at dt = 0.25 ms (-3.8 %) silently,
    for any material (the time-step guard, which runs the scheme on the sampled history, cannot see
    it). Refused above 1 % of the largest load, keyed time.dt, naming the history and a dt that
    meets the peak; a peak on a step, or held over a step, passes."""
    pulse = PiecewiseLinear((0.0, 2.6e-3, 5.2e-3), (0.0, 0.15, 0.0))
    problem = sphere_problem(Material.elastic(1.93e6, 0.3), 32, 1.5e-3, t_end=5e-3, dt=2.5e-4, scheme="linear")
    problem = replace(problem, normal=replace(problem.normal, history=pulse))
    with pytest.raises(ParameterError, match=r"^time.dt: 0.00025 s misses the turning point of normal.history at "
                       r"t = 0.0026 s \(W = 0.15 N\) by 0.00577 N \(3.8 % .* turn at 0.1442 N; use time.dt = "):
        guards.check_problem(problem)
    on_a_step = PiecewiseLinear((0.0, 2.5e-3, 5.0e-3), (0.0, 0.15, 0.0))
    guards.check_problem(replace(problem, normal=replace(problem.normal, history=on_a_step)))
    held = PiecewiseLinear((0.0, 2.4e-3, 2.6e-3, 5.0e-3), (0.0, 0.15, 0.15, 0.0))
    guards.check_problem(replace(problem, normal=replace(problem.normal, history=held)))


def test_a_gpu_run_on_a_small_grid_warns_that_the_cpu_is_likely_faster(monkeypatch):
    """solver.device = "gpu" below GPU_SMALL_GRID cells a side warns once, naming the key and the
    measurement; at GPU_SMALL_GRID it runs without the warning (CuPy's presence faked: the check is
    the guard's, not the device's)."""
    import importlib.util

    from viscontact.problem.problem import SolverSettings

    real_find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: object() if name == "cupy" else real_find_spec(name, *a))
    case = load_case(ROOT / "cases" / "seed_table1_v0.8.toml")
    problem = case.to_problem()
    small = replace(problem, solver=SolverSettings(device="gpu"))
    with pytest.warns(ViscontactWarning, match=r"solver.device = 'gpu' on 256 x 256 cells.*'cpu'"):
        guards.check_problem(small)
    large = case.with_overrides({"grid.n": guards.GPU_SMALL_GRID, "solver.device": "gpu"}).to_problem()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        guards.check_problem(large, transient=False)
    assert not [w for w in caught if "solver.device" in str(w.message)]
