# make demo | make test | make test-all | make docs   (each creates .venv when missing; safe to re-run)
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP_RUN := $(VENV)/.installed-run
STAMP_TEST := $(VENV)/.installed-test
STAMP_DOCS := $(VENV)/.installed-docs

.PHONY: demo test test-all docs clean

$(PY):
	$(PYTHON) -m venv $(VENV)

$(STAMP_RUN): pyproject.toml | $(PY)
	$(PY) -m pip install --quiet -e .
	touch $@

$(STAMP_TEST): pyproject.toml | $(PY)
	$(PY) -m pip install --quiet -e '.[test]'
	touch $@ $(STAMP_RUN)

$(STAMP_DOCS): pyproject.toml | $(PY)
	$(PY) -m pip install --quiet -e '.[docs]'
	touch $@ $(STAMP_RUN)

demo: $(STAMP_RUN)
	$(VENV)/bin/viscontact run cases/creep_indentation.toml --out demo/creep_indentation.nc --plots demo/ --force

# one pytest worker per core (pytest-xdist): the tests are independent processes' worth of work
test: $(STAMP_TEST)
	$(PY) -m pytest -q -n auto -m "not slow"

test-all: $(STAMP_TEST)
	$(PY) -m pytest -q -n auto

# the HTML site in docs/_build/html; any Sphinx warning fails the build; the gallery examples run
docs: $(STAMP_DOCS)
	$(VENV)/bin/sphinx-build -W --keep-going -q -j auto -b html docs docs/_build/html

clean:
	rm -rf demo/ .pytest_cache/ .hypothesis/ docs/_build/ docs/generated/ docs/auto_examples/ docs/api.rst
