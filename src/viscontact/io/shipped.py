"""The case files shipped with viscontact (package data), found wherever the package is installed.

The seed's cases (Wang et al., Friction 2023, Tables 1-3 and Fig. 10), the creep and relaxation
demonstrations and the sweep files live in the package folder ``viscontact/cases`` (in the
repository also reachable as ``cases/``). Each states in its header comment where its parameters
come from.

Examples
--------
>>> from viscontact import load_case, shipped_case
>>> shipped_case("creep_indentation").name
'creep_indentation.toml'
>>> load_case(shipped_case("seed_table1_v0.4")).tangential.mode
'frictionless_sliding'
>>> "sweeps/steady_mu_app_vs_speed" in shipped_case_names()
True
"""
from __future__ import annotations

from importlib.resources import files
from pathlib import Path

from viscontact.errors import ParameterError, check_type

__all__ = ["shipped_case", "shipped_case_names", "shipped_cases_dir"]


def shipped_cases_dir() -> Path:
    """The folder of the shipped case files (``viscontact/cases`` in the installed package)."""
    return Path(str(files("viscontact") / "cases"))


def shipped_case_names() -> list[str]:
    """Names of the shipped cases, sorted: file stems, with the sub-folder for sweeps
    (``"seed_table1_v0.4"``, ``"sweeps/steady_mu_app_vs_speed"``, ...)."""
    folder = shipped_cases_dir()
    return sorted(p.relative_to(folder).with_suffix("").as_posix() for p in folder.rglob("*.toml"))


def shipped_case(name: str) -> Path:
    """Path of the shipped case file ``name`` (with or without ``.toml``).

    Parameters
    ----------
    name
        A name from :func:`shipped_case_names`, e.g. ``"creep_indentation"`` or
        ``"sweeps/steady_mu_app_vs_speed"``.

    Raises
    ------
    ParameterError
        No shipped case has that name (the message lists those that exist).
    TypeError
        ``name`` is not a str.
    """
    check_type(name, str, "shipped_case's name", "a str such as 'creep_indentation'")
    stem = name[:-len(".toml")] if name.endswith(".toml") else name
    names = shipped_case_names()
    if stem not in names:
        raise ParameterError("case", f"no shipped case named {name!r}; shipped: {', '.join(names)}")
    return shipped_cases_dir() / f"{stem}.toml"
