"""What every solved state passes before it is kept: finite pressures, a contact inside a
non-periodic domain, a balanced load (the transient's every step and each steady state)."""
from __future__ import annotations

import numpy as np

from viscontact.errors import NumericalGuardError
from viscontact.problem.problem import Problem

#: pressure, relative to its peak, above which a cell counts as loaded in :func:`check_solution`
LOADED_FRACTION = 1e-6
#: relative load imbalance sum p dA / W - 1 that :func:`check_solution` refuses
LOAD_BALANCE_TOLERANCE = 1e-6


def check_solution(problem: Problem, pressure: np.ndarray, load: float, value: float, *, where: str = "") -> None:
    """Refuse a solved pressure field that cannot be trusted (the transient's every step and each
    steady state): NaN or Inf, contact at the edge of a non-periodic domain (the body beyond the edge
    is missing, so the contact is cut off and the pressure inside it is wrong), or a load that does
    not balance.

    Parameters
    ----------
    problem
        What was solved (its grid and normal control).
    pressure
        The solved pressure [Pa], (n, n); negative (tension) only with ``problem.adhesion``, where
        the edge check reads |p|.
    load
        sum p dA [N].
    value
        The prescribed load [N] under load control, signed (ignored under displacement control).
    where
        Said after the finding, e.g. ``" at v = 0.1 m/s"``.

    Raises
    ------
    NumericalGuardError
        Saying what to change.
    """
    if not np.all(np.isfinite(pressure)):
        raise NumericalGuardError(f"pressure has NaN or Inf values{where}; check the inputs (material, load, grid)")
    grid = problem.grid
    adhesion = problem.adhesion
    # adhesion: tension loads a cell too; a law whose tension reaches every cell (the exponential; its tail, cut
    # off at the edge, is judged before the run: running/guards.py) has the compressed contact judged
    loaded = pressure if adhesion is None else np.maximum(pressure, 0.0) if adhesion.kind.reaches_every_cell \
        else np.abs(pressure)
    edge = grid.edge_values(loaded)
    peak = float(loaded.max())
    if peak > 0 and edge.max() > LOADED_FRACTION * peak and not grid.periodic:
        x, y = grid.mesh()
        reach = float(np.sqrt(x**2 + y**2)[loaded > LOADED_FRACTION * peak].max())
        advice = (f"enlarge grid.half_width to more than {1.5 * reach:.4g} m (now {grid.half_width:.4g} m; the edge "
                  "cuts the contact off, so it may need more)" if problem.shape is not None else
                  "a rough or measured surface touches all over, at any width: make the domain one period of it "
                  "(grid.periodic = true), or enlarge grid.half_width if its contact is compact")
        raise NumericalGuardError(
            f"the contact reaches the edge of the domain{where} (pressure {edge.max() / peak:.1e} of its peak there); "
            + advice)
    # a tensile load (adhesion) balances as a compressive one
    if problem.normal.control == "load" and value != 0 and abs(load - value) > LOAD_BALANCE_TOLERANCE * abs(value):
        raise NumericalGuardError(f"load balance violated{where}: sum p dA = {load:.6g} N for W = {value:.6g} N")
