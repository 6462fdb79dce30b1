"""The compliance of a :class:`~viscontact.problem.problem.Problem`: its body's
(:attr:`~viscontact.problem.problem.Problem.body`, a :class:`~viscontact.bodies.base.Body`) with the
kernels the run needs and the problem's solver settings."""
from __future__ import annotations

from typing import Sequence

from viscontact.bodies.compliance import TermSubstrate
from viscontact.numerics.arrays import ArrayBackend, array_backend


def substrate_for(problem, components: Sequence[str] | None = None,
                  backend: ArrayBackend | None = None) -> TermSubstrate:
    """The compliance of ``problem``'s body (:meth:`~viscontact.bodies.base.Body.compliance`).

    ``components``: the kernels to build; by default what the transient needs: ``zz``, ``xx`` for
    partial slip, and the coupling ``xz``, ``zx`` when sliding with friction, nu < 0.5 and
    ``solver.coupling``. The steady solver asks for ``("zz",)`` (it builds its own kernels).

    ``backend``: where the fields live (:mod:`viscontact.numerics.arrays`); None: that of ``solver.device``.
    """
    backend = backend or array_backend(problem.solver.device)
    if components is None:
        nu = problem.material.poisson_ratio
        mode = problem.tangential.mode
        components = ["zz"] + (["xx"] if mode == "partial_slip" else [])
        if nu < 0.5 and problem.solver.coupling and mode in ("partial_slip", "gross_sliding"):
            components += ["xz", "zx"]
    solver = problem.solver
    return problem.body.compliance(problem.grid, components, problem.time.scheme, problem.time.dt,
                                   workers=solver.workers, direct=solver.history == "direct", fft=solver.fft,
                                   backend=backend)
