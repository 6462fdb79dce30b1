"""What the tests share: the seed's constants, its material and the sphere problem built from them
(no case files involved), and the seed's material as case-file text."""
from __future__ import annotations

from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.problem.problem import (
    NormalLoading,
    OutputSettings,
    PiecewiseLinear,
    Problem,
    SolverSettings,
    TangentialLoading,
    TimeStepping,
)

#: the seed's material and contact: G(0) = 1.93 MPa (the seed's mu = 2G),
#: G(inf) = G(0)/10, retardation time 0.01 s, nu = 0.3, R = 10 mm, W = 0.15 N
SEED_G0, SEED_TAU, SEED_NU, SEED_RADIUS, SEED_LOAD = 1.93e6, 0.01, 0.3, 0.01, 0.15
SEED_GINF = SEED_G0 / 10
SEED_A0 = 588.7e-6  # Hertz radius at 0.15 N with G(0) [m]
SEED_P0 = 0.2067e6  # Hertz peak pressure at 0.15 N with G(0) [Pa]

#: the seed's material as a case-file section
SEED_MATERIAL_TOML = f"""\
[material]
type = "zener"
shear_modulus_instantaneous = {SEED_G0!r}
shear_modulus_long_term = {SEED_GINF!r}
retardation_time = {SEED_TAU!r}
poisson_ratio = {SEED_NU!r}
"""


def seed_material(ratio: float = 10.0, poisson_ratio: float = SEED_NU) -> Material:
    """The seed's Zener material with G(0)/G(inf) = ``ratio``."""
    return Material.zener(SEED_G0, SEED_G0 / ratio, SEED_TAU, poisson_ratio)


def sphere_problem(material: Material, n: int, half_width: float, *, control: str = "load",
                   value: float | PiecewiseLinear = SEED_LOAD, mode: str = "none", friction: float = 0.0,
                   rate: float = 0.0, speed: float = 0.0, t_end: float = 0.0, dt: float | None = None,
                   scheme: str = "constant", every: int = 1, solver: SolverSettings | None = None,
                   fields: tuple[str, ...] = OutputSettings.fields, title: str = "",
                   displacement_history: PiecewiseLinear | None = None) -> Problem:
    """A rigid sphere (R = 10 mm) on ``material`` on an n x n grid of [-half_width, half_width]^2 [m].

    ``value`` is the held load [N] or approach [m] (``control``), or a piecewise-linear history of
    it. With sliding, dt defaults to one cell per step, else to tau/20. ``displacement_history``:
    partial slip's delta_x(t) [m] (with the incremental slip; no speed needed).
    """
    grid = Grid(n, half_width)
    x, y = grid.mesh()
    if dt is None:
        dt = grid.spacing / speed if speed > 0 else SEED_TAU / 20
    history = value if isinstance(value, PiecewiseLinear) else PiecewiseLinear.constant(value)
    return Problem(material=material, grid=grid, gap=(x**2 + y**2) / (2 * SEED_RADIUS),
                   normal=NormalLoading(control, history),
                   tangential=TangentialLoading(mode, friction, rate, speed, slip="incremental" if displacement_history
                                                else "total", displacement_history=displacement_history),
                   time=TimeStepping(t_end, dt, scheme), solver=solver or SolverSettings(),
                   output=OutputSettings(every, fields), radius=SEED_RADIUS, title=title)


def observed_order(hs, errors) -> float:
    """Least-squares slope of log(error) against log(h)."""
    import numpy as np

    return float(np.polyfit(np.log(hs), np.log(errors), 1)[0])


def periodic_elastic_contact(grid: Grid, gap, shear_modulus: float, poisson_ratio: float, load: float):
    """Elastic frictionless contact on a periodic domain under ``load`` [N] on one period:
    PeriodicConvolver + Polonsky-Keer. Returns (pressure [Pa], approach [m], u_z [m], iterations)."""
    import numpy as np

    from viscontact.numerics.constrained import constrained_cg
    from viscontact.physics.periodic import PeriodicConvolver

    conv = PeriodicConvolver.for_grid(grid, poisson_ratio, components=("zz",))
    sol = constrained_cg(lambda p: conv.apply("zz", p) / shear_modulus, -gap, np.zeros_like(gap), 0.0, np.inf,
                         total=load, cell_area=grid.cell_area, tolerance=1e-12,
                         preconditioner=conv.preconditioner("zz", 1.0 / shear_modulus))
    return sol.x, sol.multiplier, conv.apply("zz", sol.x) / shear_modulus, sol.iterations


def dry_run(capsys, case, *sets: str) -> tuple[int, list[str]]:
    """``viscontact run CASE --dry-run`` with ``--set`` each of ``sets``: (exit status, the non-empty
    lines of stderr)."""
    import os
    import tempfile
    from pathlib import Path

    from viscontact import cli

    # a folder that does not exist (a dry run writes nothing), in a writable place and one per process:
    # the run's lock file goes there while the command runs, and pytest-xdist's workers run side by side
    out = Path(tempfile.gettempdir()) / f"viscontact-dry-run-{os.getpid()}" / "r.nc"
    args = ["run", str(case), "--out", str(out), "--dry-run"]
    for s in sets:
        args += ["--set", s]
    code = cli.main(args)
    return code, [line for line in capsys.readouterr().err.splitlines() if line.strip()]


def elastic_pull_off_run(shear_modulus: float, poisson_ratio: float, radius: float, adhesion, reference: float,
                         n: int, half_width: float, *, press: float = 1.0, end: float = 1.1,
                         load_step: float = 0.01):
    """(the records, the run's ending) of an elastic sphere (R = ``radius`` [m]) with ``adhesion`` on n x n
    cells of +-``half_width`` [m], pressed with ``press`` |P_c| and pulled under load control in steps
    of ``load_step`` P_c from 0.9 P_c on to ``end`` P_c, where ``reference`` is the expected pull-off
    P_c [N] (< 0); warnings (the cohesive-zone guard's) silenced."""
    import warnings

    from viscontact.solvers import transient

    steps = round((end - 0.9) / load_step)
    history = PiecewiseLinear((0.0, 1.0, 11.0, 11.0 + steps), (-press * reference, -press * reference,
                                                                 0.9 * reference, end * reference))
    grid = Grid(n, half_width)
    x, y = grid.mesh()
    problem = Problem(material=Material.elastic(shear_modulus, poisson_ratio), grid=grid,
                      gap=(x**2 + y**2) / (2 * radius), normal=NormalLoading("load", history, tensile=True),
                      time=TimeStepping(history.times[-1], 1.0, "linear"), solver=SolverSettings(tolerance=1e-8),
                      output=OutputSettings(1, ("pressure",)), radius=radius, adhesion=adhesion)
    run = transient.steps(problem)
    records = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        while True:
            try:
                _, record = next(run)
            except StopIteration as stop:
                return records, stop.value
            records.append(record)


def rolling_cylinder_case(n: int, *, shear_modulus: float, poisson_ratio: float, radius: float, load: float,
                          speed: float, friction: float, half_width: float, held: str, t_end: float,
                          extra: str = ""):
    """A rigid cylinder rolling on an elastic half-plane in line contact (``grid.dimension = 1``): the
    case of the rolling validations (Carter's problem). ``held``: the ``[tangential]`` line that holds
    the creepage or the tangential force; ``half_width`` [m] of the grid; ``t_end`` [s] of the run;
    ``extra``: more case text (e.g. a ``[solver]`` table)."""
    from viscontact.io.case import Case

    return Case.from_toml_text(f"""
[material]
type = "elastic"
shear_modulus = {shear_modulus}
poisson_ratio = {poisson_ratio}
[indenter]
shape = "cylinder"
radius = {radius}
[grid]
dimension = 1
n = {n}
half_width = {half_width}
[normal]
control = "load"
value = {load}
[tangential]
mode = "rolling"
rolling_speed = {speed}
{held}
friction_coefficient = {friction}
[time]
t_end = {t_end}
{extra}""")
