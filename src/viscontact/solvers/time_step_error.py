"""The time scheme's error on one point: how far ``time.dt`` misses the material's response.

The time scheme (:mod:`viscontact.numerics.schemes`, :mod:`viscontact.numerics.history`) is run on one
point of a contact whose area does not change: under displacement control the traction responds to the
approach history delta(t) through the relaxation modulus G(t); under load control the displacement
responds to the load history W(t) through the creep compliance J(t). Both are compared with the exact
hereditary integrals of the piecewise-linear history (seed Eq. 5 with dt -> 0,
:func:`viscontact.numerics.hereditary.hereditary_integral`). The limits on the estimate are the guards'
(:data:`viscontact.running.guards.TIME_ERROR_LIMIT`, :data:`~viscontact.running.guards.TIME_WARNING_LIMIT`).
"""
from __future__ import annotations

import numpy as np

from viscontact.numerics.hereditary import hereditary_integral
from viscontact.numerics.history import PronyHistory
from viscontact.numerics.schemes import step_coefficients
from viscontact.problem.problem import Problem

__all__ = ["MAX_CHECKED_STEPS", "REFERENCE_REFINEMENT", "RELATIVE_FLOOR", "scheme_response", "time_step_error"]

#: the time-step check runs the scheme over at most this many steps (the response has settled by then
#: or the estimate is taken over the first part of the run)
MAX_CHECKED_STEPS = 4000
#: sub-steps per time step of the reference hereditary integrals
REFERENCE_REFINEMENT = 16
#: the time-step error of a step is relative to the exact value at that step, but not to less than this
#: fraction of the largest exact value (a value that passes through zero, e.g. an approach released)
RELATIVE_FLOOR = 0.05


def scheme_response(problem: Problem, driving: np.ndarray) -> np.ndarray:
    """The time scheme of :mod:`viscontact.solvers.transient` on one point: the traction under the
    displacements ``driving`` (displacement control) or the displacement under the tractions
    ``driving`` (load control), at the steps t_k = k dt."""
    spectrum, dt, scheme = problem.material.creep, problem.time.dt, problem.time.scheme
    first, regular = (step_coefficients(spectrum, dt, scheme, f) for f in (True, False))
    hist = PronyHistory.zeros(spectrum.retardation_times.size, 1)
    out = np.empty(driving.size)
    for k, value in enumerate(driving):
        coef = first if k == 0 else regular
        r = float(hist.known(coef, k * dt)[0, 0])
        if problem.normal.control == "displacement":
            p = out[k] = (value - r) / coef.instantaneous
        else:
            p, out[k] = value, coef.instantaneous * value + r
        hist = hist.advanced(np.full((1, 1), p), coef, k * dt)
    return out


def time_step_error(problem: Problem) -> float:
    """Estimated relative error [-] of the transient from the time discretisation alone.

    The scheme runs on one point of the Lee & Radok (1960) solution for a sphere, whose exact values
    are hereditary integrals of the normal history computed on a grid :data:`REFERENCE_REFINEMENT`
    times finer (:func:`hereditary_integral`):

    * displacement control: the contact radius is held by the approach, the traction at a point
      follows int G(t - s) d delta(s); the scheme is driven by delta(t_k) and returns the traction;
    * load control: a(t)^3 ~ int J(t - s) dW(s) grows, the centre pressure is ~ int G(t - s) da(s)
      and the centre displacement ~ a(t); the scheme is driven by the centre pressure and returns
      the displacement.

    Returns the largest difference over the run (at most :data:`MAX_CHECKED_STEPS` steps) relative to
    the largest exact value under load control; under displacement control relative to the exact
    value at its step, or to :data:`RELATIVE_FLOOR` of the largest where that is larger (the traction
    relaxes by G(0)/G(inf): relative to the largest value, the first, errors of 20 % and more late in
    the run passed unseen); 0 for an elastic material.
    """
    mat = problem.material
    if mat.is_elastic:
        return 0.0
    n_steps = min(problem.time.n_steps, MAX_CHECKED_STEPS)
    h = problem.time.dt / REFERENCE_REFINEMENT
    fine = np.arange((n_steps - 1) * REFERENCE_REFINEMENT + 1) * h
    history = problem.normal.history.sample(fine) if len(problem.normal.history.times) > 1 \
        else np.full(fine.size, problem.normal.history.reference)
    relaxation = (mat.g_inf, np.array(mat.g), np.array(mat.tau))
    creep = mat.creep
    if problem.normal.control == "displacement":
        driving = history
        exact = hereditary_integral(*relaxation, history, h)
    else:
        compliance = hereditary_integral(creep.long_term, -creep.amplitudes, creep.retardation_times, history, h)
        exact = np.cbrt(np.maximum(compliance, 0.0))
        driving = hereditary_integral(*relaxation, exact, h)
    driving, exact = driving[::REFERENCE_REFINEMENT], exact[::REFERENCE_REFINEMENT]
    scale = float(np.max(np.abs(exact)))
    if not scale > 0:
        return 0.0
    # under a held approach the traction relaxes by G(0)/G(inf): each step against its own value; under
    # load control the contact only grows, and the largest value is the scale the limits were set on
    reference = (np.maximum(np.abs(exact), RELATIVE_FLOOR * scale) if problem.normal.control == "displacement"
                 else scale)
    return float(np.max(np.abs(scheme_response(problem, driving) - exact) / reference))
