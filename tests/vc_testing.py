"""Small programmatic problems shared by the validation tests (no case files involved)."""
from __future__ import annotations

from viscontact.grid import Grid
from viscontact.materials import Material
from viscontact.problem import (NormalLoading, OutputSettings, PiecewiseLinear, Problem, SolverSettings,
                                TangentialLoading, TimeStepping)

#: the seed's material (SPEC section 1): G(0) = 1.93 MPa, G(inf) = G(0)/10, retardation time 0.01 s
SEED_G0, SEED_TAU, SEED_NU, SEED_RADIUS = 1.93e6, 0.01, 0.3, 0.01
SEED_A0 = 588.7e-6  # Hertz radius at 0.15 N with G(0) [m]


def seed_material(ratio: float = 10.0, poisson_ratio: float = SEED_NU) -> Material:
    return Material.zener(SEED_G0, SEED_G0 / ratio, SEED_TAU, poisson_ratio)


def sphere_problem(material: Material, n: int, half_width: float, *, control: str = "load", value: float = 0.15,
                   mode: str = "none", friction: float = 0.0, rate: float = 0.0, speed: float = 0.0,
                   t_end: float = 0.0, dt: float | None = None, scheme: str = "constant",
                   every: int = 1, solver: SolverSettings | None = None) -> Problem:
    """A rigid sphere (R = 10 mm) on ``material``; with sliding, dt defaults to one cell per step."""
    grid = Grid(n, half_width)
    x, y = grid.mesh()
    if dt is None:
        dt = grid.spacing / speed if speed > 0 else SEED_TAU / 20
    return Problem(material=material, grid=grid, gap=(x**2 + y**2) / (2 * SEED_RADIUS),
                   normal=NormalLoading(control, PiecewiseLinear.constant(value)),
                   tangential=TangentialLoading(mode, friction, rate, speed),
                   time=TimeStepping(t_end, dt, scheme), solver=solver or SolverSettings(),
                   output=OutputSettings(every=every), radius=SEED_RADIUS)


def observed_order(hs, errors) -> float:
    """Least-squares slope of log(error) against log(h)."""
    import numpy as np

    return float(np.polyfit(np.log(hs), np.log(errors), 1)[0])
