"""viscontact: transient frictional sliding contact of a rigid indenter on a linear viscoelastic
half-space (boundary elements + DC-FFT), after Wang et al., Friction (2023).

Public API::

    import viscontact as vc
    case = vc.load_case("cases/creep_indentation.toml")
    ds = vc.run(case)                       # xarray.Dataset (SPEC §3)
    vc.write_netcdf(ds, "creep.nc")
"""
from importlib.metadata import version as _v

from .api import run, steady
from .case import Case, load_case
from .errors import ConvergenceError, NumericalGuardError, ParameterError, ViscontactError, ViscontactWarning
from .grid import Grid
from .materials import Material
from .problem import (NormalLoading, OutputSettings, PiecewiseLinear, Problem, SolverSettings, TangentialLoading,
                      TimeStepping)
from .records import StepRecord
from .results import open_result, to_dataset, write_netcdf

__version__ = _v("viscontact")

__all__ = [
    "__version__",
    "load_case", "Case", "run", "steady",
    "Material", "Grid", "Problem", "NormalLoading", "PiecewiseLinear", "TangentialLoading", "TimeStepping",
    "SolverSettings", "OutputSettings", "StepRecord",
    "to_dataset", "write_netcdf", "open_result",
    "ViscontactError", "ParameterError", "ConvergenceError", "NumericalGuardError", "ViscontactWarning",
]
