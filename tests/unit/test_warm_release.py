"""The constrained CG's first iteration releases the bound points of the warm start whose gradient
points inwards (:mod:`viscontact.numerics.constrained`): from the solution of a smaller load or
approach (a contact that grows over the step: the warm start misses its new ring of points), the
solve ends on the solution of a solve 1e4 times tighter from nothing, under load and displacement
control, and the solution's new points are loaded."""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.bodies.half_space import HalfSpace
from viscontact.numerics.constrained import constrained_cg
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material


@pytest.mark.parametrize("control", ["load", "displacement"])
def test_solve_from_a_smaller_contact_reaches_the_solution(control):
    sub = HalfSpace(Grid(64, 2e-3), Material.elastic(1.93e6, 0.3), ("zz",), "linear", 1e-3)
    x, y = sub.grid.mesh()
    gap = (x**2 + y**2) / (2 * 0.01)
    op = sub.elastic_operator("z", True)

    def solve(value: float, start: np.ndarray, tolerance: float):
        kwargs = dict(tolerance=tolerance, max_iterations=500, **op.cg_options())
        if control == "load":
            return constrained_cg(op.apply, -gap, start, 0.0, np.inf, total=value, cell_area=sub.grid.cell_area,
                                  **kwargs)
        return constrained_cg(op.apply, value - gap, start, 0.0, np.inf, **kwargs)

    small, large = (0.14, 0.15) if control == "load" else (19e-6, 20e-6)
    previous = solve(small, np.zeros_like(gap), 1e-12)
    reference = solve(large, np.zeros_like(gap), 1e-12)
    ours = solve(large, previous.x, 1e-8)
    grown = (reference.x > 0) & (previous.x == 0)
    assert grown.sum() >= 8  # the warm start misses a ring of the contact
    assert np.all(ours.x[grown] > 0)
    assert np.max(np.abs(ours.x - reference.x)) <= 1e-7 * np.max(reference.x)
