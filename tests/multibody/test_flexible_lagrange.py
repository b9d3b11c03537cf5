"""The planar flexible pendulum: self-checks of the independent sympy Lagrange oracle (``flexible_lagrange``), and the
MFM floating-frame flexible body (``wecss.multibody.ElasticBody``) against it."""

from __future__ import annotations

import importlib

import numpy as np
import pytest
from scipy.integrate import solve_ivp

pytest.importorskip("sympy")

from .flexible_lagrange import (  # after the sympy guard
    EI,
    LENGTH,
    MASS_PER_LENGTH,
    G,
    pendulum_accelerations,
    pendulum_accelerations_exact,
    pendulum_energy,
    pendulum_invariants,
    pendulum_mass_matrix,
)

PARAMS = {"length": LENGTH, "mass_per_length": MASS_PER_LENGTH, "ei": EI, "g": G}
TOL = 1e-12  # the relative tolerance (max norm); do not loosen


def _random_states(count: int = 20, seed: int = 28) -> list[tuple[np.ndarray, np.ndarray]]:
    """Seeded states: theta in [-pi, pi], xi in [-0.05, 0.05] m, rates in [-2, 2]."""
    rng = np.random.default_rng(seed)
    return [
        (
            np.array([rng.uniform(-np.pi, np.pi), *rng.uniform(-0.05, 0.05, 2)]),
            rng.uniform(-2.0, 2.0, 3),
        )
        for _ in range(count)
    ]


def _large_states(count: int = 6, seed: int = 2828) -> list[tuple[np.ndarray, np.ndarray]]:
    """Large deformation, |xi| in [0.2, 0.4] m (tip deflection up to ~0.8 m of a 2 m beam): the terms quadratic
    in xi (theta_dot^2 xi, the deformed inertia) are of order one here."""
    rng = np.random.default_rng(seed)
    states = [(np.array([0.7, 0.3, -0.3]), np.array([1.5, -0.8, 1.1])), (np.array([-2.0, 0.3, 0.3]), np.ones(3))]
    for _ in range(count - len(states)):
        xi = rng.uniform(0.2, 0.4, 2) * rng.choice([-1.0, 1.0], 2)
        states.append((np.array([rng.uniform(-np.pi, np.pi), *xi]), rng.uniform(-2.0, 2.0, 3)))
    return states


# --- the oracle itself --------------------------------------------------------------------------------------------


def test_closed_form_accelerations_match_an_exact_solve():
    """The lambdified closed-form accelerations against the symbolic M and h solved in 40-digit arithmetic."""
    for q, v in _random_states(2) + _large_states(2):
        exact = pendulum_accelerations_exact(q, v, **PARAMS)
        got = pendulum_accelerations(q, v, **PARAMS)
        assert np.abs(got - exact).max() <= 1e-14 * max(1.0, np.abs(exact).max())


def test_energy_is_conserved():
    """T + V along a 2 s DOP853 solve (rtol 1e-12) with large deflection and rates, no damping."""

    def rhs(_, y):
        return np.concatenate([y[3:], pendulum_accelerations(y[:3], y[3:], **PARAMS)])

    y0 = np.array([0.4, 0.08, -0.05, 1.0, -0.5, 0.7])
    sol = solve_ivp(rhs, (0.0, 2.0), y0, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=False)
    assert sol.success
    energy = np.array([pendulum_energy(y[:3], y[3:], **PARAMS) for y in sol.y.T])
    scale = max(abs(energy[0]), 1.0)
    assert np.abs(energy - energy[0]).max() <= 1e-9 * scale
    assert np.abs(sol.y[1:3]).max() > 0.05  # the modes did move (the check is not vacuous)


@pytest.mark.parametrize("theta", [0.0, 0.3, -1.2, 2.5])
@pytest.mark.parametrize("ei", [EI, 1e8])
def test_rigid_limit(theta, ei):
    """At xi = xi_dot = 0 with the modes frozen the pendulum is rigid: rho_A L^3 / 3 theta_ddot = rho_A g L^2 / 2
    cos(theta), i.e. theta_ddot = +m g (L/2) cos(theta) / (m L^2 / 3) = 3 g cos(theta) / (2 L).

    The sign, derived: V = -m g (L/2) sin(theta) (positive theta lowers the +x end, r_z = -x sin(theta)), so
    -dV/dtheta = +m g (L/2) cos(theta): from the horizontal the beam falls towards positive theta.

    At xi = 0 the stiffness does no work, so a stiff EI does not freeze the modes instantaneously (the free-mode
    theta_ddot is not the rigid one, whatever EI); freezing them means that the modal rows carry the constraint
    forces and the theta row of Lagrange's equations holds with (theta_ddot, 0, 0): M[0] @ a = M[0, 0] theta_ddot_rigid.
    """
    params = {**PARAMS, "ei": ei}
    q, v = np.array([theta, 0.0, 0.0]), np.array([0.7, 0.0, 0.0])
    rigid = 3.0 * G * np.cos(theta) / (2.0 * LENGTH)
    mass = pendulum_mass_matrix(q, **params)
    a = pendulum_accelerations(q, v, **params)
    m = MASS_PER_LENGTH * LENGTH
    assert mass[0, 0] == pytest.approx(m * LENGTH**2 / 3.0, rel=1e-15)
    assert mass[0] @ a == pytest.approx(mass[0, 0] * rigid, rel=1e-13, abs=1e-13)
    # and the free modes do change theta_ddot (the coupling is there): the Schur complement is small, ~ m L^2 / 300
    assert abs(a[0] - rigid) > 1.0


def test_stiff_beam_follows_the_rigid_pendulum():
    """Dynamically, a stiffer beam released from rest at theta = 0 stays closer to the rigid pendulum."""

    def run(ei):
        params = {**PARAMS, "ei": ei}
        sol = solve_ivp(
            lambda _, y: np.concatenate([y[3:], pendulum_accelerations(y[:3], y[3:], **params)]),
            (0.0, 0.3),
            np.zeros(6),
            method="DOP853",
            rtol=1e-8,
            atol=1e-10,
            t_eval=[0.3],
        )
        return sol.y[0, -1]

    rigid = solve_ivp(
        lambda _, y: [y[1], 3.0 * G * np.cos(y[0]) / (2.0 * LENGTH)],
        (0.0, 0.3),
        [0.0, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        t_eval=[0.3],
    ).y[0, -1]
    soft, stiff = abs(run(1e2) - rigid), abs(run(1e4) - rigid)  # measured: 1.7e-2, 3.8e-5 rad
    assert stiff < 1e-3 * abs(rigid)
    assert stiff < soft / 10.0


def test_invariants_closed_forms():
    """Quadrature invariants against closed forms of the uniform beam with S_k = (x/L)^k+1 e_z about (L/2, 0, 0)."""
    length, rho, ei = LENGTH, MASS_PER_LENGTH, EI
    inv = pendulum_invariants(length, rho, ei)
    m = rho * length
    j = rho * length**3 / 12.0  # slender rod about its middle, no section inertia
    # int_0^L (x - L/2) phi_k dx = L^2 (1/4 - 1/6), L^2 (1/5 - 1/8)
    lever = rho * length**2 * np.array([1.0 / 12.0, 3.0 / 40.0])
    expected = {
        "origin": np.array([length / 2.0, 0.0, 0.0]),
        "first_moment": np.zeros(3),
        "inertia": np.diag([0.0, j, j]),
        "translational_coupling": np.array([[0.0, 0.0], [0.0, 0.0], [m / 3.0, m / 4.0]]),
        "rotational_coupling": np.array([[0.0, 0.0], -lever, [0.0, 0.0]]),  # (x, 0, 0) x (0, 0, phi) = (0, -x phi, 0)
        "modal_mass": m * np.array([[1.0 / 5.0, 1.0 / 6.0], [1.0 / 6.0, 1.0 / 7.0]]),
        "modal_stiffness": ei / length**3 * np.array([[4.0, 6.0], [6.0, 12.0]]),
        "modal_damping": np.zeros((2, 2)),
        "second_moment": np.diag([j, 0.0, 0.0]),
        "gyroscopic": np.zeros((2, 2, 3)),
    }
    p1 = np.zeros((2, 3, 3))
    p1[:, 0, 2] = lever
    p2 = np.zeros((2, 2, 3, 3))
    p2[:, :, 2, 2] = expected["modal_mass"]
    expected |= {"inertia_first": p1, "inertia_second": p2}
    assert inv.mass == pytest.approx(m, rel=1e-15)
    for name, value in expected.items():
        got = getattr(inv, name)
        assert got.shape == value.shape, name
        assert np.abs(got - value).max() <= 1e-14 * max(1.0, np.abs(value).max()), name


def test_invariants_agree_with_the_sympy_mass_matrix():
    """The two independent routes (sympy T, quadrature invariants) meet: M_xi_xi = modal mass; M_theta_xi = the y
    component of the rotational coupling about the pivot, int rho (x e_x) x S_k = Cr + origin x Ct; and
    M_theta_theta(xi) = J(xi)_yy + m (L/2)^2 (parallel axes from the origin to the pivot: int rho (x^2 - (x - L/2)^2)
    dx = m L^2 / 4, for the deformed body too, as w does not enter the difference)."""
    inv = pendulum_invariants(LENGTH, MASS_PER_LENGTH, EI)
    for q, _ in _random_states(4) + _large_states(3):
        mass = pendulum_mass_matrix(q, **PARAMS)
        pivot_coupling = inv.rotational_coupling + np.cross(inv.origin[:, None], inv.translational_coupling, axis=0)
        # the body's angular velocity is theta_dot e_y, the deflection's rate xi_dot: M_theta_xi = e_y . coupling
        assert np.abs(mass[0, 1:] - pivot_coupling[1]).max() <= 1e-14 * np.abs(mass).max()
        assert np.abs(mass[1:, 1:] - inv.modal_mass).max() <= 1e-14 * np.abs(mass).max()
        j_pivot = inv.inertia_at(q[1:])[1, 1] + inv.mass * inv.origin[0] ** 2
        assert mass[0, 0] == pytest.approx(j_pivot, rel=1e-14)


# --- the MFM flexible body against the oracle ---------------------------------------------------------------------


@pytest.fixture(scope="module")
def mfm():
    """(wecss.multibody, Dynamics, model) of the pendulum; skipped until ``ElasticBody`` exists."""
    multibody = importlib.import_module("wecss.multibody")
    if not hasattr(multibody, "ElasticBody"):
        pytest.skip("wecss.multibody has no ElasticBody yet (floating-frame flexible bodies)")
    inv = pendulum_invariants(LENGTH, MASS_PER_LENGTH, EI)
    elastic = multibody.ElasticBody(names=("w1", "w2"), invariants=inv)
    body = multibody.Body("beam", inv.mass, inv.inertia, center_of_mass=inv.origin, elastic=elastic)
    ground = multibody.Body("ground", 1.0, [1.0, 1.0, 1.0], [0.0, 0.0, 0.0])  # fixed: its mass plays no part
    joints = [
        multibody.Joint("base", "fixed", child="ground"),
        multibody.Joint("pivot", "revolute", child="beam", parent="ground", axis=(0.0, 1.0, 0.0), point=(0.0,) * 3),
    ]
    model = multibody.Multibody([ground, body], joints)
    return multibody, multibody.Dynamics(model), model


def _mfm_accelerations(mfm, q, v, g):
    multibody, dyn, model = mfm
    force = multibody.gravity_force(model, g) + multibody.structural_force(model, q, v)
    return np.asarray(dyn.accelerations(q, v, force), dtype=float)


@pytest.mark.parametrize("g", [G, 0.0], ids=["gravity", "no-gravity"])
@pytest.mark.parametrize("family", ["random", "large"])
def test_mfm_accelerations_match_the_oracle(mfm, family, g):
    """MFM accelerations against Lagrange's, 1e-12 relative (max norm), small and large deformation; without gravity
    too, so a mismatch can be told apart between the inertial terms and the gravity load on the deformed body."""
    states = _random_states() if family == "random" else _large_states()
    for q, v in states:
        oracle = pendulum_accelerations(q, v, **{**PARAMS, "g": g})
        got = _mfm_accelerations(mfm, q, v, g)
        err = np.abs(got - oracle).max()
        assert err <= TOL * max(1.0, np.abs(oracle).max()), (q, v, got, oracle, err)


@pytest.mark.parametrize("family", ["random", "large"])
def test_mfm_mass_matrix_matches_the_oracle(mfm, family):
    """MFM generalised mass matrix against d^2 T / dv^2 of the oracle, 1e-12 relative (max norm)."""
    _, dyn, _ = mfm
    states = _random_states() if family == "random" else _large_states()
    for q, v in states:
        oracle = pendulum_mass_matrix(q, **PARAMS)
        got = np.asarray(dyn.terms(q, v).mass, dtype=float)
        err = np.abs(got - oracle).max()
        assert err <= TOL * max(1.0, np.abs(oracle).max()), (q, got, oracle, err)
