# Two commands do all the set-up on a fresh machine with python3 and pip:
#   make demo   runs the main job on the embedded default
#   make test   runs the test suite
# Each creates the local virtual environment .venv and installs what it needs on first use.

PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
COMPILED := $(VENV)/.precompiled

.PHONY: demo test test-all lint typecheck docs studies-quick clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[test,bem,h5,fast,dask,fatigue,docs]"
	touch $(STAMP)

# numba's cache of the runners' time loops, filled once after the install (wecss precompile: minutes, two processes);
# the suite's workers then load the loops instead of each compiling them
$(COMPILED): $(STAMP)
	$(VENV)/bin/wecss precompile --jobs 2
	touch $(COMPILED)

demo: $(STAMP)
	$(VENV)/bin/wecss run

# the suite on one worker process per core (pytest-xdist); PYTEST_WORKERS=0 runs it in this process
PYTEST_WORKERS ?= auto

test: $(COMPILED)
	$(PY) -m pytest -n $(PYTEST_WORKERS)

test-all: $(COMPILED)
	$(PY) -m pytest -n $(PYTEST_WORKERS) -m "slow or not slow"

lint: $(STAMP)
	$(VENV)/bin/ruff format --check .
	$(VENV)/bin/ruff check .

typecheck: $(STAMP)
	$(VENV)/bin/mypy

# the documentation site (mkdocs.yml: the guide docs/*.md and the API reference from the docstrings) into site/;
# --strict: a warning (a broken link, a page left out of the navigation, a docstring griffe cannot parse) fails
docs: $(STAMP)
	$(PY) -m mkdocs build --strict --site-dir site

# every studies/[a-z]*.py with --quick, two at a time (CI has two cores), stopping at the first failure
# (studies/_quick.py finds them)
studies-quick: $(STAMP)
	$(PY) studies/_quick.py --jobs 2

clean:
	rm -rf $(VENV) .pytest_cache .mypy_cache .ruff_cache site
