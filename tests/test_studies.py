"""The study scripts as a set: each takes a bare ``--quick`` (CI runs every ``studies/[a-z]*.py`` that way, through
``studies/_quick.py``), ``studies/README.md`` lists each, and the runner stops at the first failing study and names
it. The scripts' argument parsers are read with ``ast``; no study runs here."""

from __future__ import annotations

import ast
import importlib.util
import re
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parent.parent
STUDIES = sorted((ROOT / "studies").glob("[a-z]*.py"))


def _arguments(path: Path) -> Iterator[ast.Call]:
    """Every ``<parser>.add_argument(...)`` call of a script."""
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "add_argument":
            yield node


def _keyword(call: ast.Call, name: str) -> object:
    for keyword in call.keywords:
        if keyword.arg == name:
            return ast.literal_eval(keyword.value) if isinstance(keyword.value, ast.Constant) else keyword.value
    return None


def _flags(call: ast.Call) -> list[str]:
    return [a.value for a in call.args if isinstance(a, ast.Constant) and isinstance(a.value, str)]


def _load(path: Path) -> ModuleType:
    """A study script as a module (its folder on ``sys.path`` for its bare-name imports, as when it runs)."""
    spec = importlib.util.spec_from_file_location(f"_study_{path.stem}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.path.insert(0, str(path.parent))
    try:
        spec.loader.exec_module(module)
    finally:
        sys.path.remove(str(path.parent))
    return module


def test_the_studies_are_found():
    assert len(STUDIES) >= 18
    assert not any(path.name.startswith("_") for path in STUDIES)


def _bare_quick_problems(path: Path) -> list[str]:
    """Why ``python <path> --quick`` would not parse: no ``--quick`` switch, an option marked required, or a
    positional argument that must be given."""
    calls = list(_arguments(path))
    quick = [call for call in calls if "--quick" in _flags(call)]
    problems = [] if len(quick) == 1 else [f"{path.name} declares --quick {len(quick)} times"]
    if quick and _keyword(quick[0], "action") != "store_true":
        problems.append(f"{path.name}: --quick is not a switch (action='store_true')")
    for call in calls:
        flags = _flags(call)
        if _keyword(call, "required") is True:
            problems.append(f"{path.name}: {flags[0]} is required")
        if flags and not flags[0].startswith("-") and _keyword(call, "nargs") not in ("*", "?"):
            problems.append(f"{path.name}: the positional {flags[0]} must be given")
    return problems


@pytest.mark.parametrize("path", STUDIES, ids=lambda p: p.stem)
def test_every_study_takes_a_bare_quick_flag(path: Path) -> None:
    """``python studies/X.py --quick`` is what CI runs: ``--quick`` is a switch and nothing else must be given."""
    assert _bare_quick_problems(path) == []


def test_the_check_finds_a_study_without_a_bare_quick(tmp_path: Path) -> None:
    script = tmp_path / "made_up.py"
    head = "import argparse\np = argparse.ArgumentParser()\n"
    script.write_text(head + "p.add_argument('--quick', action='store_true')\np.add_argument('names', nargs='+')\n")
    assert _bare_quick_problems(script) == ["made_up.py: the positional names must be given"]
    script.write_text(head + "p.add_argument('--quick', type=int)\np.add_argument('--out', required=True)\n")
    assert _bare_quick_problems(script) == [
        "made_up.py: --quick is not a switch (action='store_true')",
        "made_up.py: --out is required",
    ]
    script.write_text(head + "p.add_argument('--fast', action='store_true')\n")
    assert _bare_quick_problems(script) == ["made_up.py declares --quick 0 times"]


def test_the_studies_readme_lists_every_study_and_no_other():
    text = (ROOT / "studies" / "README.md").read_text()
    headings = set(re.findall(r"^### `([a-z]\w*\.py)`", text, flags=re.MULTILINE))
    assert headings == {path.name for path in STUDIES}
    for path in STUDIES:
        assert f"python studies/{path.name} --quick" in text, f"the README does not say how to run {path.name}"


def test_generate_hydro_quick_alone_makes_every_database_coarse(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    study = _load(ROOT / "studies" / "generate_hydro.py")
    made: list[tuple[str, bool]] = []
    monkeypatch.setattr(study, "generate", lambda name, folder, quick, n_jobs: made.append((name, quick)))
    assert study.main(["--quick", "--output-dir", str(tmp_path)]) == 0
    assert made == [(name, True) for name in study.available()] and len(made) >= 4
    made.clear()
    assert study.main(["m4-111", "--quick", "--output-dir", str(tmp_path)]) == 0
    assert made == [("m4-111", True)]
    with pytest.raises(SystemExit):  # a full run needs --all or names
        study.main(["--output-dir", str(tmp_path)])


def _fake_studies(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[ModuleType, Path, str]:
    """The study runner pointed at ``tmp_path``, the folder where each fake study leaves a file named after it when
    it runs, and the body of such a study (it checks its arguments are a bare ``--quick``)."""
    runner = _load(ROOT / "studies" / "_quick.py")
    monkeypatch.setattr(runner, "STUDIES", tmp_path)
    ran = tmp_path / "ran"
    ran.mkdir()
    body = "import sys\nfrom pathlib import Path\nassert sys.argv[1:] == ['--quick']\n"
    body += f"Path({str(ran)!r}, Path(__file__).stem).touch()\n"
    return runner, ran, body


def test_the_runner_runs_every_study_and_stops_at_the_first_failure_naming_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    runner, ran, body = _fake_studies(tmp_path, monkeypatch)
    (tmp_path / "a_first.py").write_text(body)
    (tmp_path / "b_fails.py").write_text(body + "sys.exit(3)\n")
    (tmp_path / "c_after.py").write_text(body)
    (tmp_path / "_helper.py").write_text(body)
    assert [p.name for p in runner.studies()] == ["a_first.py", "b_fails.py", "c_after.py"]
    assert runner.main([]) == 1
    assert sorted(p.name for p in ran.iterdir()) == ["a_first", "b_fails"]
    assert "b_fails.py --quick failed (exit status 3)" in capsys.readouterr().err
    (tmp_path / "b_fails.py").write_text(body)
    assert runner.main([]) == 0
    assert sorted(p.name for p in ran.iterdir()) == ["a_first", "b_fails", "c_after"]
    assert "(3 studies)" in capsys.readouterr().out


def test_the_runner_with_two_jobs_fills_a_free_place_at_once_prints_in_name_order_and_starts_none_after_a_failure(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    runner, ran, body = _fake_studies(tmp_path, monkeypatch)
    # the first study ends last (it waits until c has started, then a second more, for c's failure to be seen): its
    # output must still come first, and whole
    wait = (
        "import time\nstart = time.monotonic()\n"
        f"while not Path({str(ran)!r}, 'c_fails').exists() and time.monotonic() - start < 60:\n"
        "    time.sleep(0.05)\ntime.sleep(1.0)\n"
    )
    (tmp_path / "a_slow.py").write_text(body + wait + "print('a line one')\nprint('a line two')\n")
    (tmp_path / "b_quick.py").write_text(body + "print('b says')\n")
    (tmp_path / "c_fails.py").write_text(body + "print('c says', file=sys.stderr)\nsys.exit(4)\n")
    (tmp_path / "d_next.py").write_text(body)
    (tmp_path / "e_never.py").write_text(body)
    assert runner.main(["--jobs", "2"]) == 1
    captured = capsys.readouterr()
    out = captured.out
    assert out.index("a_slow.py --quick\na line one\na line two\n") < out.index("b_quick.py --quick\nb says\n")
    assert out.index("b says") < out.index("c_fails.py --quick\nc says")
    assert "c_fails.py --quick failed (exit status 4)" in captured.err
    # a and b take the two places, c takes b's as soon as b ends (a still sleeping): c's failure starts nothing
    # more (d never runs), and a, which started before c, ends and is printed first
    assert sorted(p.name for p in ran.iterdir()) == ["a_slow", "b_quick", "c_fails"]
    assert "d_next.py --quick" not in out
    (tmp_path / "c_fails.py").write_text(body)
    assert runner.main(["--jobs", "2"]) == 0
    assert sorted(p.name for p in ran.iterdir()) == ["a_slow", "b_quick", "c_fails", "d_next", "e_never"]
    assert "of wall time, 2 at once" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        runner.main(["--jobs", "0"])
