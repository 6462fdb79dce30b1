"""Moving frame and sliding outputs: hysteresis friction (seed Eq. 15) and the dropped wake.

Once sliding, the grid follows the indenter (seed Sec. 2.2): with v dt = dx / k, the stored
material history moves one cell towards -x every k steps, and the indenter sits at
``frame_offset = j dx / k`` (j = 0..k-1) within the grid between two shifts. Material leaving at
the trailing edge takes its unrecovered history with it; :class:`Wake` keeps track of that history
and estimates how much it would still change the apparent friction.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from viscontact.errors import ParameterError
from viscontact.numerics.exponentials import CreepSpectrum
from viscontact.numerics.grid import Grid


def hysteresis_force(pressure: np.ndarray, displacement_z: np.ndarray, grid: Grid, periodic: bool = False) -> float:
    """F_T = -sum p du_z/dx dA [N] (seed Eq. 15 with the sign that makes it positive when it resists
    sliding in +x); central finite differences (wrapping around on a ``periodic`` domain, one-sided
    at the edges otherwise), rectangle rule."""
    if periodic:
        slope = (np.roll(displacement_z, -1, axis=1) - np.roll(displacement_z, 1, axis=1)) / (2 * grid.spacing)
    else:
        slope = np.gradient(displacement_z, grid.spacing, axis=1)
    return float(-np.sum(pressure * slope) * grid.cell_area)


def pressure_centroid(pressure: np.ndarray, grid: Grid) -> float:
    """x-centroid of the pressure [m] (the contact shift, positive in +x); 0 without contact."""
    total = pressure.sum()
    if total <= 0:
        return 0.0
    return float(np.sum(pressure.sum(axis=0) * grid.x) / total)


@dataclass(frozen=True)
class Wake:
    """History that left the grid at the trailing edge, kept to estimate its effect.

    Each strip is the internal history (M, n) of one dropped column, its distance behind the
    trailing cell centre (in cells) and its age (steps). The material behind the contact recovers
    as sum_m J_m A_m^age H_m; its x-gradient over the contact, weighted by the load, is the error in
    F_T (seed Eq. 15) that truncating the domain makes.
    """

    strips: list[np.ndarray] = field(default_factory=list)
    distance: list[int] = field(default_factory=list)
    age: list[int] = field(default_factory=list)

    def dropped(self, dropped_internal: np.ndarray) -> "Wake":
        """After a shift: every strip moves one cell further; the new one enters at distance 1."""
        return Wake(self.strips + [dropped_internal[..., 0].copy()], [d + 1 for d in self.distance] + [1],
                    self.age + [0])

    def ticked(self, response: CreepSpectrum, dt: float) -> "Wake":
        """After one time step [s]; strips whose history has decayed below 1e-9 are forgotten."""
        lam_max = float(response.retardation_times.max(initial=0.0))
        keep = [i for i, a in enumerate(self.age) if lam_max > 0 and (a + 1) * dt / lam_max < 20.7]
        return Wake([self.strips[i] for i in keep], [self.distance[i] for i in keep], [self.age[i] + 1 for i in keep])

    def lost_displacement(self, response: CreepSpectrum, poisson_ratio: float, grid: Grid, dt: float,
                          pressure: np.ndarray) -> tuple[float, float]:
        """(u_lost [m], du_lost/dx [-]) at the pressure centroid: the surface displacement that the
        history dropped at the trailing edge would still produce there.

        Each strip is a line of point sources (Boussinesq, u_z = (1 - nu) / (2 pi G r) F) carrying its
        remaining history traction -sum_m J_m A_m^age H_m; u_lost is smooth over the contact since its
        sources lie outside the grid. Under load control a uniform u_lost only shifts delta_z; its
        slope changes F_T (seed Eq. 15) by about -W du_lost/dx. ``response`` is the time response of
        the normal history, ``poisson_ratio`` that of the Boussinesq kernel.
        """
        if not self.strips or pressure.sum() <= 0:
            return 0.0, 0.0
        c = response
        nu = poisson_ratio
        xc = pressure_centroid(pressure, grid)
        yc = float(np.sum(pressure.sum(axis=1) * grid.y) / pressure.sum())
        dists = np.asarray(self.distance, dtype=float)
        ages = np.asarray(self.age, dtype=float)
        decay = np.exp(-np.outer(ages * dt, 1.0 / c.retardation_times))          # (S, M)
        traction = -np.einsum("sm,smy->sy", decay * c.amplitudes, np.asarray(self.strips))  # (S, n)
        dx = (xc - (grid.x[0] - dists * grid.spacing))[:, None]                  # (S, 1)
        dy = (yc - grid.y)[None, :]
        r = np.sqrt(dx * dx + dy * dy)
        area = grid.cell_area
        u = float(np.sum(traction * (1 - nu) / (2 * np.pi * r))) * area
        slope = float(np.sum(traction * (-(1 - nu) * dx / (2 * np.pi * r**3)))) * area
        return u, slope


def check_speed(speed: float) -> None:
    """A steady state needs a sliding ``speed`` > 0 m/s (:class:`ParameterError` otherwise)."""
    if not speed > 0:
        raise ParameterError("tangential.sliding_speed", f"must be > 0 m/s for a steady state, got {speed}")
