"""Case keys of periodic domains and rough surfaces: ``[grid] periodic``, ``[indenter] shape =
"self_affine" | "topography"``, ``[indenter.roughness]`` on a sphere; bad input is one line naming
the key (from the API and from the command line, exit status 2)."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from viscontact.io.case import Case
from viscontact.errors import ParameterError, ViscontactWarning
from viscontact.numerics.grid import Grid
from viscontact.problem.topography import gap_from_heights, self_affine_heights, sphere_heights

ROOT = Path(__file__).resolve().parents[2]
ROUGH = (ROOT / "cases" / "rough_periodic_sliding.toml").read_text()
SPHERE = (ROOT / "cases" / "creep_indentation.toml").read_text()
ST = pytest.importorskip("SurfaceTopography")


def _case(text: str, changes: dict[str, str], base_dir: Path | str = ".") -> Case:
    for old, new in changes.items():
        assert old in text, old
        text = text.replace(old, new, 1)
    return Case.from_toml_text(text, base_dir)


def test_periodic_self_affine_case():
    problem = _case(ROUGH, {}).to_problem()
    assert problem.grid == Grid(64, 0.0005, periodic=True)
    heights = self_affine_heights(Grid(64, 0.0005), hurst=0.8, rms_slope=0.1, short_cutoff=125e-6, seed=1)
    np.testing.assert_array_equal(problem.gap, gap_from_heights(heights))
    assert not _case(ROUGH, {"periodic = true": "periodic = false"}).to_problem().grid.periodic


@pytest.mark.parametrize("old, new, key, words", [
    ("hurst = 0.8", "hurst = 1.5", "indenter.hurst", "<= 1"),
    ("hurst = 0.8\n", "", "indenter.hurst", "required"),
    ("rms_slope = 0.1", "rms_slope = 0.1\nrms_height = 1e-6", "indenter.rms_height", "exactly one"),
    ("rms_slope = 0.1", "rms_slope = 0.1\nradius = 0.01", "indenter.radius", "only with shape = 'sphere'"),
    ("seed = 1", "seed = 1\nresample = true", "indenter.resample", "only with shape = 'topography'"),
    ("seed = 1", "seed = -1", "indenter.seed", ">= 0"),
    ("periodic = true", "periodic = 1", "grid.periodic", "boolean"),
])
def test_bad_rough_keys(old, new, key, words):
    with pytest.raises(ParameterError) as err:
        _case(ROUGH, {old: new}).to_problem()
    assert err.value.key == key and words in err.value.message and "\n" not in str(err.value)


def test_short_cutoff_below_two_cells_is_caught_when_the_grid_is_known():
    case = _case(ROUGH, {"short_cutoff = 125e-6": "short_cutoff = 10e-6"})
    with pytest.raises(ParameterError) as err:
        case.to_problem()
    assert err.value.key == "indenter.short_cutoff"


def test_rough_sphere():
    smooth = _case(SPHERE, {}).to_problem()
    rough = _case(SPHERE, {'radius = 0.01': 'radius = 0.01\n[indenter.roughness]\nhurst = 0.7\n'
                                            'rms_height = 0.2e-6\nseed = 3'}).to_problem()
    assert rough.radius == smooth.radius
    heights = self_affine_heights(smooth.grid, hurst=0.7, rms_height=0.2e-6, seed=3, key="indenter.roughness")
    expected = gap_from_heights(sphere_heights(smooth.grid, 0.01) + heights)
    np.testing.assert_allclose(rough.gap, expected, rtol=0, atol=1e-18)
    with pytest.raises(ParameterError) as err:
        _case(SPHERE, {'radius = 0.01': 'radius = 0.01\n[indenter.roughness]\nrms_height = 0.2e-6'}).to_problem()
    assert err.value.key == "indenter.roughness.hurst"


def _topography_case(tmp_path: Path, n_file: int, resample: bool) -> Case:
    heights = self_affine_heights(Grid(n_file, 0.0005), hurst=0.8, rms_slope=0.1, seed=1)
    ST.Topography(heights.T * 1e6, (1000.0, 1000.0), unit="um", periodic=True).to_netcdf(str(tmp_path / "s.nc"))
    extra = "\nresample = true" if resample else ""
    return _case(ROUGH, {'shape = "self_affine"\nhurst = 0.8\nrms_slope = 0.1\n'
                         'short_cutoff = 125e-6                 # m, 1/8 of the period\nseed = 1':
                         f'shape = "topography"\nfile = "s.nc"{extra}'}, tmp_path)


def test_topography_file(tmp_path):
    problem = _topography_case(tmp_path, 64, False).to_problem()
    heights = self_affine_heights(Grid(64, 0.0005), hurst=0.8, rms_slope=0.1, seed=1)
    np.testing.assert_allclose(problem.gap, gap_from_heights(heights), rtol=0, atol=1e-12 * np.ptp(heights))
    with pytest.raises(ParameterError, match="32 x 32 points over 0.001 m x 0.001 m; the grid has 64 x 64"):
        _topography_case(tmp_path, 32, False).to_problem()
    assert _topography_case(tmp_path, 32, True).to_problem().gap.shape == (64, 64)


def test_topography_mismatch_on_the_command_line(tmp_path):
    case = _topography_case(tmp_path, 32, False)
    (tmp_path / "case.toml").write_text(case.text)
    script = Path(sys.executable).with_name("viscontact")
    command = [str(script)] if script.exists() else [sys.executable, "-m", "viscontact.cli"]
    proc = subprocess.run([*command, "run", "case.toml", "--out", "out.nc"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300, check=False)
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("viscontact: error: indenter.file: "), proc.stderr
    assert not (tmp_path / "out.nc").exists()


def test_a_map_without_its_size_reads_with_physical_size_and_unit(tmp_path):
    """A .npy of heights [x, y] in um carries no size or unit: physical_size and unit give them, and
    the gap is the NetCDF file's (which carries them). Given for a file that has its own: one line."""
    heights = self_affine_heights(Grid(64, 0.0005), hurst=0.8, rms_slope=0.1, seed=1)
    np.save(tmp_path / "s.npy", heights.T * 1e6)  # SurfaceTopography's [x, y], in um
    from_netcdf = _topography_case(tmp_path, 64, False).to_problem().gap
    npy = {'file = "s.nc"': 'file = "s.npy"\nphysical_size = [1000.0, 1000.0]\nunit = "um"'}
    from_npy = _case(_topography_case(tmp_path, 64, False).text, npy, tmp_path).to_problem().gap
    np.testing.assert_allclose(from_npy, from_netcdf, rtol=0, atol=1e-12 * np.ptp(from_netcdf))
    with pytest.raises(ParameterError, match="physical_size = \\[width, height\\] and indenter.unit"):
        _case(_topography_case(tmp_path, 64, False).text, {'file = "s.nc"': 'file = "s.npy"'}, tmp_path).to_problem()
    both = {'file = "s.nc"': 'file = "s.nc"\nphysical_size = [1000.0, 1000.0]\nunit = "um"'}
    with pytest.raises(ParameterError, match="the file gives its own size and unit"):
        _case(_topography_case(tmp_path, 64, False).text, both, tmp_path).to_problem()


def test_physical_size_in_metres_and_its_deprecated_form_in_the_unit(tmp_path):
    """``indenter.physical_size_m`` is SI (metres) whatever the heights' ``unit``; the older
    ``physical_size`` (in ``indenter.unit``) keeps its meaning and warns, naming the SI key and value.
    Both at once, or physical_size_m without the heights' unit, are refused, each in one line."""
    heights = self_affine_heights(Grid(64, 0.0005), hurst=0.8, rms_slope=0.1, seed=1)
    np.save(tmp_path / "s.npy", heights.T * 1e6)  # SurfaceTopography's [x, y], in um
    text = _topography_case(tmp_path, 64, False).text
    from_netcdf = _topography_case(tmp_path, 64, False).to_problem().gap
    si = {'file = "s.nc"': 'file = "s.npy"\nphysical_size_m = [1e-3, 1e-3]\nunit = "um"'}
    np.testing.assert_allclose(_case(text, si, tmp_path).to_problem().gap, from_netcdf, rtol=0,
                               atol=1e-12 * np.ptp(from_netcdf))
    old = {'file = "s.nc"': 'file = "s.npy"\nphysical_size = [1000.0, 1000.0]\nunit = "um"'}
    with pytest.warns(ViscontactWarning, match=r"indenter.physical_size is deprecated.*use "
                      r"indenter.physical_size_m = \[0.001, 0.001\] \(metres\)"):
        deprecated = _case(text, old, tmp_path).to_problem().gap
    np.testing.assert_array_equal(deprecated, _case(text, si, tmp_path).to_problem().gap)
    both = {'file = "s.nc"': 'file = "s.npy"\nphysical_size_m = [1e-3, 1e-3]\nphysical_size = [1e3, 1e3]\nunit = "um"'}
    with pytest.raises(ParameterError, match="^indenter.physical_size: give indenter.physical_size_m"):
        _case(text, both, tmp_path)
    with pytest.raises(ParameterError, match="^indenter.unit: required with indenter.physical_size_m"):
        _case(text, {'file = "s.nc"': 'file = "s.npy"\nphysical_size_m = [1e-3, 1e-3]'}, tmp_path)
