"""viscontact: transient frictional sliding contact of a rigid indenter on a linear viscoelastic
half-space (boundary elements + DC-FFT), after Wang et al., Friction (2023).

Public API::

    import viscontact as vc
    case = vc.load_case(vc.shipped_case("creep_indentation"))   # or a path to your own TOML file
    ds = vc.run(case)                       # xarray.Dataset (see the result-file docs)
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
from .shipped import shipped_case

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
    "shipped_case",
    "steady",
    "to_dataset",
    "write_netcdf",
]
