"""What a solver reports for one time step (the raw material of ``viscontact.results``)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class StepRecord:
    """Scalars and fields of one recorded step. SI units; fields are (n, n) arrays indexed [y, x]
    on the grid of the moving frame, or ``None`` when not requested.

    Attributes
    ----------
    step, t
        Step index and time [s].
    phase
        0 indentation, 1 partial slip, 2 gross sliding.
    load
        Normal load W = sum p dA [N].
    delta_z, delta_x
        Normal and tangential rigid-body displacements of the indenter [m].
    sliding_distance
        Distance slid since gross sliding started [m].
    contact_area
        [m^2]; ``stick_ratio`` stick area / contact area [-].
    friction_force
        Dry friction sum q_x dA [N], positive when it resists the motion.
    hysteresis_force
        F_T = -sum p du_z/dx dA [N] (seed Eq. 15), positive when it resists the motion.
    mu_app
        F_T / W [-].
    contact_shift
        x-centroid of the pressure relative to the indenter centre [m] (positive in +x).
    frame_offset
        Position of the indenter centre on the grid [m]: 0 unless steps_per_cell = k > 1, when the
        indenter moves by dx/k per step between two shifts of the frame. Fields are stored on the
        grid, so the indenter-frame coordinate of a field value is x - frame_offset.
    wake_loss
        Estimated relative error [-] of mu_app (and, under displacement control, of the load) caused
        by the history dropped at the trailing edge of the moving frame (:mod:`viscontact.sliding`).
    iterations, coupling_iterations
        Constrained-CG iterations (all solves of the step) and normal/tangential alternations.
    """

    step: int
    t: float
    phase: int
    load: float
    delta_z: float
    delta_x: float
    sliding_distance: float
    contact_area: float
    stick_ratio: float
    friction_force: float
    hysteresis_force: float
    mu_app: float
    contact_shift: float
    frame_offset: float = 0.0
    wake_loss: float = 0.0
    iterations: int = 0
    coupling_iterations: int = 0
    pressure: np.ndarray | None = field(default=None, repr=False)
    shear_x: np.ndarray | None = field(default=None, repr=False)
    stick: np.ndarray | None = field(default=None, repr=False)
    displacement_z: np.ndarray | None = field(default=None, repr=False)

    SCALARS = ("load", "delta_z", "delta_x", "sliding_distance", "contact_area", "stick_ratio",
               "phase", "friction_force", "hysteresis_force", "mu_app", "contact_shift",
               "frame_offset", "wake_loss", "iterations", "coupling_iterations")
    FIELDS = ("pressure", "shear_x", "stick", "displacement_z")
