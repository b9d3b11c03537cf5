"""The streamed stress field of the NOTC arm (its StressModes from the device catalogue) against the whole-record
path: the stress array of every point, ``rainflow_cycles``, ``miner_damage`` and ``life_years`` per point, to 1e-12
relative; extremes, RMS and kept series; the life map plot; bad inputs."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr

from wecss.devices import load
from wecss.results import (
    StressFieldRecorder,
    life_years,
    miner_damage,
    open_result,
    plot_life_map,
    rainflow_cycles,
    save,
)
from wecss.structure import default_points, stress_modes

pytest.importorskip("rainflow")

RTOL = 1e-12


@pytest.fixture(scope="module")
def arm():  # type: ignore[no-untyped-def]
    return load("notc-10kw").flexible_body("arm")


def synthetic_run(modes, n: int, dt: float, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # type: ignore[no-untyped-def]
    """Modal coordinates of sinusoids at three wave periods plus noise, scaled so each mode alone gives up to
    ~10 MPa (those that stress the arm little, less); their accelerations; rigid-motion loads of gravity and small
    accelerations."""
    rng = np.random.default_rng(seed)
    t = np.arange(n)[:, None] * dt
    n_modes = modes.normal.shape[1]
    peak = np.abs(modes.normal).max(axis=0)  # [Pa per 1]; the axial and torsion modes stress the arm little
    scale = 10e6 / np.maximum(peak, 1e-2 * peak.max())
    q = np.zeros((n, n_modes))
    q_ddot = np.zeros((n, n_modes))
    for period in (6.0, 8.5, 11.0):
        omega = 2 * np.pi / period
        a = scale * rng.uniform(0.05, 0.4, n_modes)
        phase = rng.uniform(0, 2 * np.pi, n_modes)
        q += a * np.sin(omega * t + phase)
        q_ddot -= omega**2 * a * np.sin(omega * t + phase)
    q += 0.02 * scale * rng.normal(size=(n, n_modes))
    rigid = np.zeros((n, 12))
    rigid[:, 2] = -9.81 + 0.5 * np.sin(2 * np.pi * t[:, 0] / 8.5)
    rigid[:, :6] += 0.05 * rng.normal(size=(n, 6))
    return q, q_ddot, rigid


def test_streamed_field_equals_the_whole_record_path(arm):
    modes = arm.stresses
    n, dt = 2000, 0.05
    q, q_ddot, rigid = synthetic_run(modes, n, dt, seed=1)
    keep = ["arm.lug_top", "arm@2.4.fibre4"]
    recorder = StressFieldRecorder(modes, dt, keep=keep, every=3)
    rng = np.random.default_rng(2)
    i = 0
    while i < n:
        k = int(rng.integers(0, 500))
        recorder.update(q[i : i + k], q_ddot[i : i + k], rigid[i : i + k])
        i += k
    ds = recorder.result()

    signed = modes.stresses(q, q_ddot, rigid)["signed_von_mises"]  # (n, n_point): the whole field
    duration = (n - 1) * dt
    damage = np.array([miner_damage(rainflow_cycles(signed[:, p])) for p in range(signed.shape[1])])
    life = np.array([life_years(d, duration) for d in damage])
    assert np.all(damage > 0)
    np.testing.assert_allclose(ds.damage.values, damage, rtol=RTOL, atol=0.0)
    np.testing.assert_allclose(ds.life_years.values, life, rtol=RTOL, atol=0.0)
    # the products of a chunk and of the whole record may round apart (BLAS blocks by size): 1e-12 of the peak
    atol = RTOL * np.abs(signed).max()
    np.testing.assert_allclose(ds.signed_von_mises_max.values, signed.max(axis=0), rtol=0.0, atol=atol)
    np.testing.assert_allclose(ds.signed_von_mises_min.values, signed.min(axis=0), rtol=0.0, atol=atol)
    np.testing.assert_allclose(ds.von_mises_rms.values, np.sqrt(np.mean(signed**2, axis=0)), rtol=RTOL, atol=0.0)
    columns = [recorder.names.index(k) for k in keep]
    np.testing.assert_allclose(ds.signed_von_mises_series.values, signed[::3, columns], rtol=0.0, atol=atol)
    np.testing.assert_allclose(ds.series_time.values, 3 * dt * np.arange(ds.sizes["series_time"]))

    assert list(ds.point.values[:2]) == ["arm.lug_top", "arm.lug_bottom"]
    assert ds.sizes["point"] == len(modes.points) == 138
    assert set(ds.member.values) == {"arm"}
    assert ds.life_years.attrs["units"] == "year" and ds.damage.attrs["units"] == "1"
    assert ds.signed_von_mises_max.attrs["units"] == "Pa" and ds.station.attrs["units"] == "m"
    assert ds.attrs["duration"] == duration and ds.attrs["sn_curve"] == "paper-003-table-5"


def test_modal_coordinates_alone_and_an_unstressed_record(arm):
    modes = arm.stresses
    q, _, _ = synthetic_run(modes, 600, 0.1, seed=3)
    recorder = StressFieldRecorder(modes, 0.1)
    recorder.update(q[:250])
    recorder.update(q[250:])
    signed = modes.stresses(q)["signed_von_mises"]
    expected = [miner_damage(rainflow_cycles(signed[:, p])) for p in range(signed.shape[1])]
    np.testing.assert_allclose(recorder.result().damage.values, expected, rtol=RTOL, atol=0.0)

    still = StressFieldRecorder(modes, 0.1)
    still.update(np.zeros((50, modes.normal.shape[1])))
    ds = still.result()
    assert np.all(ds.damage.values == 0.0) and np.all(np.isinf(ds.life_years.values))


def test_life_map_plots_on_the_frame_and_on_member_axes(arm, tmp_path):
    modes = arm.stresses
    q, q_ddot, rigid = synthetic_run(modes, 800, 0.05, seed=4)
    recorder = StressFieldRecorder(modes, 0.05)
    recorder.update(q, q_ddot, rigid)
    ds = recorder.result()
    for frame, name in ((arm.frame, "frame.png"), (None, "axes.png")):
        fig = plot_life_map(ds, tmp_path / name, frame=frame)
        try:
            assert (tmp_path / name).stat().st_size > 10_000
            texts = [t.get_text() for t in fig.axes[0].texts]
            worst = str(ds.point.values[int(np.argmin(ds.life_years.values))])
            assert any(t.startswith(worst) for t in texts)
        finally:
            plt.close(fig)
    still = StressFieldRecorder(modes, 0.05)
    still.update(np.zeros((10, modes.normal.shape[1])))
    fig = plot_life_map(still.result(), tmp_path / "still.png")
    plt.close(fig)
    with pytest.raises(ValueError, match="plane must be one of"):
        plot_life_map(ds, plane="xw")
    with pytest.raises(ValueError, match="not a stress field"):
        plot_life_map(ds.drop_vars("life_years"))


def test_the_field_round_trips_through_netcdf(arm, tmp_path):
    q, q_ddot, rigid = synthetic_run(arm.stresses, 300, 0.05, seed=5)
    recorder = StressFieldRecorder(arm.stresses, 0.05, keep=["arm.lug_top"], every=2)
    recorder.update(q, q_ddot, rigid)
    ds = recorder.result()
    save(ds, tmp_path / "field.nc")
    back = open_result(tmp_path / "field.nc")
    xr.testing.assert_identical(back, ds)


def test_points_without_distinct_names_get_their_place_in_the_name(arm):
    modes = stress_modes(arm.frame, arm.basis.basis, default_points(arm.frame)[:16])
    recorder = StressFieldRecorder(modes, 0.1)
    assert recorder.names[:2] == ["arm@0.fibre0", "arm@0.fibre1"]
    assert len(set(recorder.names)) == 16


def test_bad_inputs_say_what_is_accepted(arm):
    modes = arm.stresses
    n_modes = modes.normal.shape[1]
    recorder = StressFieldRecorder(modes, 0.1)
    with pytest.raises(ValueError, match=rf"q must be \(n, {n_modes}\)"):
        recorder.update(np.zeros((4, n_modes + 1)))
    with pytest.raises(ValueError, match=r"rigid must be \(4, 12\)"):
        recorder.update(np.zeros((4, n_modes)), rigid=np.zeros((4, 6)))
    with pytest.raises(ValueError, match="NaN"):
        recorder.update(np.full((2, n_modes), np.nan))
    with pytest.raises(ValueError, match="at least two samples"):
        recorder.result()
    with pytest.raises(ValueError, match="dt must be"):
        StressFieldRecorder(modes, 0.0)
    with pytest.raises(ValueError, match="not among"):
        StressFieldRecorder(modes, 0.1, keep=["nowhere"])
    with pytest.raises(ValueError, match="every must be"):
        StressFieldRecorder(modes, 0.1, every=0)
    with pytest.raises(ValueError, match="StressModes"):
        StressFieldRecorder(arm, 0.1)  # type: ignore[arg-type]
