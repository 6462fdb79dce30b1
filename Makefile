# make demo | make test | make test-all   (each creates .venv when missing; safe to re-run)
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP_RUN := $(VENV)/.installed-run
STAMP_TEST := $(VENV)/.installed-test

.PHONY: demo test test-all clean

$(PY):
	$(PYTHON) -m venv $(VENV)

$(STAMP_RUN): pyproject.toml | $(PY)
	$(PY) -m pip install --quiet -e .
	touch $@

$(STAMP_TEST): pyproject.toml | $(PY)
	$(PY) -m pip install --quiet -e '.[test]'
	touch $@ $(STAMP_RUN)

demo: $(STAMP_RUN)
	$(VENV)/bin/viscontact run cases/creep_indentation.toml --out demo/creep_indentation.nc --plots demo/ --force

test: $(STAMP_TEST)
	$(PY) -m pytest -q -m "not slow"

test-all: $(STAMP_TEST)
	$(PY) -m pytest -q

clean:
	rm -rf demo/ .pytest_cache/ .hypothesis/
