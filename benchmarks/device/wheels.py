"""The wheels a GPU session carries (``.whl/``): what viscontact's device tests and benchmark import
that the lent GPU machine's image lacks, for its Python 3.12 (see docs/gpu.md).

    python3 benchmarks/device/wheels.py pins            # NAME==VERSION, one a line (prepare.sh downloads them)
    python3 benchmarks/device/wheels.py prune .whl      # delete wheels that are not one of the pins
    python3 benchmarks/device/wheels.py verify .whl     # one wheel per pin; every Requires-Dist met
    python3 benchmarks/device/wheels.py missing .whl    # the wheels whose package this Python lacks (check.sh)
    python3 benchmarks/device/wheels.py source-metadata /tmp/site   # viscontact's version for src/ (check.sh)

The image (no network there) has Python 3.12 with numpy 2.5, scipy, xarray, h5py, matplotlib, tqdm,
pytest, pytest-xdist, hypothesis and cupy-cuda13x, and what pip installed with them (:data:`IMAGE`).
The pins are the versions the test suite runs with here. What needs them, at import:

* pydantic (+ pydantic-core, annotated-types, typing-inspection, typing-extensions): case files
  (``viscontact.io.case``; the seam tests load the shipped rough case);
* h5netcdf: result files (the seam's streamed run);
* SurfaceTopography (+ NuMPI, array-api-compat, primefac and its readers' packages): the
  self-affine surface of the rough periodic case (``viscontact.problem.topography``).

dask and distributed are not carried: only ``viscontact sweep`` imports them (results.py does where
present); neither the seam tests nor ``benchmarks/bench_device.py`` need them.
"""
from __future__ import annotations

import re
import sys
import tomllib
import zipfile
from importlib import metadata
from pathlib import Path

from packaging.requirements import Requirement

PINS = """
pydantic==2.14.4
pydantic-core==2.50.5
annotated-types==0.8.0
typing-inspection==0.4.5
typing-extensions==4.16.0
h5netcdf==1.8.2
SurfaceTopography==1.27.1
NuMPI==0.18.1
array-api-compat==1.16.0
primefac==2.0.12
igor2==0.5.15
numpyencoder==0.3.2
olefile==0.47
openpyxl==3.1.5
et-xmlfile==2.0.0
defusedxml==0.7.1
xmltodict==1.0.4
PyYAML==6.0.4
requests==2.34.2
urllib3==2.8.0
idna==3.20
certifi==2026.10.19.post1
charset-normalizer==3.5.3
tifffile==2026.3.3
zstandard==0.25.0
""".split()

#: on the GPU image: the packages it names and the dependencies pip installed with them
IMAGE = {"numpy", "scipy", "xarray", "h5py", "matplotlib", "tqdm", "pytest", "pytest-xdist", "hypothesis",
         "cupy-cuda13x",
         # xarray, matplotlib, pytest, pytest-xdist, hypothesis, cupy
         "pandas", "packaging", "python-dateutil", "six", "tzdata", "pillow", "pyparsing", "contourpy", "cycler",
         "fonttools", "kiwisolver", "iniconfig", "pluggy", "pygments", "execnet", "sortedcontainers", "fastrlock",
         "cuda-pathfinder"}

#: the target: CPython 3.12 on Linux x86-64 (environment markers of Requires-Dist; no extras)
TARGET = {"python_version": "3.12", "python_full_version": "3.12.0", "sys_platform": "linux",
          "platform_system": "Linux", "platform_machine": "x86_64", "os_name": "posix",
          "implementation_name": "cpython", "platform_python_implementation": "CPython", "extra": ""}


def normalized(name: str) -> str:
    """PEP 503's name: lower case, runs of -, _ and . as one -."""
    return re.sub(r"[-_.]+", "-", name).lower()


def pinned() -> dict[str, str]:
    """normalized name -> version."""
    return {normalized(name): version for name, version in (pin.split("==") for pin in PINS)}


def wheel_id(path: Path) -> tuple[str, str]:
    """(normalized name, version) of a wheel file's name."""
    name, version = path.name.split("-")[:2]
    return normalized(name), version


def requirements(path: Path) -> list[str]:
    """The normalized names a wheel requires on the target (no extras)."""
    with zipfile.ZipFile(path) as wheel:
        meta = next(n for n in wheel.namelist() if n.endswith(".dist-info/METADATA"))
        lines = wheel.read(meta).decode().splitlines()
    out = []
    for line in lines:
        if not line.startswith("Requires-Dist:"):
            continue
        requirement = Requirement(line[len("Requires-Dist:"):].strip())
        if requirement.marker is None or requirement.marker.evaluate(TARGET):
            out.append(normalized(requirement.name))
    return out


def prune(folder: Path) -> None:
    pins = pinned()
    for path in sorted(folder.glob("*.whl")):
        name, version = wheel_id(path)
        if pins.get(name) != version:
            print(f"removed {path.name} (not pinned)")
            path.unlink()


def verify(folder: Path) -> int:
    """0 when each pin has exactly one wheel and every requirement of every wheel is on the image or
    among the wheels; prints the wheels with their sizes and what they require."""
    pins, wheels = pinned(), sorted(folder.glob("*.whl"))
    found: dict[str, list[Path]] = {}
    for path in wheels:
        found.setdefault(wheel_id(path)[0], []).append(path)
    problems = [f"no wheel for {name}=={version}" for name, version in pins.items() if name not in found]
    problems += [f"{len(paths)} wheels for {name}" for name, paths in found.items() if len(paths) > 1]
    problems += [f"{name} is not pinned" for name in found if name not in pins]
    total = 0
    for path in wheels:
        needs = requirements(path)
        unmet = [r for r in needs if r not in IMAGE and r not in found]
        problems += [f"{path.name} requires {r}: neither on the image nor carried" for r in unmet]
        total += path.stat().st_size
        print(f"{path.stat().st_size / 2**20:7.2f} MiB  {path.name}  requires: {', '.join(needs) or '-'}")
    print(f"{total / 2**20:7.2f} MiB  in {len(wheels)} wheels")
    for name, version in pins.items():  # the suite ran here with other versions: a note, not a problem
        try:
            installed = metadata.version(name)
        except metadata.PackageNotFoundError:
            continue
        if installed != version:
            print(f"note: {name} pinned {version}, {installed} in {sys.executable}")
    for problem in problems:
        print("PROBLEM:", problem)
    return 1 if problems else 0


def missing(folder: Path) -> None:
    """The wheels (paths) whose distribution this Python does not have."""
    for path in sorted(folder.glob("*.whl")):
        try:
            metadata.version(wheel_id(path)[0])
        except metadata.PackageNotFoundError:
            print(path)


def source_metadata(site: Path, root: Path = Path(__file__).resolve().parents[2]) -> Path | None:
    """Where viscontact runs from its source tree without being installed (``PYTHONPATH=src``), a
    metadata folder in ``site`` giving its version (``viscontact.__version__``, which result files
    record, reads it), as an installation leaves one; None where this Python has it already."""
    try:
        print("viscontact", metadata.version("viscontact"), "installed")
        return None
    except metadata.PackageNotFoundError:
        pass
    version = tomllib.loads((root / "pyproject.toml").read_text())["project"]["version"]
    info = site / f"viscontact-{version}.dist-info"
    info.mkdir(parents=True, exist_ok=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: viscontact\nVersion: {version}\n")
    print(f"viscontact {version} from {root / 'src'} (its metadata in {info})")
    return info


if __name__ == "__main__":
    command = sys.argv[1] if len(sys.argv) > 1 else ""
    if command == "pins":
        print("\n".join(PINS))
    elif command in ("prune", "verify", "missing", "source-metadata") and len(sys.argv) == 3:
        run = {"prune": prune, "verify": verify, "missing": missing, "source-metadata": source_metadata}[command]
        result = run(Path(sys.argv[2]))
        sys.exit(result if isinstance(result, int) else 0)
    else:
        sys.exit(__doc__)
