"""What the ``wecss`` command does to its own process (``wecss.command_process``): the commands but ``sweep`` keep
dask out of it (``wecss.dask_free``: xarray would import dask.array for its first variable and distributed for its
first netCDF write, about 0.35 s), and the garbage collector is tuned for a short process. A call of ``main([...])``
from Python leaves the caller's process alone. Each check runs in a fresh process: keeping dask out cannot be
undone."""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.toy_plugins import write_distribution
from wecss.command_process import GC_THRESHOLDS

ROOT = Path(__file__).resolve().parent.parent
needs_dask = pytest.mark.skipif(importlib.util.find_spec("dask") is None, reason="the dask extra is not installed")

SCENE = (
    '[device]\nname = "m4-111"\n[sea]\nkind = "jonswap"\nheight = 0.04\nperiod = 1.2\nduration = "3 Tp"\n'
    'ramp = "1 Tp"\n[outputs]\nvariables = ["pto", "elevation"]\n'
)


def _in_fresh_process(code: str, cwd: Path) -> dict[str, object]:
    """Run ``code`` in a new interpreter (pure-Python kernels: no numba compile); return what it prints last as
    JSON, with ``loaded``: the dask and distributed modules it imported."""
    probe = (
        f"{code}\nimport gc, json, sys\nloaded = sorted(m for m, v in sys.modules.items() "
        "if v is not None and m.split('.')[0] in ('dask', 'distributed'))\n"
        "gc_state = {'thresholds': list(gc.get_threshold()), 'frozen': gc.get_freeze_count()}\n"
        "print(json.dumps({'loaded': loaded, **gc_state, **globals().get('report', {})}))"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT), "WECSS_JIT": "0"}
    out = subprocess.run([sys.executable, "-c", probe], env=env, cwd=cwd, check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _command(*args: str) -> str:
    """The ``wecss`` command as the console script calls it: ``main()`` on the process's own command line."""
    return (
        f"import sys\nfrom wecss.cli import main\nsys.argv = ['wecss', *{list(args)!r}]\nreport = {{'status': main()}}"
    )


def test_wecss_run_imports_no_dask_and_tunes_the_garbage_collector(tmp_path):
    (tmp_path / "s.toml").write_text(SCENE)
    out = _in_fresh_process(_command("run", "s.toml", "-o", "r.nc", "-q"), tmp_path)
    assert out["status"] == 0 and (tmp_path / "r.nc").is_file() and (tmp_path / "r.png").is_file()
    assert out["loaded"] == []
    assert out["thresholds"] == list(GC_THRESHOLDS) and out["frozen"] > 0  # frozen for the exit


def test_a_failed_command_leaves_its_process_frozen_for_the_exit(tmp_path):
    out = _in_fresh_process(_command("run", "missing.toml", "-q"), tmp_path)
    assert out["status"] == 2 and out["frozen"] > 0


@needs_dask
def test_allow_dask_lets_xarray_import_it(tmp_path):
    (tmp_path / "s.toml").write_text(SCENE)
    out = _in_fresh_process(_command("run", "s.toml", "-o", "r.nc", "-q", "--allow-dask"), tmp_path)
    assert out["status"] == 0 and "dask.array" in out["loaded"]


@needs_dask
def test_main_called_with_arguments_leaves_the_calling_process_as_it_is(tmp_path):
    """From Python (``main([...])``) the process is the caller's: it may use dask after the command."""
    (tmp_path / "s.toml").write_text(SCENE)
    code = (
        "import gc\nthresholds = gc.get_threshold()\nfrom wecss.cli import main\n"
        "report = {'status': main(['run', 's.toml', '-o', 'r.nc', '-q']), 'before': list(thresholds)}"
    )
    out = _in_fresh_process(code, tmp_path)
    assert out["status"] == 0 and "dask.array" in out["loaded"]
    assert out["thresholds"] == out["before"] and out["frozen"] == 0


@needs_dask
def test_an_import_of_dask_kept_out_fails_and_says_why(tmp_path):
    code = (
        "from wecss.dask_free import keep_dask_out, refusal_hint\n"
        "kept = keep_dask_out()\n"
        "try:\n    import dask.array\n    hint = None\nexcept ImportError as err:\n    hint = refusal_hint(err)\n"
        "report = {'kept': kept, 'hint': hint}"
    )
    out = _in_fresh_process(code, tmp_path)
    assert out["kept"] is True and out["loaded"] == []
    assert out["hint"] == "dask is kept out of this command's process (xarray would import it for nothing)"


@needs_dask
def test_after_xarray_was_imported_dask_is_not_kept_out(tmp_path):
    """xarray decides whether dask is installed when it is imported: hiding it afterwards would break xarray."""
    (tmp_path / "s.toml").write_text(SCENE)
    code = (
        "import xarray\nfrom wecss.dask_free import keep_dask_out\nkept = keep_dask_out()\n"
        f"{_command('run', 's.toml', '-o', 'r.nc', '-q')}\nreport['kept'] = kept"
    )
    out = _in_fresh_process(code, tmp_path)
    assert out["kept"] is False and out["status"] == 0 and (tmp_path / "r.nc").is_file()


@needs_dask
def test_dask_imported_already_is_not_kept_out(tmp_path):
    code = (
        "import dask\nfrom wecss.dask_free import keep_dask_out\nkept = keep_dask_out()\n"
        "import dask.array\nreport = {'kept': kept}"
    )
    out = _in_fresh_process(code, tmp_path)
    assert out["kept"] is False and "dask.array" in out["loaded"]


NEEDS_DASK = """
import dask

from wecss_controllers import LinearDamping


class NeedsDask(LinearDamping):
    \"\"\"Linear damping from a package that imports dask.\"\"\"
"""


@needs_dask
def test_a_run_whose_controller_imports_dask_says_to_allow_it(tmp_path):
    """A plugin that imports dask under ``wecss run`` is an error that says to give ``--allow-dask``; with it
    the run goes."""
    plugin = write_distribution(
        tmp_path, "wecss.controllers", "needs-dask", "needs_dask_plugin", "NeedsDask", NEEDS_DASK
    )
    (tmp_path / "s.toml").write_text(SCENE + '[controller]\nname = "needs-dask"\n')
    env = {**os.environ, "PYTHONPATH": f"{ROOT}{os.pathsep}{plugin}", "WECSS_JIT": "0"}
    command = [sys.executable, "-m", "wecss.cli", "run", "s.toml", "-o", "r.nc", "-q"]
    refused = subprocess.run(command, env=env, cwd=tmp_path, capture_output=True, text=True)
    assert refused.returncode == 2 and not (tmp_path / "r.nc").exists()
    assert "import of dask halted" in refused.stderr and "give run --allow-dask" in refused.stderr
    allowed = subprocess.run([*command, "--allow-dask"], env=env, cwd=tmp_path, capture_output=True, text=True)
    assert allowed.returncode == 0, allowed.stderr
    assert (tmp_path / "r.nc").is_file()


def test_a_sweep_process_is_left_as_python_sets_it_up(tmp_path):
    """``wecss sweep`` may run for hours and use dask: neither dask nor the garbage collector is changed."""
    code = (
        "import gc\nfrom wecss import command_process, dask_free\nbefore = list(gc.get_threshold())\n"
        "command_process.enter('sweep')\nreport = {'before': before, 'kept': dask_free.dask_kept_out()}"
    )
    out = _in_fresh_process(code, tmp_path)
    assert out["thresholds"] == out["before"] and out["kept"] is False
