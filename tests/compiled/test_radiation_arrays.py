"""The radiation memory as the simulator applies it, against closed forms of a known state-space kernel."""

from __future__ import annotations

import numpy as np
import pytest

from tests.radiation.analytic import analytic_hydro, known_system, response
from wecss.compiled import added_mass_correction, from_impulse_response, from_state_space, weighted_memory_response
from wecss.compiled import memory_response as frequency_response
from wecss.radiation import RadiationStateSpace, impulse_response
from wecss.sim._memory import memory_advance, memory_history


def test_state_space_arrays_have_the_model_response():
    a, b, c = known_system()
    model = RadiationStateSpace(a, b, c, ("p__Heave", "q__Heave"))
    arrays, summary = from_state_space(model, 0.01)
    omega = np.linspace(0.1, 20.0, 50)
    np.testing.assert_allclose(frequency_response(arrays, omega, 0.01), response(a, b, c, omega), rtol=1e-10, atol=1e-9)
    assert summary.states == 3  # one complex state per conjugate pair


def test_first_order_hold_is_exact_for_a_velocity_linear_in_time():
    """z' = lambda z + b u with u = alpha + beta t: the step update must equal the exact solution."""
    a, b, c = known_system()
    model = RadiationStateSpace(a, b, c, ("p__Heave", "q__Heave"))
    h = 0.05
    arrays, _ = from_state_space(model, h)
    alpha, beta = np.array([0.3, -0.2]), np.array([1.0, 0.5])
    z = np.zeros(arrays.poles.size, dtype=complex)
    buf, pos = np.zeros((2, 2)), np.zeros(1, dtype=np.int64)
    steps = 40
    for n in range(steps):
        u0, u1 = alpha + beta * n * h, alpha + beta * (n + 1) * h
        force = memory_history(arrays, z, u0, buf, 0) + arrays.newest @ u1
        memory_advance(arrays, z, u0, u1, buf, pos)
    # exact: the memory force -int_0^T K(s) u(T - s) ds of the known kernel, by fine quadrature
    t_end = steps * h
    s = np.linspace(0.0, t_end, 200001)
    kernel = model.kernel(s)
    u = alpha[None] + beta[None] * (t_end - s)[:, None]
    exact = -np.trapezoid(np.einsum("tij,tj->ti", kernel, u), s, axis=0)
    np.testing.assert_allclose(force, exact, rtol=1e-6)


@pytest.mark.parametrize(("coarse_step", "fine_memory"), [(0.01, 3.0), (0.06, 3.0), (0.06, 1e3)])
def test_convolution_arrays_reproduce_the_kernel_response(coarse_step, fine_memory):
    """Also with no coarse tail at all (every lag fine: the wavestar's short memory crashed the response)."""
    hydro = analytic_hydro()
    irf = impulse_response(hydro)
    dt = 0.01
    arrays, summary = from_impulse_response(irf, dt, coarse_step=coarse_step, fine_memory=fine_memory)
    assert (fine_memory < 100) or not np.any(arrays.coarse_length)
    omega = np.linspace(0.5, 12.0, 40)
    a, b, c = known_system()
    exact = response(a, b, c, omega)
    got = frequency_response(arrays, omega, dt)
    scale = np.max(np.abs(exact))
    assert np.max(np.abs(got - exact)) <= 5e-3 * scale
    assert summary.entries == 4 and not summary.dropped_entries


@pytest.mark.parametrize("coarse_step", [0.01, 0.06])
def test_the_loop_convolution_applies_the_arrays_response(coarse_step):
    """Drive a sinusoid through memory_history / memory_advance (the ring buffer wraps many times) and compare the
    force with -Re[K_hat U exp(i omega t)] from frequency_response: the buffer indexing and the arrays agree."""
    hydro = analytic_hydro()
    dt = 0.01
    arrays, _ = from_impulse_response(impulse_response(hydro), dt, coarse_step=coarse_step)
    omega, amplitude = 3.0, np.array([1.0, 0.4 - 0.3j])
    buf = np.zeros((2, 2 * arrays.depth))
    pos = np.zeros(1, dtype=np.int64)
    z = np.zeros(0, dtype=complex)
    steps = 3 * arrays.depth + 17
    for n in range(steps):
        u_now = np.real(amplitude * np.exp(1j * omega * n * dt))
        u_new = np.real(amplitude * np.exp(1j * omega * (n + 1) * dt))
        force = memory_history(arrays, z, u_now, buf, int(pos[0])) + arrays.newest @ u_new
        memory_advance(arrays, z, u_now, u_new, buf, pos)
    k_hat = frequency_response(arrays, np.array([omega]), dt)[0]
    expected = -np.real(k_hat @ amplitude * np.exp(1j * omega * steps * dt))
    np.testing.assert_allclose(force, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())


@pytest.mark.parametrize("kind", ["state_space", "convolution"])
def test_weighted_memory_response_is_the_weighted_sum_of_the_responses(kind):
    """Summed over frequencies first (the A_inf correction of long runs): the same as the sum of the responses, over
    more frequencies than one block."""
    hydro = analytic_hydro()
    dt = 0.01
    if kind == "state_space":
        a, b, c = known_system()
        arrays, _ = from_state_space(RadiationStateSpace(a, b, c, tuple(hydro.dofs)), dt)
    else:
        arrays, _ = from_impulse_response(impulse_response(hydro), dt)
    omega = np.linspace(0.3, 15.0, 2500)
    weights = np.random.default_rng(3).uniform(-1.0, 2.0, omega.size)
    expected = np.einsum("w,wij->ij", weights, frequency_response(arrays, omega, dt))
    got = weighted_memory_response(arrays, omega, weights, dt)
    np.testing.assert_allclose(got, expected, rtol=1e-11, atol=1e-11 * np.abs(expected).max())


def test_added_mass_correction_recovers_an_offset_in_a_inf():
    """Data whose A_inf is off by a constant: the correction is that constant."""
    hydro = analytic_hydro()
    a, b, c = known_system()
    arrays, _ = from_state_space(RadiationStateSpace(a, b, c, tuple(hydro.dofs)), 0.01)
    ds = hydro.dataset
    offset = np.array([[3.0, 0.5], [0.5, -2.0]])
    omega = hydro.omega[20:200:6]  # on the data's frequencies: no interpolation error
    correction = added_mass_correction(
        arrays, 0.01, hydro.omega, ds.added_mass.values, ds.added_mass_inf.values - offset, omega, np.ones(omega.size)
    )
    np.testing.assert_allclose(correction, offset, atol=1e-6)


def test_band_limited_kernel_keeps_the_band_and_drops_the_rest():
    hydro = analytic_hydro()
    full = impulse_response(hydro)
    band = impulse_response(hydro, band=(10.0, 20.0), tail=False)
    # below the roll-off the transforms agree; K(0) loses the content above it
    weights = np.full(full.time.size, full.dt)
    weights[[0, -1]] *= 0.5
    omega = np.array([2.0, 5.0, 8.0])
    phase = np.exp(-1j * np.outer(omega, full.time)) * weights
    for w_i, row in enumerate(phase):
        f = np.tensordot(row, full.kernel, axes=(0, 0))
        g = np.tensordot(row, band.kernel, axes=(0, 0))
        assert np.abs(f.real - g.real).max() <= 0.02 * np.abs(f.real).max(), omega[w_i]
    assert band.band == (10.0, 20.0)
    # the content above the roll-off is gone: K(0) = (2/pi) int B is smaller by the part beyond 10 rad/s
    assert np.all(np.diag(band.kernel[0]) < np.diag(full.kernel[0]))
    with pytest.raises(ValueError, match="band must be"):
        impulse_response(hydro, band=(20.0, 10.0), tail=False)


def test_interpolate_matrices_equals_numpy_interp_entry_by_entry():
    """The vectorised interpolation against np.interp on every entry, inside, on and outside the data's range."""
    from wecss.compiled import interpolate_matrices

    rng = np.random.default_rng(3)
    for n in (1, 2, 40):
        omega_data = np.unique(rng.uniform(0.1, 10.0, n))
        values = rng.normal(size=(omega_data.size, 3, 3))
        omega = np.concatenate([rng.uniform(0.0, 12.0, 300), omega_data, [0.0, 12.0]])
        flat = values.reshape(omega_data.size, -1)
        expected = np.stack([np.interp(omega, omega_data, flat[:, k]) for k in range(9)], axis=-1)
        np.testing.assert_allclose(
            interpolate_matrices(omega_data, values, omega), expected.reshape(omega.size, 3, 3), rtol=1e-15, atol=0
        )
