"""viscontact: transient frictional sliding contact of a rigid indenter on a linear viscoelastic
half-space (boundary elements + DC-FFT), after Wang et al., Friction (2023).

Public API::

    import viscontact as vc
    case = vc.load_case("cases/creep_indentation.toml")
    ds = vc.run(case)                       # xarray.Dataset (SPEC §3)
    vc.write_netcdf(ds, "creep.nc")
"""
from importlib.metadata import version as _v

from . import steady  # the steady-state solver module (viscontact.steady.solve_steady, speed_sweep)
from .api import run, run_steady
from .case import Case, load_case
from .errors import ConvergenceError, NumericalGuardError, ParameterError, ViscontactError, ViscontactWarning
from .grid import Grid
from .materials import Material
from .problem import (
    NormalLoading,
    OutputSettings,
    PiecewiseLinear,
    Problem,
    SolverSettings,
    TangentialLoading,
    TimeStepping,
)
from .records import StepRecord
from .results import open_result, to_dataset, write_netcdf

__version__ = _v("viscontact")

__all__ = [
    "Case",
    "ConvergenceError",
    "Grid",
    "Material",
    "NormalLoading",
    "NumericalGuardError",
    "OutputSettings",
    "ParameterError",
    "PiecewiseLinear",
    "Problem",
    "SolverSettings",
    "StepRecord",
    "TangentialLoading",
    "TimeStepping",
    "ViscontactError",
    "ViscontactWarning",
    "__version__",
    "load_case",
    "open_result",
    "run",
    "run_steady",
    "steady",
    "to_dataset",
    "write_netcdf",
]
