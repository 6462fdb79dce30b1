"""Support-window solve (viscontact.numerics.support_window) against the full-domain solve.

* the window operator (cropped kernels on an m x m box) is the full DC-FFT operator restricted to the
  box, to round-off (1e-12 of the largest value): a wrong crop or wrap-around layout is off by O(1);
  for the one-term half-space and a two-term nu(t) compliance (``combine``);
* the windowed constrained CG equals the full-domain Polonsky-Keer solve to the solver tolerance
  (unique solution of a strictly convex programme), under load and displacement control, from a
  warm start whose support is far smaller than the contact: the first box is too small, the check
  finds the penetration outside it and the box is enlarged (asserted: more than one box side used);
* whole transients (creep indentation, frictionless sliding, partial slip: its tangential solve on
  the box of the contact, exact since q_x = 0 is pinned outside) give the same records with and
  without windows, to the solver tolerance, and do use windows.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from vc_testing import SEED_A0, seed_material, sphere_problem

from viscontact.numerics import support_window
from viscontact.solvers import transient
from viscontact.running import loop
from viscontact.numerics.arrays import CPU, cpu_fast_length, device_fast_length
from viscontact.numerics.constrained import constrained_cg
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.problem.problem import SolverSettings
from viscontact.bodies.half_space import HalfSpace


def _half_space(n: int = 32, material: Material | None = None) -> HalfSpace:
    return HalfSpace(Grid(n, 2e-3), material or seed_material(), ("zz",), "linear", 1e-3)


def _nu_t_substrate(n: int = 32):
    from viscontact.bodies.compliance import term_substrate
    from viscontact.bodies.bulk_elastic import BulkElasticMaterial, half_space_terms

    grid = Grid(n, 2e-3)
    return term_substrate(grid, half_space_terms(grid, BulkElasticMaterial(seed_material(), 5e6), ("zz",)),
                          "linear", 1e-3)


@pytest.mark.parametrize("make", [_half_space, _nu_t_substrate], ids=["half-space", "nu(t)"])
@pytest.mark.parametrize("m, r0, c0", [(12, 3, 17), (20, 0, 12), (31, 1, 0)])
def test_window_operator_is_the_full_operator_on_the_box(make, m, r0, c0):
    sub = make()
    op = sub.elastic_operator("z", False)
    field = np.zeros((32, 32))
    box = (slice(r0, r0 + m), slice(c0, c0 + m))
    field[box] = np.random.default_rng(m).random((m, m))
    full = op.apply(field)[box]
    windowed = op.window(m).apply(field[box])
    assert np.max(np.abs(windowed - full)) <= 1e-12 * np.max(np.abs(full))
    points = np.zeros((m, m))
    points[1, 2], points[m - 1, 0] = 1.0, -2.0
    sparse = op.window(m).apply_sparse(points)
    assert np.max(np.abs(sparse - op.window(m).apply(points))) <= 1e-12 * np.max(np.abs(sparse))


def test_window_convolvers_kept_are_bounded():
    """A contact that walks through many window sides keeps the convolvers of the last WINDOWS_KEPT
    only (their cropped kernels would otherwise pile up), the most recent first to stay."""
    from viscontact.bodies.compliance import WINDOWS_KEPT

    sub = _half_space(32)
    op = sub.elastic_operator("z", False)
    sides = (10, 12, 14, 16, 18, 20)
    for m in sides:
        op.window(m)
    assert list(sub._windows) == list(sides[-WINDOWS_KEPT:])
    op.window(sides[-WINDOWS_KEPT])  # reused, not rebuilt: now the most recent
    assert list(sub._windows)[-1] == sides[-WINDOWS_KEPT] and len(sub._windows) == WINDOWS_KEPT


def test_periodic_grids_have_no_window():
    sub = HalfSpace(Grid(16, 2e-3, periodic=True), seed_material(), ("zz",), "linear", 1e-3)
    assert sub.elastic_operator("z", False).window is None


@pytest.mark.parametrize("control", ["load", "displacement"])
def test_windowed_solve_equals_full_solve_and_enlarges(control, monkeypatch):
    n = 64
    sub = _half_space(n, Material.elastic(1.93e6, 0.3))
    x, y = sub.grid.mesh()
    gap = (x**2 + y**2) / (2 * 0.01)
    op = sub.elastic_operator("z", True)
    sizes = []
    window = op.window
    spy = type(op)(op.apply, op.preconditioner, op.apply_sparse, lambda m: sizes.append(m) or window(m))
    # a warm start on a disc of a fifth of the contact's radius: the first box is too small
    warm = np.where(x**2 + y**2 < (0.2 * SEED_A0) ** 2, 1e5, 0.0)
    kwargs = dict(tolerance=1e-11, max_iterations=500)
    if control == "load":
        kwargs.update(total=0.15, cell_area=sub.grid.cell_area)
        b = -gap
    else:
        b = 20e-6 - gap
    ours = support_window.windowed_cg(spy, b, warm, **kwargs)
    ref = constrained_cg(op.apply, b, np.zeros_like(b), 0.0, np.inf, **kwargs, **op.cg_options())
    assert len(set(sizes)) >= 2 and max(sizes) < n  # enlarged, still a window
    peak = np.max(ref.x)
    assert np.max(np.abs(ours.x - ref.x)) <= 1e-8 * peak
    assert np.max(np.abs(ours.gradient - ref.gradient)) <= 1e-8 * np.max(np.abs(b))
    assert ours.multiplier == pytest.approx(ref.multiplier, rel=1e-9, abs=1e-15)
    assert np.all(ours.gradient[ours.x == 0] >= -1e-9 * np.max(np.abs(b)))


def _records(problem, monkeypatch, windows: bool):
    if not windows:
        monkeypatch.setattr(support_window, "FULL_FRACTION", 0.0)
    used = []
    window_side = support_window.window_side

    def spy(extent, n, *fast_length):
        m = window_side(extent, n, *fast_length)
        used.append(m)
        return m

    monkeypatch.setattr(support_window, "window_side", spy)
    records = list(loop.simulate(problem))
    monkeypatch.undo()
    return records, [m for m in used if m is not None]


@pytest.mark.parametrize("case", ["creep", "sliding", "partial slip"])
def test_transient_with_windows_equals_full_domain(case, monkeypatch):
    material = seed_material()
    solver = SolverSettings(tolerance=1e-10)
    if case == "creep":
        problem = sphere_problem(material, 48, 2.5 * SEED_A0, t_end=0.02, dt=0.002, solver=solver,
                                 fields=("pressure", "displacement_z"))
    elif case == "sliding":
        v = 0.8 * SEED_A0 / 0.01
        problem = sphere_problem(material, 48, 3.0 * SEED_A0, mode="frictionless_sliding", speed=v,
                                 t_end=12 * 6 * SEED_A0 / 48 / v, solver=solver, fields=("pressure", "displacement_z"))
    elif case == "partial slip":
        v = 0.8 * SEED_A0 / 0.01
        problem = sphere_problem(material, 48, 2.5 * SEED_A0, mode="partial_slip", friction=0.3,
                                 rate=0.05 * SEED_A0 / 0.01, speed=v, t_end=8 * 5 * SEED_A0 / 48 / v, solver=solver,
                                 fields=("pressure", "shear_x", "displacement_z"))
    windowed, used = _records(problem, monkeypatch, True)
    full, none = _records(problem, monkeypatch, False)
    assert len(used) >= len(windowed) // 2 and not none
    for a, b in zip(windowed, full):
        peak = np.max(b.pressure)
        assert np.max(np.abs(a.pressure - b.pressure)) <= 1e-7 * peak
        assert np.max(np.abs(a.displacement_z - b.displacement_z)) <= 1e-7 * np.max(np.abs(b.displacement_z))
        assert a.delta_z == pytest.approx(b.delta_z, rel=1e-8)
        if a.shear_x is not None:
            assert np.max(np.abs(a.shear_x - b.shear_x)) <= 1e-7 * np.max(np.abs(b.shear_x))
    if case == "partial slip":
        assert 0 < windowed[-1].stick_ratio < 1  # still partial slip at the end: the tangential solves ran


def test_the_device_ladder_is_the_next_power_of_two_or_three_times_one():
    ladder = sorted({2**k for k in range(14)} | {3 * 2**k for k in range(13)})
    for length in range(1, 6000):
        assert device_fast_length(length) == next(rung for rung in ladder if rung >= length), length
    def five_smooth(length: int) -> bool:  # pocketfft's fast real lengths
        for factor in (2, 3, 5):
            while length % factor == 0:
                length //= factor
        return length == 1

    for extent in range(1, 400):  # a window side on the ladder holds the support and both margins
        least = extent + 2 * max(support_window.MARGIN_CELLS, math.ceil(support_window.MARGIN_FRACTION * extent))
        m = support_window.window_side(extent, 1024, device_fast_length)
        assert m == next(rung // 2 for rung in ladder if rung >= 2 * least)
        # the CPU's side (the default) is the smallest holding them with 2m 5-smooth, as before the ladder
        assert support_window.window_side(extent, 1024) == next(k for k in range(least, 2000) if five_smooth(2 * k))


def test_a_creeping_contact_on_the_device_ladder_keeps_its_window_longer(monkeypatch):
    """A GPU plans its transforms anew for every window side (a tenth of a second each on an H200):
    on the device ladder a creeping contact changes side less than half as often as on scipy's fast
    lengths, and the records are the same to the solver tolerance (the box holds the support)."""
    from viscontact.bodies.compliance import compliance_of

    problem = sphere_problem(seed_material(), 96, 2.5 * SEED_A0, t_end=0.03, dt=0.001,
                             solver=SolverSettings(tolerance=1e-10), fields=("pressure",))
    sides, runs = {}, {}
    window_side = support_window.window_side
    for name, lengths in (("cpu", cpu_fast_length), ("device", device_fast_length)):
        used = []
        monkeypatch.setattr(support_window, "window_side",
                            lambda extent, n, *f: used.append(window_side(extent, n, *f)) or used[-1])
        backend = dataclasses.replace(CPU, fast_length=lengths)
        runs[name] = [r for _, r in transient.steps(problem, compliance=compliance_of(problem, backend=backend))]
        sides[name] = [m for m in used if m is not None]
    changes = {name: sum(a != b for a, b in zip(used, used[1:])) for name, used in sides.items()}
    assert all(device_fast_length(2 * m) == 2 * m for m in sides["device"])
    assert changes["cpu"] >= 6 and changes["device"] <= changes["cpu"] // 2, changes
    for a, b in zip(runs["device"], runs["cpu"]):
        assert np.max(np.abs(a.pressure - b.pressure)) <= 1e-7 * np.max(b.pressure)
        assert a.delta_z == pytest.approx(b.delta_z, rel=1e-8)
