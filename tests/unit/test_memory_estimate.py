"""The peak-memory model of ``viscontact run --dry-run`` (resources.estimate): its named terms."""
from __future__ import annotations

import math

import pytest

from viscontact.io.case import load_case
from viscontact.running.resources import (PADDED_TEMPORARIES, TOPOGRAPHY_IMPORT_MEMORY, estimate, kernel_bytes,
                                  window_cells)
from viscontact.io.shipped import shipped_case
from viscontact.numerics.support_window import FULL_FRACTION, window_side


def _case(name: str, **overrides):
    return load_case(shipped_case(name)).with_overrides({"grid.n": 64, **overrides})


def test_the_windows_are_sized_by_the_contact_the_run_foresees():
    """The support windows' kernels are those of the box of the widest foreseen contact (Hertz with
    the crept compliance, guards.contact_estimate): smaller than the grid for the shipped creep case,
    larger for a longer hold (more creep), and FULL_FRACTION of the grid where no contact is foreseen
    (a rough period: none is made there, being periodic, but the bound stays)."""
    from viscontact.running.guards import contact_estimate

    short = _case("creep_indentation", **{"time.t_end": 0.0025}).problem_outline()
    long = _case("creep_indentation").problem_outline()
    assert 0 < window_cells(short) < window_cells(long) <= FULL_FRACTION * 64
    widest = 2 * contact_estimate(long).largest / long.grid.spacing
    assert window_cells(long) == window_side(int(-(-widest // 1)), 64)
    assert estimate(short).peak_memory_bytes < estimate(long).peak_memory_bytes
    rough = _case("rough_periodic_sliding").problem_outline()
    assert window_cells(rough) == int(FULL_FRACTION * 64)


def test_a_surface_made_by_surface_topography_adds_its_import():
    """SurfaceTopography's import (self-affine and measured surfaces) is a term of its own; the
    shipped rough case needs it, a sphere does not. The problem of a case carries it
    (``Problem.surface_topography``), so that ``estimate(problem)`` counts it by default, as
    ``viscontact run`` does: it was left out without ``topography=True`` (95 MB short)."""
    from viscontact.running.api import prepare

    rough, sphere = _case("rough_periodic_sliding"), _case("creep_indentation")
    assert rough.indenter.uses_surface_topography
    assert not sphere.indenter.uses_surface_topography
    outline = rough.problem_outline()
    assert outline.surface_topography and not sphere.problem_outline().surface_topography
    assert prepare(rough)[0].surface_topography and not prepare(sphere)[0].surface_topography
    assert estimate(outline).peak_memory_bytes \
        - estimate(outline, topography=False).peak_memory_bytes == int(TOPOGRAPHY_IMPORT_MEMORY)
    assert estimate(outline).peak_memory_bytes == estimate(outline, topography=True).peak_memory_bytes
    assert estimate(prepare(rough)[0], transform=1e-3).peak_memory_bytes \
        == estimate(outline, transform=1e-3).peak_memory_bytes
    sphere_outline = sphere.problem_outline()
    assert estimate(sphere_outline, topography=True).peak_memory_bytes \
        - estimate(sphere_outline).peak_memory_bytes == int(TOPOGRAPHY_IMPORT_MEMORY)


def test_the_subsurface_stresses_add_the_transforms_of_the_tractions_the_mode_makes():
    """The subsurface stresses (on top of the run's peak) cost working_bytes of the pressure alone
    where the mode makes no shear traction (q_x = 0: not transformed), of p and q_x in gross sliding."""
    import dataclasses

    from viscontact.physics.subsurface import working_bytes

    for mode, tractions in (("none", 1), ("frictionless_sliding", 1), ("gross_sliding", 2)):
        moving = {"tangential.sliding_speed": 0.01} if mode != "none" else {}
        problem = _case("creep_subsurface_stress", **{"tangential.mode": mode, **moving}).problem_outline()
        depths = problem.output.subsurface_depths
        bare = dataclasses.replace(problem, output=dataclasses.replace(problem.output, subsurface_depths=()))
        added = estimate(problem).peak_memory_bytes - estimate(bare).peak_memory_bytes
        assert added == working_bytes(problem.grid, max(depths), tractions)
    assert working_bytes(problem.grid, max(depths), 1) < 0.85 * working_bytes(problem.grid, max(depths), 2)


def test_the_arrays_scale_with_the_cells_above_a_constant_base():
    """Every array term of a periodic case (no windows: no contact to size them) is a number of n x n
    or padded (2n)^2 fields: the estimate's growth from 256^2 to 512^2 is 4x its growth from 128^2 to
    256^2, and the step's padded temporaries are part of it."""
    peak = {n: estimate(_case("rough_periodic_sliding", **{"grid.n": n}).problem_outline()).peak_memory_bytes
            for n in (128, 256, 512)}
    grown = (peak[512] - peak[256]) / (peak[256] - peak[128])
    assert 3.98 < grown < 4.02
    assert PADDED_TEMPORARIES * 4 * (512**2 - 256**2) * 8 < peak[512] - peak[256]
    assert 3.99 < kernel_bytes(512) / kernel_bytes(256) < 4.01


def test_the_run_time_scales_with_the_transform_time_of_the_machine():
    """The run time is a start and a fixed part a step plus transform pairs timed on the machine that
    estimates: injecting a transform time twice as long doubles the transform-bound part; for the same
    grid and steps partial slip > gross sliding > frictionless sliding > indentation, and a
    smaller support window costs less."""
    from viscontact.running import resources

    problem = _case("seed_table1_v0.8").problem_outline()
    steps, mode = problem.time.n_steps, problem.tangential.mode
    fixed = resources.START_SECONDS + steps * resources.STEP_SECONDS[mode]
    one, two = (estimate(problem, transform=t).seconds - fixed for t in (1e-3, 2e-3))
    assert abs(two / one - 2.0) < 1e-9
    timed = resources.transform_seconds(problem)
    assert 0.0 < timed < 1.0 and resources.transform_seconds(problem) == timed  # cached per size
    assert estimate(problem).seconds == estimate(problem, transform=timed).seconds
    by_mode = {m: resources.run_seconds(steps, m, 1e-3) for m in resources.FULL_TRANSFORMS}
    assert by_mode["partial_slip"] > by_mode["gross_sliding"] > by_mode["frictionless_sliding"] > by_mode["none"]
    assert resources.run_seconds(steps, "none", 1e-3, periodic=True) > by_mode["none"]
    assert resources.run_seconds(steps, "none", 1e-3, share=0.25) < by_mode["none"]  # a smaller support window


def test_a_huge_grid_is_timed_at_a_bounded_side():
    """A dry run of a grid above TIMED_SIDE_LIMIT times the transforms there and scales them by
    n^2 log2(2n): no huge field is made."""
    from viscontact.running import resources

    big = _case("creep_indentation", **{"grid.n": 4 * resources.TIMED_SIDE_LIMIT}).problem_outline()
    limit = resources.TIMED_SIDE_LIMIT
    at_limit = resources._timed_pair(limit, False, big.solver.workers)
    n = 4 * limit
    assert resources.transform_seconds(big) == pytest.approx(
        at_limit * n * n * math.log2(2 * n) / (limit * limit * math.log2(2 * limit)))
