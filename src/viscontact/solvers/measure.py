"""One measurement of a solved contact state into a :class:`~viscontact.problem.records.StepRecord`.

The transient's every step (:func:`viscontact.solvers.transient.step`) and each steady state
(:func:`viscontact.solvers.steady.solve_steady`) are measured by :func:`measure`: the load W = sum p dA,
the contact area, the dry friction sum q_x dA, the hysteresis friction F_T (seed Eq. 15) and
mu_app = F_T / W, the stick ratio, the contact's shift and the rough-contact outputs; the solved
pressure is checked first (:func:`~viscontact.solvers.checks.check_solution`).
"""
from __future__ import annotations

from dataclasses import asdict

import numpy as np

from viscontact.problem.problem import Problem
from viscontact.problem.records import StepRecord
from viscontact.problem.roughness import roughness_metrics
from viscontact.solvers.adhesive_law import adhesive_cells
from viscontact.solvers.checks import check_solution
from viscontact.solvers.sliding import hysteresis_force, pressure_centroid


def measure(problem: Problem, pressure: np.ndarray, shear: np.ndarray, displacement_z: np.ndarray, *,
            delta_z: float, value: float, gap: np.ndarray, step: int, t: float, phase: int,
            stick: np.ndarray | None = None, slides: bool = True, delta_x: float = 0.0,
            sliding_distance: float = 0.0, frame_offset: float = 0.0, iterations: int = 0,
            coupling_iterations: int = 1, where: str = "", interaction: np.ndarray | None = None) -> StepRecord:
    """The record of a solved state (fields on the host), after checking its pressure.

    Parameters
    ----------
    problem
        What was solved (its grid, normal control and tangential mode).
    pressure, shear, displacement_z
        p [Pa], q_x [Pa] and the total u_z [m], (n, n) on the host, indexed [y, x].
    delta_z
        Approach [m].
    value
        The normal condition: the prescribed load [N] under load control (checked against sum p dA),
        else the approach [m].
    gap
        The undeformed gap [m] at the indenter's position on the grid (the deformed gap is
        gap + u_z - delta_z).
    step, t, phase
        Step index, time [s] and phase code (:mod:`viscontact.problem.problem`).
    stick
        The stuck points (boolean field); the stick ratio is their share of the contact (NaN
        without contact in partial slip, 0 in the other modes). None: no field of stick, ratio 0.
    slides
        Whether the indenter slides: else F_T = 0 (not measured).
    delta_x, sliding_distance
        Tangential displacement and distance slid [m].
    frame_offset
        Indenter centre on the grid [m]: the contact shift is the pressure centroid less it.
    iterations, coupling_iterations
        The solve's iteration counts.
    where
        Said after a refusal of the pressure, e.g. ``" at v = 0.1 m/s"``.
    interaction
        With adhesion: the solution's interaction zone (boolean, on the host). The contact area is
        then the area at gap 0 (:func:`~viscontact.solvers.adhesive_law.contact_cells`), the adhesive
        force the tensile part of the load, sum min(p, 0) dA [N], and the adhesive area that of the
        cohesive zone (gap open, tension sigma_0; with the exponential law, gap open and tension above
        1 % of its peak w / rho: :func:`~viscontact.solvers.adhesive_law.adhesive_cells`) [m^2].

    Returns
    -------
    StepRecord
        With ``wake_loss`` 0 (the transient's moving frame adds its own).

    Raises
    ------
    NumericalGuardError
        From :func:`~viscontact.solvers.checks.check_solution`.
    """
    grid = problem.grid
    load = float(pressure.sum() * grid.cell_area)
    check_solution(problem, pressure, load, value, where=where)
    f_t = hysteresis_force(pressure, displacement_z, grid, grid.periodic) if slides else 0.0
    adhesion = problem.adhesion
    if adhesion is None:
        n_contact, adhesive = int((pressure > 0).sum()), {}
    else:
        contact, cohesive_cells = adhesive_cells(adhesion, pressure, interaction)
        n_contact = int(contact.sum())
        cohesive = int(cohesive_cells.sum())
        adhesive = {"adhesive_force": float(np.minimum(pressure, 0.0).sum() * grid.cell_area),
                    "adhesive_area": cohesive * grid.cell_area}
    if stick is None:
        stick, stick_ratio = np.zeros(pressure.shape, dtype=bool), 0.0
    else:
        # no contact: nothing sticks or slips (undefined in partial slip; zero by definition in the other modes)
        stick_ratio = (float(stick.sum()) / n_contact if n_contact else
                       float("nan") if problem.tangential.mode == "partial_slip" else 0.0)
    return StepRecord(
        step=step, t=t, phase=phase, load=load, delta_z=delta_z, delta_x=delta_x, sliding_distance=sliding_distance,
        contact_area=n_contact * grid.cell_area, stick_ratio=stick_ratio,
        friction_force=float(shear.sum() * grid.cell_area), hysteresis_force=f_t,
        mu_app=f_t / load if load > 0 else 0.0, contact_shift=pressure_centroid(pressure, grid) - frame_offset,
        frame_offset=frame_offset, iterations=iterations, coupling_iterations=coupling_iterations,
        **asdict(roughness_metrics(pressure, gap + displacement_z - delta_z, grid.periodic)),
        pressure=pressure, shear_x=shear, stick=stick, displacement_z=displacement_z, **adhesive,
    )
