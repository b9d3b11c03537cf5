"""The controller interface in both simulators: a controller object passed to simulate(), the measurement it asks
for (state, excitation preview, elevation) exactly as the run has it, refusals before the run, and PTO limits
that act and are reported (issue 13)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import ControlContext, Controller, Measurement, compile_scene
from wecss.sim import PtoLimitExceeded, SceneError, simulate
from wecss_controllers import LinearDamping

M4_111 = Path(__file__).resolve().parents[2] / "wecss" / "data" / "devices" / "m4-111.toml"


class Recorder(Controller):
    """Damping 6 N m s/rad held over each control period; keeps every measurement it is given."""

    def __init__(self, needs_state=False, preview_horizon=None, elevation_at=None, damping=6.0):
        self.needs_state = needs_state
        self.preview_horizon = preview_horizon
        self.elevation_at = elevation_at
        self.damping = damping
        self.seen: list[tuple[float, Measurement]] = []
        self.context: ControlContext | None = None

    def setup(self, context: ControlContext) -> None:
        self.context = context
        self.seen = []

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        self.seen.append((t, measurement))
        return -self.damping * measurement.velocity


def _scene(method="beeman", **sea):
    radiation = "state_space"
    sea = {"kind": "jonswap", "height": 0.02, "period": 1.2, "duration": 6.0, "ramp": 1.2, **sea}
    return scene("m4-111", sea=sea, solver={"method": method}, radiation={"method": radiation},
                 outputs={"variables": ["motion", "pto"]})  # fmt: skip


@pytest.mark.parametrize("method", ["beeman", "rk4", "linear"])
def test_a_controller_object_gets_the_state_and_the_preview_exactly(method):
    controller = Recorder(needs_state=True, preview_horizon=0.024, elevation_at=(0.5, 0.0))
    compiled = compile_scene(_scene(method), controller)
    ds = simulate(_scene(method), controller=controller)
    assert ds.attrs["controller_class"].endswith("Recorder") and len(controller.seen) == ds.time.size - 1
    nq = compiled.q0.size
    angles = ds.angle.values
    for k in (0, 7, len(controller.seen) - 1):
        t, m = controller.seen[k]
        assert t == pytest.approx(ds.time.values[k], abs=1e-12)
        # the generalised coordinates at the call: the recorded angles at that step (joint coordinates here)
        names = [*ds.dof_linear.values, *ds.dof_angular.values]
        q = np.concatenate([ds.displacement.values[k], angles[k]])
        order = [names.index(n) for n in compiled.device.model.coordinate_names]
        np.testing.assert_allclose(m.state[:nq], q[order], rtol=0, atol=1e-12)
        v = np.concatenate([ds.velocity.values[k], ds.angular_velocity.values[k]])
        np.testing.assert_allclose(m.state[nq : 2 * nq], v[order], rtol=0, atol=1e-12)
        times = t + 0.006 * np.arange(1, 5)
        np.testing.assert_allclose(m.preview_times, times, rtol=0, atol=1e-12)
        np.testing.assert_allclose(m.preview, compiled.excitation.force(times).T, rtol=1e-12, atol=1e-12)
        assert m.elevation is not None
    # the elevation at x = 0.5 m: the wave components shifted by their wavenumber, with the ramp
    t, m = controller.seen[-1]
    waves = compiled.waves
    k = waves.omega**2 / 9.81 if np.isinf(compiled.hydro.water_depth) else None
    if k is not None:
        expected = np.real(np.sum(waves.amplitude * np.exp(1j * (waves.omega * t - k * 0.5))))
        assert m.elevation == pytest.approx(expected, rel=1e-9, abs=1e-12)


def test_what_a_controller_declares_is_checked_before_the_run():
    with pytest.raises(SceneError, match=r"preview_horizon 0\.01 s must be a whole number"):
        compile_scene(_scene(), Recorder(preview_horizon=0.01))
    with pytest.raises(TypeError, match="needs_state must be True or False"):
        compile_scene(_scene(), Recorder(needs_state="yes"))
    with pytest.raises(TypeError, match="is not a wecss controller"):
        simulate(_scene(), controller=object())  # type: ignore[arg-type]


def _limited_device(tmp_path, **limits) -> str:
    text = M4_111.read_text()  # its last table is the PTO's
    extra = "".join(f"{k} = {v}\n" for k, v in limits.items())
    path = tmp_path / "m4-111-limited.toml"
    path.write_text(text.rstrip() + "\n" + extra)
    return str(path)


@pytest.mark.parametrize("method", ["beeman", "linear"])
def test_a_force_limit_saturates_and_is_counted(tmp_path, method):
    device = _limited_device(tmp_path, force_limit=0.05)
    sc = scene(device, sea={"height": 0.04, "duration": 12.0, "ramp": 1.2}, solver={"method": method},
               radiation={"method": "state_space"}, outputs={"variables": ["pto"]})  # fmt: skip
    ds = simulate(sc)
    torque = ds.pto_torque.values  # controller force (the device has no spring)
    assert np.max(np.abs(torque)) <= 0.05 * (1 + 1e-9)
    assert ds.force_limit_time.values[0] > 0 and ds.force_limit_episodes.values[0] >= 2
    free = simulate(scene("m4-111", sea={"height": 0.04, "duration": 12.0, "ramp": 1.2}, solver={"method": method},
                          radiation={"method": "state_space"}, outputs={"variables": ["pto"]}))  # fmt: skip
    assert np.max(np.abs(free.pto_torque.values)) > 0.1  # the limit did act
    assert float(free.force_limit_time.values[0]) == 0.0


@pytest.mark.parametrize("method", ["beeman", "linear"])
def test_an_end_stop_keeps_the_stroke_near_its_limit(tmp_path, method):
    """Half the free run's largest hinge angle as the limit: an end stop of stiffness k_s lets the stroke pass the
    limit by at most its impact compliance v_max sqrt(M_hh / k_s) (the free run's largest rate, the hinge's mass
    term: the kinetic energy taken up by the stop's spring), less for a stiffer stop; without one the run stops."""
    sea = {"height": 0.08, "duration": 12.0, "ramp": 1.2}
    kw = {"solver": {"method": method}, "radiation": {"method": "state_space"}, "outputs": {"variables": ["pto"]}}
    free = simulate(scene("m4-111", sea=sea, **kw))
    limit = 0.5 * float(np.max(np.abs(free.pto_angle.values)))
    rate = float(np.max(np.abs(free.pto_angular_velocity.values)))
    model = compile_scene(scene("m4-111", sea=sea, **kw)).control_context.linear_model()
    k = int(np.argmax(np.abs(model.pto_jacobian[0])))
    passed = []
    for stiffness in (2e3, 2e4):
        device = _limited_device(
            tmp_path, stroke_limit=limit, end_stop_stiffness=stiffness, end_stop_damping=0.01 * stiffness
        )
        ds = simulate(scene(device, sea=sea, **kw))
        passed.append(float(np.max(np.abs(ds.pto_angle.values))) - limit)
        assert 0 < passed[-1] <= rate * np.sqrt(model.mass[k, k] / stiffness)
        assert ds.stroke_limit_time.values[0] > 0 and ds.stroke_limit_episodes.values[0] >= 2
    assert passed[1] < 0.5 * passed[0]
    stop = _limited_device(tmp_path, stroke_limit=limit)
    with pytest.raises(PtoLimitExceeded, match="passed its stroke_limit"):
        simulate(scene(stop, sea=sea, **kw))


def test_the_device_limits_reach_the_context():
    controller = Recorder()
    compile_scene(_scene(), controller)
    assert controller.context is not None and controller.context.force_limit == (np.inf,)
    assert controller.context.pto_kinds == ("rotary",)
    model = controller.context.linear_model()
    np.testing.assert_array_equal(model.pto_damping, [0.0])
    np.testing.assert_array_equal(controller.context.linear_model(damping=6.0).pto_damping, [6.0])
    assert isinstance(LinearDamping(), Controller)


def test_the_frequency_domain_says_it_does_not_apply_limits(tmp_path):
    device = _limited_device(tmp_path, force_limit=0.05)
    sc = scene(device, sea={"height": 0.04, "duration": 12.0, "ramp": 1.2}, solver={"method": "frequency"},
               outputs={"variables": ["pto"]})  # fmt: skip
    ds = simulate(sc)
    reach = float(np.max(np.abs(ds.pto_torque.values))) / 0.05
    assert (
        ds.attrs["pto_limits"].startswith("not applied")
        and f"{reach:.3g} and 0 of their limits" in ds.attrs["pto_limits"]
    )
