"""Exact runs in modal coordinates: closed forms, the matrix exponential of the augmented system, and the cases the
modal form must refuse."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.linear._modal_recursion import BLOCK_STEPS, ModalForm, NotDiagonalisable, outputs, run


def test_free_integrator_follows_the_closed_form():
    """x' = v, v' = -v + u with u = 1 (ZOH) or u = t (FOH, exact for a ramp) from rest: x is free (no state depends
    on it), v a real mode; both follow the closed forms to round-off, over several blocks."""
    a = np.array([[0.0, 1.0], [0.0, -1.0]])
    b = np.array([[0.0], [1.0]])
    form = ModalForm.of(a)
    assert form.free.tolist() == [0] and form.n_modes == 1
    dt = 0.01
    t = dt * np.arange(3 * BLOCK_STEPS + 7)
    y = run(form, form.steps(b, dt, "zoh"), np.ones((t.size, 1)), np.eye(2))
    np.testing.assert_allclose(y[:, 1], -np.expm1(-t), rtol=0, atol=1e-13)
    np.testing.assert_allclose(y[:, 0], t + np.expm1(-t), rtol=0, atol=1e-12)
    y = run(form, form.steps(b, dt, "foh"), t[:, None], np.eye(2))
    # v' = -v + t: v = t - 1 + e^-t, x = t^2/2 - t + 1 - e^-t
    np.testing.assert_allclose(y[:, 1], t + np.expm1(-t), rtol=0, atol=1e-12)
    np.testing.assert_allclose(y[:, 0], t**2 / 2 - t - np.expm1(-t), rtol=0, atol=1e-11)


def test_a_jordan_block_without_a_free_state_is_refused():
    with pytest.raises(NotDiagonalisable, match="condition number"):
        ModalForm.of(np.array([[-1.0, 1.0], [0.0, -1.0]]))


@pytest.mark.parametrize("hold", ["foh", "zoh"])
def test_modal_run_of_m4_134_equals_the_matrix_exponential_step(hold):
    """The linear model of m4-134 (free surge, 414 states): the modal run driven by generalised forces against the
    dense step x_{k+1} = Phi x_k + G0 u_k + G1 u_{k+1} from the exponential of the augmented system, with the model's
    own inputs (hydro forces and PTO forces), from a non-zero state, across block boundaries."""
    from tests.linear.test_model import _compiled
    from wecss.sim import linearize

    model = linearize(_compiled("m4-134"))
    nv, n_h = model.mass.shape[0], model.hydro_jacobian.shape[0]
    dt, n = 0.006, BLOCK_STEPS + 300
    t = dt * np.arange(n)
    rng = np.random.default_rng(5)
    m = model.state_space.ninputs
    u = np.sin(np.outer(t, rng.uniform(2.0, 8.0, m)) + rng.uniform(0, 2 * np.pi, m)) * rng.uniform(1, 20, m)
    x0 = np.zeros(model.n_states)
    x0[: 2 * nv] = rng.normal(scale=1e-3, size=2 * nv)
    phi, g0, g1 = model.discretise(dt, hold)
    x = np.empty((n, model.n_states))
    x[0] = x0
    for k in range(n - 1):
        x[k + 1] = phi @ x[k] + g0 @ u[k] + g1 @ u[k + 1]
    force = u[:, :n_h] @ model.hydro_jacobian + u[:, n_h:] @ model.pto_jacobian
    form = model.modal_form
    assert form.free.tolist() == [0]  # the surge displacement
    select = np.eye(model.n_states)[: 2 * nv]
    y = run(form, model.modal_steps(dt, hold), force, select, x0)
    scale = np.max(np.abs(x[:, : 2 * nv]), axis=0)
    assert np.max(np.abs(y - x[:, : 2 * nv]) / scale) <= 1e-9
    # the radiation states too, through outputs() on the modal coordinates
    z = np.array([form.inverse @ xk[form.rest] for xk in x[:5]])
    np.testing.assert_allclose(outputs(form, np.eye(model.n_states), z, x[:5, form.free]), x[:5], atol=1e-12)


@pytest.mark.parametrize("s", [1e-9, 0.003 - 0.02j, 0.0999, 0.1001, -0.7 + 3j, -25.0 + 0.5j])
def test_phi_functions_equal_their_integrals(s):
    """phi_j(s) = int_0^1 e^{(1 - t) s} t^(j - 1) / (j - 1)! dt, by quadrature, on both sides of the series switch."""
    import math

    from scipy.integrate import quad

    from wecss.compiled.kernels import phi_functions

    values = phi_functions(np.array([s]))
    for j, value in zip((1, 2, 3), values, strict=True):

        def part(t, f, j=j):
            return f(np.exp((1 - t) * s) * t ** (j - 1) / math.factorial(j - 1))

        exact = quad(part, 0, 1, args=(np.real,), epsabs=0, epsrel=1e-13)[0]
        exact += 1j * quad(part, 0, 1, args=(np.imag,), epsabs=0, epsrel=1e-13)[0]
        assert abs(value[0] - exact) <= 1e-12 * abs(exact)


def test_recursion_without_numba_equals_the_compiled_one():
    """The numpy recursion (the path without numba) against the compiled one, and both against complex
    arithmetic step by step, on decaying and oscillating modes over many steps."""
    from wecss.linear._modal_recursion import _numpy_recursion, shifted_recursion

    rng = np.random.default_rng(5)
    n_modes, n = 9, 300
    decay = np.exp(-rng.uniform(0.0, 0.05, n_modes) + 1j * rng.uniform(-1.0, 1.0, n_modes))
    forcing = rng.normal(size=(n, 2 * n_modes))
    s0 = rng.normal(size=2 * n_modes)
    expected = np.empty((n + 1, n_modes), dtype=complex)
    expected[0] = s0[:n_modes] + 1j * s0[n_modes:]
    for k in range(n):
        expected[k + 1] = decay * expected[k] + forcing[k, :n_modes] + 1j * forcing[k, n_modes:]
    for recursion in (_numpy_recursion, shifted_recursion):
        out = np.empty((n + 1, 2 * n_modes))
        recursion(decay, forcing, s0, out)
        np.testing.assert_allclose(out[:, :n_modes] + 1j * out[:, n_modes:], expected, rtol=1e-12, atol=1e-12)
