# Two commands do all the set-up on a fresh machine with python3 and pip:
#   make demo   runs the main job on the embedded default
#   make test   runs the test suite
# Each creates the local virtual environment .venv and installs what it needs on first use.

PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: demo test test-all lint typecheck studies-quick clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[test,bem,h5,fast,dask,fatigue]"
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/wecss run

test: $(STAMP)
	$(PY) -m pytest

test-all: $(STAMP)
	$(PY) -m pytest -m "slow or not slow"

lint: $(STAMP)
	$(VENV)/bin/ruff format --check .
	$(VENV)/bin/ruff check .

typecheck: $(STAMP)
	$(VENV)/bin/mypy

studies-quick: $(STAMP)
	$(PY) studies/generate_hydro.py --all --quick
	$(PY) studies/generate_fits.py --quick
	$(PY) studies/radiation_fits.py --quick
	$(PY) studies/bench_radiation.py --quick
	$(PY) studies/bench_simulator.py --quick
	$(PY) studies/wecccomp.py --quick
	$(PY) studies/linear_vs_nonlinear.py --quick
	$(PY) studies/control_example.py --quick
	$(PY) studies/control_table.py --quick
	$(PY) studies/m4_control.py --quick
	$(PY) studies/bench_mpc.py --quick
	$(PY) studies/work_precision.py --quick
	$(PY) studies/stability.py --quick
	$(PY) studies/bench_startup.py --quick
	$(PY) studies/m4_paper.py --quick
	$(PY) studies/bench_sweep.py --quick
	$(PY) studies/notc.py --quick
	$(PY) studies/bench_memory.py --quick

clean:
	rm -rf $(VENV) .pytest_cache .mypy_cache .ruff_cache
