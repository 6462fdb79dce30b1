"""The examples in the docstrings run, from the repository's root folder as they say, and none is
skipped."""
from __future__ import annotations

import doctest
import importlib
import pkgutil
from pathlib import Path

import pytest

import viscontact

ROOT = Path(__file__).resolve().parents[2]
MODULES = sorted(m.name for m in pkgutil.walk_packages(viscontact.__path__, "viscontact.")) + ["viscontact"]


def _examples(name: str) -> list[doctest.DocTest]:
    return [t for t in doctest.DocTestFinder().find(importlib.import_module(name)) if t.examples]


@pytest.mark.filterwarnings("ignore::viscontact.ViscontactWarning")  # coarse steps of the tiny examples
@pytest.mark.parametrize("name", [m for m in MODULES if _examples(m)])
def test_examples_run(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for test in _examples(name):
        runner.run(test)
    assert runner.failures == 0, f"{runner.failures} example(s) of {name} failed (see the captured output)"


def test_examples_exist_and_none_is_skipped() -> None:
    assert sum(len(t.examples) for m in MODULES for t in _examples(m)) >= 8
    for path in (ROOT / "src" / "viscontact").rglob("*.py"):
        assert "+SKIP" not in path.read_text(encoding="utf-8"), path
