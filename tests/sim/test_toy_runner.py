"""A new integrator is one module: a toy runner (the semi-implicit Euler method, first order), defined in this file
alone and registered at run time, runs every scene the built-ins run (every output group, streamed to a file,
controllers with and without linear gains) and converges to the reference solution at its order."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
import xarray as xr

from tests.sim.scenes import HeldDamping, scene
from wecss.compiled.kernels import configure, integrate_configuration, respond
from wecss.scene import Capabilities, SceneError, available_runners, register_runner, unregister_runner
from wecss.sim import simulate
from wecss.sim.runners import (
    Chunk,
    FixedStepRunner,
    LoopStatus,
    block_history,
    memory_advance,
    record_step,
)


class SemiImplicitEuler(FixedStepRunner):
    """v_{n+1} = v_n + h a_n, q_{n+1} = q_n + h v_{n+1}; a_{n+1} at the new state with the memory force there."""

    name = "toy-euler"
    description = "semi-implicit Euler (a test's toy)"
    capabilities = Capabilities(streaming=True, order=1)

    def advance(self, prepared: Any, chunk: Chunk) -> tuple[int, int]:
        p, r, excitation, command, step0, settings, state, out, work = chunk
        h = settings.h
        q, v, acc, z, u_now, buf, pos, far = (
            state.q,
            state.v,
            state.acc,
            state.z,
            state.u_now,
            state.buf,
            state.pos,
            state.far,
        )
        for k in range(excitation.shape[0] - 1):
            n1 = step0 + k + 1
            hist = block_history(r, z, u_now, buf, pos[0], far, (n1 - 1) % far.shape[0])
            v1 = v + h * acc
            q1 = integrate_configuration(p, q, h * v1)
            if not configure(p, q1, excitation[k + 1] + hist, (step0 + k + 1) * h, work):
                return LoopStatus.NOT_FINITE, n1
            respond(p, v1, r.newest, command, work)
            if not (np.all(np.isfinite(work.acc)) and np.all(np.isfinite(q1))):
                return LoopStatus.NOT_FINITE, n1
            rad = hist + r.newest @ work.u
            memory_advance(r, z, u_now, work.u, buf, pos)
            u_now[:] = work.u
            q[:], v[:], acc[:] = q1, v1, work.acc
            state.pto_now[0], state.pto_now[1], state.pto_now[2] = work.stroke, work.xdot, work.f
            record_step(
                out, n1, p, (q, v, acc, work.stroke.copy(), work.xdot.copy(), work.f.copy(), rad, excitation[k + 1])
            )
        return LoopStatus.OK, step0 + excitation.shape[0] - 1


@pytest.fixture
def toy():
    runner = register_runner(SemiImplicitEuler())
    yield runner
    unregister_runner(runner.name)


def _scene(method: str, dt: str, **sections: Any):
    return scene(
        "m4-111",
        solver={"method": method, "dt": dt},
        sea={"kind": "regular", "height": 0.02, "period": 1.2, "duration": 6.0, "ramp": 2.0},
        **sections,
    )


def test_the_toy_runner_is_a_runner_like_the_builtins(toy, tmp_path):
    assert "toy-euler" in available_runners()
    groups = {"outputs": {"variables": ["motion", "pto", "excitation", "radiation", "elevation", "poses", "loads"]}}
    ds = simulate(_scene("toy-euler", "Tp/200", **groups))
    beeman = simulate(_scene("beeman", "Tp/200", **groups))
    assert set(ds.variables) == set(beeman.variables)
    assert ds.attrs["solver"] == "toy-euler"
    # streamed to a file as the built-in fixed-step runners are
    streamed = simulate(_scene("toy-euler", "Tp/200"), path=tmp_path / "toy.nc")
    whole = simulate(_scene("toy-euler", "Tp/200"))
    xr.testing.assert_allclose(streamed.angle.load(), whole.angle, rtol=0, atol=0)
    streamed.close()
    # a controller without linear gains, called per step and held
    held = simulate(_scene("toy-euler", "Tp/200"), controller=HeldDamping())
    assert np.all(np.isfinite(held.pto_power.values))


def test_the_toy_runner_converges_at_first_order(toy):
    reference = simulate(
        _scene("reference", "Tp/400", radiation={"method": "state_space"}, outputs={"variables": ["motion"]})
    )
    errors = []
    for divisor in (400, 800):
        toy_run = simulate(_scene("toy-euler", f"Tp/{divisor}", outputs={"variables": ["motion"]}))
        stride = divisor // 400
        angle = toy_run.angle.values[::stride]
        errors.append(np.max(np.abs(angle - reference.angle.values)))
    order = np.log2(errors[0] / errors[1])
    assert 0.8 < order < 1.3, f"errors {errors}, observed order {order:.2f}"


def test_an_unknown_method_lists_the_registered_runners(toy):
    with pytest.raises(SceneError, match="toy-euler"):
        _scene("euler", "Tp/200")


def test_a_runner_refuses_what_it_does_not_declare(toy):
    with pytest.raises(SceneError, match=r"solver\.hold applies to solver\.method 'linear' only"):
        scene("m4-111", solver={"method": "toy-euler", "hold": "zoh"})
