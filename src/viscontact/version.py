"""The installed package's version (the foundation layer: any module may ask it)."""
from __future__ import annotations

from functools import lru_cache


@lru_cache(maxsize=1)
def package_version() -> str:
    """The version of the installed viscontact distribution ("unknown" where it is not installed)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("viscontact")
    except PackageNotFoundError:
        return "unknown"
