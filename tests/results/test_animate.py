"""The animation of a run's bodies: frames read back from the GIF follow the data; refusals."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from wecss.results import animate, check_animation
from wecss.results._animate import COLOURS, rotation_matrices

STEPS = 24


def _poses(heave_amplitude: float = 1.0) -> xr.Dataset:
    """Two bodies: the first at x = 0 heaving 1 m, the second at x = 3 m still but pitching."""
    t = np.linspace(0.0, 2.3, STEPS)
    position = np.zeros((STEPS, 2, 3))
    position[:, 0, 2] = heave_amplitude * np.sin(2 * np.pi * t / 2.3)
    position[:, 1, 0] = 3.0
    rotation = np.zeros((STEPS, 2, 3))
    rotation[:, 1, 1] = 0.3 * np.sin(2 * np.pi * t / 2.3)
    coords = {"time": t, "body": ["a", "b"], "axis": ["x", "y", "z"]}
    dims = ("time", "body", "axis")
    return xr.Dataset(
        {
            "body_position": (dims, position, {"units": "m"}),
            "body_rotation": (dims, rotation, {"units": "rad"}),
            "wave_elevation": ("time", 0.2 * np.cos(t)),
        },
        coords=coords,
    )


def _centroids(path, colour: str) -> list[tuple[float, float]]:  # type: ignore[no-untyped-def]
    """Per frame, the centroid (column, row) of the pixels of ``colour`` in the left 40 % of the side view."""
    from PIL import Image

    target = np.array([int(colour[k : k + 2], 16) for k in (1, 3, 5)])
    out = []
    with Image.open(path) as movie:
        for k in range(movie.n_frames):
            movie.seek(k)
            rgb = np.asarray(movie.convert("RGB"), dtype=int)
            side = rgb[: rgb.shape[0] // 2, : int(rgb.shape[1] * 0.4)]
            rows, cols = np.nonzero(np.all(np.abs(side - target) < 40, axis=-1))
            assert rows.size > 10, f"frame {k}: the body's dot is not drawn"
            out.append((float(cols.mean()), float(rows.mean())))
    return out


def test_the_drawn_dot_of_a_heaving_body_follows_its_heave(tmp_path):  # type: ignore[no-untyped-def]
    from PIL import Image

    ds = _poses()
    path = animate(ds, tmp_path / "bodies.gif", stride=3, fps=10, progress=None)
    with Image.open(path) as movie:
        assert movie.n_frames == 8  # 24 steps, every 3rd
    centroids = _centroids(path, COLOURS[0])
    heave = ds.body_position.values[::3, 0, 2]
    rows = np.array([row for _, row in centroids])
    slope, offset = np.polyfit(heave, rows, 1)
    assert slope < 0  # z up: a higher body is a smaller row
    assert np.max(np.abs(rows - (offset + slope * heave))) < 1.0  # within a pixel of a straight line
    assert np.ptp([col for col, _ in centroids]) < 1.0  # no surge in the data, none drawn


def test_rotation_matrices_turn_the_body_x_axis_by_the_pitch():
    pitch = 0.3
    axis = rotation_matrices(np.array([0.0, pitch, 0.0]))[:, 0]
    np.testing.assert_allclose(axis, [np.cos(pitch), 0.0, -np.sin(pitch)], atol=1e-15)  # nose down for +pitch


def test_refusals(tmp_path):  # type: ignore[no-untyped-def]
    ds = _poses()
    with pytest.raises(ValueError, match=r"no body poses \(body_rotation missing\).*'poses' output group"):
        check_animation(ds.drop_vars("body_rotation"))
    with pytest.raises(ValueError, match="stride must be a whole number of saved steps >= 1; got 0"):
        check_animation(ds, stride=0)
    with pytest.raises(ValueError, match="stride 24 leaves one frame"):
        check_animation(ds, stride=24)
    with pytest.raises(ValueError, match=r"fps must be a whole number of frames per second >= 1; got 0\.5"):
        check_animation(ds, fps=0.5)  # type: ignore[arg-type]
    assert check_animation(xr.concat([ds] * 10, "time")) == 2  # 240 steps: at most 150 frames
    with pytest.raises(ValueError, match=r"must end in .gif or .mp4; got '.*bodies.avi'"):
        animate(ds, tmp_path / "bodies.avi")


def test_mp4_without_ffmpeg_is_refused(tmp_path, monkeypatch):  # type: ignore[no-untyped-def]
    from matplotlib import animation

    monkeypatch.setattr(animation.writers, "is_available", lambda name: False)
    with pytest.raises(ValueError, match="needs ffmpeg on the PATH"):
        animate(_poses(), tmp_path / "bodies.mp4")
    assert not (tmp_path / "bodies.mp4").exists()


def test_a_progress_line_once_writing_takes_long(tmp_path, monkeypatch):  # type: ignore[no-untyped-def]
    import io

    from wecss.results import _animate

    monkeypatch.setattr(_animate, "PROGRESS_AFTER_S", 0.0)
    stream = io.StringIO()
    animate(_poses(), tmp_path / "b.gif", stride=6, progress=stream)
    assert stream.getvalue().endswith("\rframe 4/4\n")
