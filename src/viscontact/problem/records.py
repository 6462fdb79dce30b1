"""What a solver reports for one time step (the raw material of ``viscontact.io.results``)."""
from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Sequence

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
        0 indentation, 1 partial slip, 2 gross sliding. A partial-slip run is in phase 1 until the
        stick zone of a contact vanishes (also before its first contact), then in 2 for good.
    load
        Normal load W = sum p dA [N].
    delta_z, delta_x
        Normal and tangential rigid-body displacements of the indenter [m].
    sliding_distance
        Distance slid since gross sliding started [m].
    contact_area
        [m^2]; ``stick_ratio`` stick area / contact area [-] (partial slip: NaN without contact;
        0 in the other modes).
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
        by the history dropped at the trailing edge of the moving frame (:mod:`viscontact.solvers.sliding`).
    iterations, coupling_iterations
        Constrained-CG iterations (all solves of the step) and normal/tangential alternations.
    contact_fraction, contact_patches, mean_gap, mean_contact_pressure
        Rough-contact outputs (:mod:`viscontact.problem.roughness`): real contact area / domain area [-],
        number of contact patches (periodic-aware), mean deformed gap over the domain [m], load /
        real contact area [Pa].
    adhesive_force, adhesive_area
        With adhesion only (:data:`ADHESIVE_SCALARS`): the tensile part of the load, sum min(p, 0) dA
        [N] (<= 0), and the area where the gap is open and tension acts [m^2] (the cohesive zone).
    creepage
        Rolling only (:data:`ROLLING_SCALARS`): the creepage (V_c - V) / V [-] of the step, held or
        found under a held tangential force (NaN at t = 0 there: nothing has rolled yet).
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
    contact_fraction: float = 0.0
    contact_patches: int = 0
    mean_gap: float = 0.0
    mean_contact_pressure: float = 0.0
    adhesive_force: float = 0.0
    adhesive_area: float = 0.0
    creepage: float = 0.0
    pressure: np.ndarray | None = field(default=None, repr=False)
    shear_x: np.ndarray | None = field(default=None, repr=False)
    stick: np.ndarray | None = field(default=None, repr=False)
    displacement_z: np.ndarray | None = field(default=None, repr=False)

    SCALARS = ("load", "delta_z", "delta_x", "sliding_distance", "contact_area", "stick_ratio",
               "phase", "friction_force", "hysteresis_force", "mu_app", "contact_shift",
               "frame_offset", "wake_loss", "iterations", "coupling_iterations", "contact_fraction",
               "contact_patches", "mean_gap", "mean_contact_pressure")
    FIELDS = ("pressure", "shear_x", "stick", "displacement_z")
    #: the scalars a result holds only with adhesion (after :attr:`SCALARS`)
    ADHESIVE_SCALARS = ("adhesive_force", "adhesive_area")
    #: the scalars a result holds only in rolling (after the others)
    ROLLING_SCALARS = ("creepage",)

    @classmethod
    def scalars(cls, adhesive: bool, rolling: bool = False) -> tuple[str, ...]:
        """The scalar histories of a result: :attr:`SCALARS`, with ``adhesive`` :attr:`ADHESIVE_SCALARS`
        and with ``rolling`` :attr:`ROLLING_SCALARS`."""
        return cls.SCALARS + (cls.ADHESIVE_SCALARS if adhesive else ()) + (cls.ROLLING_SCALARS if rolling else ())


def records_to_arrays(records: Sequence[StepRecord]) -> dict[str, np.ndarray]:
    """Stack records into arrays (one per scalar, (k, n, n) per recorded field): exact, for checkpoints."""
    out: dict[str, np.ndarray] = {"count": np.array(len(records))}
    for f in fields(StepRecord):
        values = [getattr(r, f.name) for r in records]
        if f.name in StepRecord.FIELDS:
            if values and all(v is not None for v in values):
                out[f.name] = np.stack(values)
        else:
            out[f.name] = np.array(values)
    return out


def records_from_arrays(arrays: dict[str, np.ndarray]) -> list[StepRecord]:
    """Inverse of :func:`records_to_arrays`."""
    count = int(arrays.get("count", 0))
    out = []
    for i in range(count):
        kwargs = {}
        for f in fields(StepRecord):
            if f.name in StepRecord.FIELDS:
                kwargs[f.name] = arrays[f.name][i].copy() if f.name in arrays else None
            elif f.name in arrays:
                kwargs[f.name] = arrays[f.name][i].item()
            # else: a field added after the arrays were written keeps its default
        out.append(StepRecord(**kwargs))
    return out
