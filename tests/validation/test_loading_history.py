"""Piecewise-linear normal histories, including unloading (contact shrinking to nothing).

Elastic material: every step is a Hertz contact of the current load, so the contact radius must
follow (3 W(t) R / 4 E*)^(1/3) on the way up and on the way down (tolerance: two cells of the
radius, the area being a cell count), the load balance holds at every step, and at zero load the
pressure vanishes. Viscoelastic material: unloading at the same rate leaves a larger contact than
loading did at the same load (the material has crept while loaded).
"""
import numpy as np
import pytest

from viscontact.physics.materials import Material
from viscontact.problem.problem import PiecewiseLinear
from viscontact.physics.reference import hertz_from_load
from viscontact.running.loop import simulate

from vc_testing import SEED_G0, SEED_NU, SEED_RADIUS, seed_material, sphere_problem

HISTORY = PiecewiseLinear((0.0, 0.01, 0.02), (0.0, 0.15, 0.0))  # N: up in 10 ms, down in 10 ms


def _run(material, n=64, dt=5e-4, scheme="linear"):
    pb = sphere_problem(material, n, 1.6e-3, value=HISTORY, t_end=0.02, dt=dt, scheme=scheme)
    return pb.grid, list(simulate(pb))


def test_elastic_load_unload_follows_hertz():
    g = SEED_G0
    grid, recs = _run(Material.elastic(g, SEED_NU))
    for r in recs:
        w = HISTORY(r.t)
        assert r.load == pytest.approx(w, rel=1e-8, abs=1e-12)
        if w == 0:
            assert not np.any(r.pressure)
            continue
        a = np.sqrt(r.contact_area / np.pi)
        assert a == pytest.approx(hertz_from_load(w, SEED_RADIUS, g, SEED_NU).radius, abs=2 * grid.spacing)
    up = [r for r in recs if 0 < r.t < 0.01]
    down = [r for r in recs if 0.01 < r.t < 0.02]
    assert np.all(np.diff([r.contact_area for r in up]) >= 0)
    assert np.all(np.diff([r.contact_area for r in down]) <= 0)


def test_viscoelastic_unloading_contact_is_larger_than_loading_at_same_load():
    grid, recs = _run(seed_material())
    by_t = {round(r.t, 6): r for r in recs}
    for t_up in (0.0025, 0.005, 0.0075):
        up, down = by_t[round(t_up, 6)], by_t[round(0.02 - t_up, 6)]
        assert HISTORY(up.t) == pytest.approx(HISTORY(down.t))
        assert down.contact_area > up.contact_area  # crept while loaded
        assert down.load == pytest.approx(up.load, rel=1e-8)
    assert recs[-1].load == 0 and not np.any(recs[-1].pressure)
