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
    "run": "running.api", "run_steady": "running.api", "run_to_file": "running.api", "Written": "running.api",
    "Case": "io.case", "load_case": "io.case",
    "ConvergenceError": "errors", "NumericalGuardError": "errors", "ParameterError": "errors",
    "ViscontactError": "errors", "ViscontactWarning": "errors",
    "Grid": "numerics.grid", "Material": "physics.materials",
    "NormalLoading": "problem.problem", "OutputSettings": "problem.problem", "PiecewiseLinear": "problem.problem",
    "Problem": "problem.problem", "SolverSettings": "problem.problem", "TangentialLoading": "problem.problem",
    "TimeStepping": "problem.problem", "StepRecord": "problem.records",
    "open_result": "io.netcdf", "to_dataset": "io.results", "write_netcdf": "io.netcdf",
    "shipped_case": "io.shipped",
}


def __getattr__(name: str):
    """The public names, imported lazily (PEP 562); ``steady`` is the steady-state solver module."""
    if name == "steady":
        return _import_module(".solvers.steady", __name__)
    if name == "__version__":
        from viscontact.version import package_version

        globals()[name] = package_version()
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
