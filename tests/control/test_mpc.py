"""Model predictive control (issue 14): it reaches the complex-conjugate bound's closed form as its horizon grows,
its limits hold in every step, its two solver paths give the same forces, and a failed solve falls back and is
counted."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import compile_scene
from wecss.control.mpc import CvxpyPath, OsqpPath, Solution
from wecss.sim import Scene, simulate
from wecss_controllers import MPC

FLOAT = Path(__file__).with_name("heaving_float.toml")  # the M4 stern float on a vertical slider
M4_111 = Path(__file__).parents[2] / "wecss" / "data" / "devices" / "m4-111.toml"
PERIOD = 1.0


def _float_scene(parameters: dict) -> Scene:
    return Scene.from_dict(
        {
            "device": {"name": str(FLOAT)},
            # a regular wave: the mean over the final 10 T is that over the final 30 T of a 60 T run (measured ratios
            # to the bound 0.53165 and 0.99865 against 0.53165 and 0.99869)
            "sea": {"kind": "regular", "height": 0.01, "period": PERIOD, "duration": "20 T", "ramp": "5 T"},
            "controller": {"name": "mpc", "dt": 0.05, "parameters": parameters},
            "solver": {"method": "linear"},
            "radiation": {"method": "state_space"},
            "outputs": {"variables": ["pto"], "window": 0.5},
        }
    )


def test_with_a_longer_horizon_mpc_reaches_the_complex_conjugate_bound():
    """Regular wave, no limits, perfect preview: |F|^2 / (8 B) from the database (not from the control code)
    within 1 % at a horizon of 40 periods (2 s); clearly below it at 5 (0.25 s)."""
    compiled = compile_scene(_float_scene({"preview": "perfect"}))
    hydro, omega = compiled.hydro, 2 * np.pi / PERIOD
    k = list(hydro.dofs).index("float_3__Heave")
    b = np.interp(omega, hydro.omega, hydro.dataset.radiation_damping.values[:, k, k])
    bound = abs(compiled.excitation.coefficients[k, 0]) ** 2 / (8 * b)
    power = {
        n: float(simulate(_float_scene({"preview": "perfect", "horizon": n, "force_penalty": 1e-3})).mean_pto_power[0])
        for n in (5, 40)
    }
    assert power[40] == pytest.approx(bound, rel=0.01)
    assert power[5] < 0.7 * bound


def _limited_m4_111(tmp_path: Path, **limits: float) -> str:
    path = tmp_path / "m4-111-limited.toml"
    path.write_text(M4_111.read_text().rstrip() + "\n" + "".join(f"{k} = {v}\n" for k, v in limits.items()))
    return str(path)


@pytest.mark.parametrize("preview", ["perfect", "causal"])
def test_the_force_limit_holds_exactly_and_the_stroke_within_its_slack(tmp_path, preview):
    """m4-111 in the linear simulator with a torque limit of 1 N m and a stroke limit of 0.08 rad (the free MPC
    run reaches 3.4 N m and 0.14 rad): the torque never passes its limit, and at the control instants the stroke
    stays within the limit plus the largest slack the programme used, up to 5 % of the limit for the prediction's
    error (estimation, the excitation's interpolation)."""
    force, stroke = 1.0, 0.08
    device = _limited_m4_111(tmp_path, force_limit=force, stroke_limit=stroke, end_stop_stiffness=50.0)
    control = {"name": "mpc", "dt": 0.06, "parameters": {"preview": preview, "horizon": 20}}
    kw = {"solver": {"method": "linear"}, "radiation": {"method": "state_space"}, "outputs": {"variables": ["pto"]}}
    sea = {"height": 0.02, "duration": 30.0, "ramp": 2.4}
    ds = simulate(scene(device, sea=sea, controller=control, **kw))
    assert np.max(np.abs(ds.pto_torque.values)) <= force
    slack = float(ds.attrs["controller_largest_stroke_slack"])
    at_control = ds.pto_angle.values[:: round(0.06 / ds.attrs["time_step"]), 0]
    assert np.max(np.abs(at_control)) <= stroke * (1 + slack + 0.05)
    assert ds.attrs["controller_fallbacks"] == 0
    unlimited = {"name": "mpc", "dt": 0.06, "parameters": {"preview": "perfect", "horizon": 20}}
    free = simulate(scene("m4-111", sea=sea, controller=unlimited, **kw))
    assert np.max(np.abs(free.pto_angle.values)) > 1.5 * stroke  # the limits bind
    assert np.max(np.abs(free.pto_torque.values)) > 1.5 * force


class _RecordingPath:
    """The controller's own solver path, keeping every programme it was given and its solution."""

    def __init__(self, inner: OsqpPath) -> None:
        self.inner, self.given, self.solutions = inner, [], []

    def solve(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> Solution:
        solution = self.inner.solve(q, lower, upper)
        self.given.append((q.copy(), lower.copy(), upper.copy()))
        self.solutions.append(solution)
        return solution


class _RecordingMPC(MPC):
    def reset(self):  # type: ignore[no-untyped-def]
        super().reset()
        self.path = _RecordingPath(self.path)  # type: ignore[arg-type]


def test_direct_osqp_and_cvxpy_give_the_same_forces(tmp_path):
    """The programmes of a run on m4-111 with its limits binding (torque 1 N m, stroke 0.08 rad, rate 20 N m/s):
    OSQP directly, cvxpy with OSQP and cvxpy with Clarabel (an interior-point method: an independent solver) plan
    the same forces to 5e-4 of the force limit; and whole runs with either path agree to 1e-3 of it."""
    device = _limited_m4_111(tmp_path, force_limit=1.0, stroke_limit=0.08, end_stop_stiffness=50.0)
    kw = {"solver": {"method": "linear"}, "radiation": {"method": "state_space"}, "outputs": {"variables": ["pto"]}}
    sea = {"height": 0.02, "duration": 12.0, "ramp": 1.2}
    controller = _RecordingMPC(preview="perfect", horizon=15, rate_limit=20.0)
    simulate(scene(device, sea=sea, controller={"name": "mpc", "dt": 0.06}, **kw), controller=controller)
    recorded = controller.path
    assert isinstance(recorded, _RecordingPath)
    qp = controller.qp
    others = [CvxpyPath(qp), CvxpyPath(qp, solver="CLARABEL")]
    bound = 0
    for given, solution in list(zip(recorded.given, recorded.solutions, strict=True))[::4]:
        assert solution.x is not None, solution.status
        planned = qp.forces(solution.x)
        bound += int(np.any(np.abs(np.abs(planned) - 1.0) < 1e-6))
        for other in others:
            again = other.solve(*given)
            assert again.x is not None, again.status
            # OSQP (ADMM) stops on its residuals (1e-9): its forces are within 4e-4 N m of Clarabel's here
            np.testing.assert_allclose(qp.forces(again.x), planned, atol=5e-4)
    assert bound >= 3  # some of the compared programmes sit on the torque limit
    run = {}
    for solver in ("osqp", "cvxpy"):
        control = {"name": "mpc", "dt": 0.06, "parameters": {"preview": "perfect", "horizon": 10, "solver": solver}}
        run[solver] = simulate(scene(device, sea={**sea, "duration": 6.0}, controller=control, **kw))
    np.testing.assert_allclose(run["cvxpy"].pto_torque.values, run["osqp"].pto_torque.values, atol=1e-3)


class _FailingPath:
    """A solver path whose every third solve fails (as an infeasible or unsolved programme would)."""

    def __init__(self, inner: OsqpPath) -> None:
        self.inner, self.calls, self.failed = inner, 0, 0

    def solve(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> Solution:
        self.calls += 1
        if self.calls % 3 == 0:
            self.failed += 1
            return Solution(None, "infeasible (forced by the test)", 0.0)
        return self.inner.solve(q, lower, upper)


class _FailingMPC(MPC):
    def reset(self):  # type: ignore[no-untyped-def]
        super().reset()
        self.path = _FailingPath(self.path)  # type: ignore[arg-type]


@pytest.mark.parametrize("method", ["linear", "beeman"])
def test_a_failed_solve_falls_back_and_is_counted(method):
    """Every third solve fails: the run goes on with the last plan, counts each fallback, and still absorbs
    power."""
    controller = _FailingMPC(preview="perfect", horizon=15)
    sc = scene("m4-111", sea={"height": 0.02, "duration": 6.0, "ramp": 1.2},
               controller={"name": "mpc", "dt": 0.06}, solver={"method": method},
               radiation={"method": "state_space"}, outputs={"variables": ["pto"]})  # fmt: skip
    ds = simulate(sc, controller=controller)
    assert isinstance(controller.path, _FailingPath)
    assert controller.path.failed >= 30
    assert ds.attrs["controller_fallbacks"] == controller.path.failed
    assert "fallbacks = " in ds.attrs["notes"]
    assert float(ds.mean_pto_power[0]) > 0


def test_bad_parameters_are_refused_with_what_is_accepted():
    for kwargs, message in (
        ({"horizon": 0}, "horizon must be a whole number"),
        ({"preview": "oracle"}, "preview must be one of"),
        ({"efficiency": 1.5}, r"efficiency must lie in \(0, 1\]"),
        ({"solver": "gurobi"}, "solver must be one of"),
        ({"sequential_solves": 0, "efficiency": 0.7}, "sequential_solves must be an integer >= 1"),
        ({"sequential_solves": 2}, "applies to the electrical objective only"),
        ({"rate_limit": -1.0}, "rate_limit must be positive"),
        ({"radiation_error": 1.0}, r"radiation_error must lie in \[0, 1\)"),
    ):
        with pytest.raises(ValueError, match=message):
            MPC(**kwargs)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"radiation\.method = 'state_space'"):
        simulate(scene("m4-111", controller={"name": "mpc", "dt": 0.06}, radiation={"method": "convolution"}))


def test_the_reduced_plan_converges_to_the_full_one():
    """m4-111, perfect preview, linear simulator: the plan's radiation memory reduced by balanced truncation keeps
    far fewer states, and the run's mean power approaches the full model's as the allowed error shrinks (measured:
    1.2 % off at 1e-2 with 60 of 350 states, 0.05 % at 1e-3 with 93)."""
    sc = scene("m4-111", sea={"height": 0.02, "duration": 12.0, "ramp": 1.2},
               controller={"name": "mpc", "dt": 0.06}, solver={"method": "linear"},
               radiation={"method": "state_space"}, outputs={"variables": ["pto"]})  # fmt: skip
    runs = {}
    for error in (0.0, 0.01, 0.001):
        controller = MPC(preview="perfect", horizon=20, radiation_error=error)
        runs[error] = (simulate(sc, controller=controller), controller)
    full = runs[0.0][1].radiation_states
    assert full[0] == full[1] == runs[0.001][1].radiation_states[0]
    assert runs[0.01][1].radiation_states[1] < runs[0.001][1].radiation_states[1] < 0.3 * full[0]
    for error in (0.01, 0.001):
        assert runs[error][1].radiation_measured_error <= error
    assert "balanced truncation" in runs[0.001][0].attrs["controller_radiation_states"]
    power = {e: float(ds.mean_pto_power.sum()) for e, (ds, _) in runs.items()}
    gaps = {e: abs(power[e] / power[0.0] - 1) for e in (0.01, 0.001)}
    assert gaps[0.001] < 0.002
    assert gaps[0.01] < 0.02


def test_a_reused_controller_plans_as_a_fresh_one():
    """One MPC object run on two sea states in turn (its build kept only for the same plant and sea) absorbs
    exactly what a new object does in each."""
    reused = MPC(preview="perfect", horizon=10)
    for height in (0.02, 0.03, 0.02):
        sc = scene("m4-111", sea={"height": height, "duration": 6.0, "ramp": 1.2},
                   controller={"name": "mpc", "dt": 0.06}, solver={"method": "linear"},
                   radiation={"method": "state_space"}, outputs={"variables": ["pto"]})  # fmt: skip
        again = simulate(sc, controller=reused).pto_torque.values
        fresh = simulate(sc, controller=MPC(preview="perfect", horizon=10)).pto_torque.values
        np.testing.assert_array_equal(again, fresh)


def _causal_run(device: str, method: str, sea: dict, hydro: str | None = None) -> float:
    """Mean absorbed power [W] of causal MPC at force penalty 0.01 (horizon 30, T = Tp/20, dt = Tp/200)."""
    period = sea["period"]
    sc = Scene.from_dict(
        {
            "device": {"name": device, **({"hydro": hydro} if hydro else {})},
            "sea": {"kind": "jonswap", "gamma": 3.3, "seed": 1, "ramp": 5 * period, **sea},
            "controller": {"name": "mpc", "dt": period / 20},
            "solver": {"method": method, "dt": period / 200},
            "radiation": {"method": "state_space"},
            "outputs": {"variables": ["pto"]},
        }
    )
    return float(simulate(sc, controller=MPC(preview="causal", force_penalty=0.01)).mean_pto_power.sum())


def test_causal_mpc_at_a_low_force_penalty_runs_on_in_the_nonlinear_simulator():
    """m4-111, JONSWAP Hs 0.04 m, Tp 1.2 s, force penalty 0.01: with the predictor fitted without a ridge the
    nonlinear run diverged within 2 s of the ramp's end (a hinge past 1.5 rad); now 10 s complete and absorb power."""
    assert _causal_run("m4-111", "beeman", {"height": 0.04, "period": 1.2, "duration": 10.0}) > 0.1


@pytest.mark.slow
def test_causal_mpc_at_a_low_force_penalty_is_stable_in_the_nonlinear_simulator():
    """m4-111, JONSWAP Hs 0.04 m, Tp 1.2 s, 24 s, force penalty 0.01: causal MPC diverged in the nonlinear simulator
    within 2 s when its AR predictor was fitted without a ridge (it amplified the estimate's error, the linear-
    nonlinear mismatch among it: ``test_a_ridge_keeps_the_predictor_from_amplifying_the_estimates_error``); now the
    run completes and absorbs within 5 % of the linear simulator's power (measured 428.7 against 445.3 mW, -3.7 %;
    perfect preview -0.7 %; at Hs 0.02 m -0.4 %)."""
    sea = {"height": 0.04, "period": 1.2, "duration": 24.0}
    power = {method: _causal_run("m4-111", method, sea) for method in ("linear", "beeman")}
    assert power["linear"] > 0.3
    assert power["beeman"] == pytest.approx(power["linear"], rel=0.05), power


WAMIT = Path(__file__).resolve().parents[3] / "shared" / "data" / "wamit"


@pytest.mark.slow
@pytest.mark.parametrize(
    ("device", "sea", "hydro", "gap"),
    [
        ("m4-132", {"height": 0.04, "period": 1.2}, None, 0.01),
        ("m4-134", {"height": 0.04, "period": 1.2}, None, 0.01),
        ("wavestar", {"height": 0.0625, "period": 1.412}, "wavestar/wavestar.out", 0.05),
        ("rm3", {"height": 2.0, "period": 8.0}, "rm3/rm3.out", 0.05),
    ],
)
def test_causal_mpc_at_a_low_force_penalty_is_stable_on_the_catalogue(device, sea, hydro, gap):
    """Causal MPC at force penalty 0.01 over 20 peak periods in the nonlinear simulator against the linear one
    (measured gaps: m4-132 +0.01 %, m4-134 -0.3 %, rm3 +0.7 %, the Wavestar in WECCCOMP sea state 5 -4.4 %: short of
    the 1 % sought, 27 % without the estimator's stroke offset). notc-10kw is left out: there even perfect-preview
    MPC takes its arm past 1.5 rad in the nonlinear simulator (no stroke limit in its spec)."""
    if hydro is not None and not (WAMIT / hydro).exists():
        pytest.skip(f"no {WAMIT / hydro}")
    sea = {**sea, "duration": 20 * sea["period"]}
    path = None if hydro is None else str(WAMIT / hydro)
    power = {method: _causal_run(device, method, sea, path) for method in ("linear", "beeman")}
    assert power["linear"] > 0
    assert power["beeman"] == pytest.approx(power["linear"], rel=gap), power
