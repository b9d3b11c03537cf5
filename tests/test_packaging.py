"""The built-in controllers import as ``wecss_controllers`` from the folder ``controllers/`` (issue 31): a top-level
package named ``controllers`` was shadowed by any user folder or module of that name on ``sys.path`` (the
working directory of ``python -c`` or a notebook comes first), and the default scene then failed with an
AttributeError loading the ``damping`` entry point. pyproject.toml lists the packages (a mapped package is not found
by ``packages.find``): the list is held to the source tree here."""

from __future__ import annotations

import importlib.metadata
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def test_the_listed_packages_are_the_source_trees():
    setuptools = PYPROJECT["tool"]["setuptools"]
    found = {".".join(p.parent.relative_to(ROOT).parts) for p in (ROOT / "wecss").rglob("__init__.py")}
    assert set(setuptools["packages"]) == found | {"wecss_controllers"}
    assert setuptools["package-dir"] == {"wecss_controllers": "controllers"}
    assert PYPROJECT["tool"]["mypy"]["files"] == ["wecss", "controllers"]  # mypy reads folders


def test_every_builtin_entry_point_names_the_renamed_package():
    declared = PYPROJECT["project"]["entry-points"]["wecss.controllers"]
    assert {v.partition(":")[0] for v in declared.values()} == {"wecss_controllers"}
    installed = {ep.name: ep.value for ep in importlib.metadata.entry_points(group="wecss.controllers")}
    for name, value in declared.items():  # the metadata this process runs with says the same (reinstall if not)
        assert installed.get(name) == value, f"installed entry point {name} = {installed.get(name)}: pip install -e ."


RUN = """
import sys
from wecss.cli import main
sys.exit(main(["run", "--set", "sea.duration=12.0", "--set", "sea.ramp=1.2", "-o", "out.nc", "-q"]))
"""


@pytest.mark.parametrize("shadow", ["package", "module"])
def test_the_default_scene_runs_beside_a_users_controllers_folder(tmp_path, shadow):
    """``python -c`` puts its working directory first on ``sys.path``: a ``controllers`` package or module there
    hid the built-ins (AttributeError: module 'controllers' has no attribute 'LinearDamping')."""
    if shadow == "package":
        (tmp_path / "controllers").mkdir()
        (tmp_path / "controllers" / "__init__.py").write_text('"""A user\'s own controllers."""\n')
    else:
        (tmp_path / "controllers.py").write_text('"""A user\'s own controllers."""\n')
    out = subprocess.run([sys.executable, "-c", RUN], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "AttributeError" not in out.stderr
    assert (tmp_path / "out.nc").is_file()
