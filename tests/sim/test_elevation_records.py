"""Measured elevation records in a scene (``sea.kind = "elevation"``, ``sea.file``): NaN or inf values, too few
samples, non-uniform or decreasing times and records shorter than the run are refused before any work, naming the
file, what was received and what is accepted; a good record runs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from wecss.scene import SceneError
from wecss.sim import Scene, compile_scene

DT = 0.05  # s


def _record(tmp_path: Path, n: int = 400, name: str = "eta.txt") -> tuple[Path, np.ndarray]:
    t = np.arange(n) * DT
    eta = 0.01 * np.sin(2 * np.pi * t / 1.2) + 0.005 * np.sin(2 * np.pi * t / 0.9 + 1.0)
    table = np.column_stack([t, eta])
    path = tmp_path / name
    np.savetxt(path, table)
    return path, table


def _scene(path: Path, duration: float = 15.0, ramp: float = 2.0) -> Scene:
    return Scene.from_dict(
        {
            "device": {"name": "m4-111"},
            "sea": {"kind": "elevation", "file": str(path), "period": 1.2, "duration": duration, "ramp": ramp},
            "radiation": {"method": "none"},
        }
    )


def _write(path: Path, table: np.ndarray) -> Path:
    np.savetxt(path, table)
    return path


def test_a_good_record_compiles(tmp_path):
    path, _ = _record(tmp_path)
    compiled = compile_scene(_scene(path, duration=400 * DT))
    assert compiled.waves is not None and compiled.waves.repeat_period == pytest.approx(400 * DT)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda t: t.__setitem__((7, 1), np.nan), r"elevation has 1 values that are not finite numbers .* samples 8"),
        (lambda t: t.__setitem__((slice(3, 10), 1), np.inf), r"elevation has 7 values .* samples 4, 5, 6, 7, 8 \.\.\."),
        (lambda t: t.__setitem__((0, 0), np.nan), r"time has 1 values that are not finite"),
        (
            lambda t: t.__setitem__((200, 0), t[200, 0] + 0.3 * DT),
            r"the record must be sampled uniformly in time: the step is 0\.05 s",
        ),
        (lambda t: t.__setitem__((200, 0), t[198, 0]), r"time must increase: sample 201"),
    ],
)
def test_bad_values_are_refused_naming_the_file(tmp_path, change, message):
    path, table = _record(tmp_path)
    change(table)
    _write(path, table)
    with pytest.raises(SceneError, match=rf"sea\.file '{path}' \(time \[s\], elevation \[m\]\): {message}"):
        compile_scene(_scene(path))


def test_too_few_samples_are_refused(tmp_path):
    path, _ = _record(tmp_path, n=3)
    with pytest.raises(SceneError, match=rf"sea\.file '{path}'.*the record has 3 samples; at least 4 are needed"):
        compile_scene(_scene(path, duration=0.1, ramp=0.0))


def test_a_record_shorter_than_the_run_is_refused(tmp_path):
    path, _ = _record(tmp_path, n=200)  # 10 s
    with pytest.raises(
        SceneError, match=r"the record spans 10 s \(200 samples every 0\.05 s\) but sea\.duration is 15 s.*<= 10 s"
    ):
        compile_scene(_scene(path, duration=15.0))


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "holds no numbers; needs two columns"),
        ("0.0 0.1\n0.05 abc\n", "cannot read two columns of numbers"),
        ("0 1 2\n0.05 1 2\n", r"needs two columns \(time \[s\], elevation \[m\]\); found 3"),
    ],
)
def test_unreadable_records_are_refused(tmp_path, text, message):
    path = tmp_path / "eta.txt"
    path.write_text(text)
    with pytest.raises(SceneError, match=rf"sea\.file '{path}'.*{message}"):
        compile_scene(_scene(path))
