"""viscontact: transient frictional sliding contact of a rigid indenter on a linear viscoelastic
half-space (boundary elements + DC-FFT), after Wang et al., Friction (2023).

Public API::

    import viscontact as vc
    case = vc.load_case(vc.shipped_case("creep_indentation"))   # or a path to your own TOML file
    ds = vc.run(case)                       # xarray.Dataset (see the result-file docs)
    vc.write_netcdf(ds, "creep.nc")
"""
from importlib import import_module as _import_module

#: public name -> module defining it; imported on first use, so that ``viscontact.cli`` starts at once
#: (and handles SIGINT from its first moment) without loading xarray and the solvers
_EXPORTS = {
    "run": "api", "run_steady": "api", "run_to_file": "api", "Written": "api", "Case": "case", "load_case": "case",
    "ConvergenceError": "errors",
    "NumericalGuardError": "errors", "ParameterError": "errors", "ViscontactError": "errors",
    "ViscontactWarning": "errors", "Grid": "grid", "Material": "materials", "NormalLoading": "problem",
    "OutputSettings": "problem", "PiecewiseLinear": "problem", "Problem": "problem", "SolverSettings": "problem",
    "TangentialLoading": "problem", "TimeStepping": "problem", "StepRecord": "records", "open_result": "results",
    "to_dataset": "results", "write_netcdf": "results", "shipped_case": "shipped",
}


def __getattr__(name: str):
    """The public names, imported lazily (PEP 562); ``steady`` is the steady-state solver module."""
    if name == "steady":
        return _import_module(".steady", __name__)
    if name == "__version__":
        from importlib.metadata import version

        globals()[name] = version("viscontact")
        return globals()[name]
    if name in _EXPORTS:
        value = getattr(_import_module(f".{_EXPORTS[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)


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
    "Written",
    "__version__",
    "load_case",
    "open_result",
    "run",
    "run_steady",
    "run_to_file",
    "shipped_case",
    "steady",
    "to_dataset",
    "write_netcdf",
]
