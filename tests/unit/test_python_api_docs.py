"""The Python routes that getting_started.md documents run as written: a ``Case`` from a dict, a
``Problem`` from a numpy gap, and the cell centres a gap file is sampled at."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from viscontact.errors import ParameterError
from viscontact.io.case import Case, load_case

ROOT = Path(__file__).resolve().parents[2]
MARKER = "<!-- checked by tests/unit/test_python_api_docs.py"


def _checked_block() -> str:
    text = (ROOT / "docs" / "getting_started.md").read_text(encoding="utf-8")
    after = text[text.index(MARKER):]
    return re.search(r"```python\n(.*?)```", after, re.DOTALL).group(1)


@pytest.mark.filterwarnings("ignore::viscontact.ViscontactWarning")  # a coarse grid
def test_the_documented_case_and_problem_routes_run(capsys):
    """The block runs; the case from the dict and the problem from its numpy gap give the same load."""
    namespace: dict = {}
    exec(compile(_checked_block(), "getting_started.md", "exec"), namespace)
    case, ds, from_gap = namespace["case"], namespace["ds"], namespace["from_gap"]
    np.testing.assert_allclose(ds["delta_z"].values, from_gap["delta_z"].values, rtol=1e-12)
    assert Case.from_toml_text(case.text).model_dump() == case.model_dump()  # its text is the dict's TOML
    assert case.with_overrides({"grid.n": 16}).grid.n == 16


def test_a_case_dict_that_a_file_would_refuse_is_refused_the_same_way():
    with pytest.raises(ParameterError, match=r"^grid.n: must be >= 8, got 4"):
        Case.from_dict({**load_case(ROOT / "cases" / "creep_indentation.toml").model_dump(exclude_none=True),
                        "grid": {"n": 4, "half_width": 1e-3}})
    with pytest.raises(TypeError, match="Case.from_dict"):
        Case.from_dict([("grid", {})])


def test_a_gap_file_built_from_the_documented_cell_centres_is_the_sphere(tmp_path):
    """``indenter.file`` (shape = "surface") holds h0 at x_i = -half_width + (i + 1/2) dx, indexed [y, x]:
    a file built from that formula gives the sphere's gap (a surface file's lowest point shifted to 0)."""
    sphere = load_case(ROOT / "cases" / "creep_indentation.toml").with_overrides({"grid.n": 16})
    n, half_width, radius = sphere.grid.n, sphere.grid.half_width, sphere.indenter.radius
    x = -half_width + (np.arange(n) + 0.5) * (2 * half_width / n)
    np.save(tmp_path / "gap.npy", (x[None, :] ** 2 + x[:, None] ** 2) / (2 * radius))
    surface = Case.from_toml_text(sphere.text, tmp_path).with_overrides(
        {"indenter.shape": "surface", "indenter.radius": None, "indenter.file": "gap.npy"})
    problem = sphere.to_problem()
    np.testing.assert_allclose(surface.gap(problem.grid), problem.gap - problem.gap.min(), rtol=0, atol=1e-15)
