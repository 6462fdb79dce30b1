"""The scripts of a GPU session (benchmarks/device/, docs/gpu.md): the wheel set's check and
check.sh's run where there is no CUDA device."""
from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DEVICE = ROOT / "benchmarks" / "device"


def _wheels():
    spec = importlib.util.spec_from_file_location("device_wheels", DEVICE / "wheels.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _wheel(folder: Path, name: str, version: str, *requires: str) -> Path:
    """A wheel file holding only its METADATA."""
    path = folder / f"{name.replace('-', '_')}-{version}-py3-none-any.whl"
    with zipfile.ZipFile(path, "w") as wheel:
        lines = [f"Name: {name}", f"Version: {version}", *(f"Requires-Dist: {r}" for r in requires)]
        wheel.writestr(f"{name.replace('-', '_')}-{version}.dist-info/METADATA", "\n".join(lines) + "\n")
    return path


@pytest.fixture
def wheels(monkeypatch):
    module = _wheels()
    monkeypatch.setattr(module, "PINS", ["pydantic==2.14.4", "annotated-types==0.8.0", "typing_extensions==4.16.0"])
    return module


def test_a_complete_wheel_set_passes_and_markers_and_extras_are_read_for_python_3_12(wheels, tmp_path, capsys):
    _wheel(tmp_path, "pydantic", "2.14.4", "annotated-types>=0.6", "typing-extensions>=4.14",
           "numpy; python_version >= '3.12'", "email-validator>=2.0; extra == 'email'",
           "tomli; python_version < '3.11'")
    _wheel(tmp_path, "annotated-types", "0.8.0")
    _wheel(tmp_path, "typing_extensions", "4.16.0")
    assert wheels.verify(tmp_path) == 0
    out = capsys.readouterr().out
    assert "requires: annotated-types, typing-extensions, numpy\n" in out and "PROBLEM" not in out


def test_a_missing_requirement_a_second_version_and_an_unpinned_wheel_are_problems(wheels, tmp_path, capsys):
    _wheel(tmp_path, "pydantic", "2.14.4", "annotated-types", "typing-inspection")
    _wheel(tmp_path, "annotated-types", "0.8.0")
    _wheel(tmp_path, "annotated-types", "0.7.0")
    _wheel(tmp_path, "zict", "3.0.0")
    assert wheels.verify(tmp_path) == 1
    out = capsys.readouterr().out
    assert "requires typing-inspection: neither on the image nor carried" in out
    assert "no wheel for typing-extensions==4.16.0" in out and "2 wheels for annotated-types" in out
    assert "zict is not pinned" in out
    wheels.prune(tmp_path)  # keeps the pinned versions only
    assert sorted(p.name.split("-")[0] for p in tmp_path.glob("*.whl")) == ["annotated_types", "pydantic"]


def test_an_uninstalled_source_tree_gets_its_version_from_a_metadata_folder(tmp_path, monkeypatch):
    """check.sh runs viscontact from src/ on the GPU machine: without metadata ``__version__``, which
    every result file records, raised PackageNotFoundError (the seam's streamed run failed so)."""
    from importlib import metadata

    module = _wheels()
    installed = module.source_metadata(tmp_path / "a")
    assert installed is None and not (tmp_path / "a").exists()  # this environment has viscontact installed
    real = metadata.version

    def uninstalled(name):
        if name == "viscontact":
            raise metadata.PackageNotFoundError(name)
        return real(name)
    monkeypatch.setattr(metadata, "version", uninstalled)
    info = module.source_metadata(tmp_path / "site")
    dist = next(metadata.distributions(name="viscontact", path=[str(tmp_path / "site")]))
    assert info.parent == tmp_path / "site" and dist.version == real("viscontact")


def test_the_device_scripts_are_valid_bash():
    for script in ("prepare.sh", "check.sh"):
        subprocess.run(["bash", "-n", str(DEVICE / script)], check=True)


@pytest.mark.slow
def test_check_sh_without_a_cuda_device_skips_the_device_tests_and_succeeds(tmp_path):
    try:
        from viscontact.numerics.arrays import cupy_backend

        cupy_backend()
        pytest.skip("CuPy finds a CUDA device here")
    except ImportError:
        pass
    env = {**os.environ, "OUT": str(tmp_path), "PYTHON": sys.executable, "CHECK_SITE": str(tmp_path / "site"),
           "SEAM_WORKERS": "1", "PYTHONPATH": str(ROOT / "src")}
    out = subprocess.run(["bash", str(DEVICE / "check.sh")], env=env, capture_output=True, text=True, timeout=400,
                         cwd=ROOT)
    assert out.returncode == 0, out.stdout + out.stderr
    summary = (tmp_path / "summary.txt").read_text()
    for stage in ("install", "environment", "seam", "bench_128", "rough_64"):
        assert f"{stage}: status 0" in summary
    assert "no CuPy GPU backend" in (tmp_path / "seam.log").read_text()
    assert "| gpu | no CUDA device |" in (tmp_path / "bench_128.md").read_text()
    assert "| rough | 64² × 3 | cpu |" in (tmp_path / "rough_64.md").read_text()  # the case builds and runs
    assert "| rough | 64² × 3 | gpu | no CUDA device |" in (tmp_path / "rough_64.md").read_text()
    assert "no CUDA device" in (tmp_path / "env.txt").read_text()
