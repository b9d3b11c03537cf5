"""Kinematics: B against finite differences of poses, Bdot against the derivative of B, the paper's B-matrix."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.multibody import cross3, difference, integrate, kinematics
from wecss.multibody._se3 import (
    adjoint,
    frame,
    frame_inverse,
    hat,
    se3_exp,
    se3_log,
    so3_exp,
    so3_log,
    twist_bracket,
    vee,
)

from .chains import m4_111_like, mixed_chain


@pytest.mark.parametrize("base", ["planar", "free", "fixed"])
def test_b_matrix_matches_finite_differences_of_poses(base: str) -> None:
    model = mixed_chain(base)
    rng = np.random.default_rng(3)
    q = integrate(model, model.neutral_configuration(), 0.5 * rng.normal(size=model.nv))
    v = rng.normal(size=model.nv)
    state = kinematics(model, q, v)
    h = 1e-6
    plus, minus = kinematics(model, integrate(model, q, h * v)), kinematics(model, integrate(model, q, -h * v))
    p_dot = (plus.position - minus.position) / (2 * h)
    r_dot = (plus.rotation - minus.rotation) / (2 * h)
    w_body = np.array([vee(r.T @ rd) for r, rd in zip(state.rotation, r_dot, strict=True)])
    x_dot = (state.B @ v).reshape(-1, 6)
    scale = np.abs(x_dot).max()
    np.testing.assert_allclose(x_dot[:, :3], p_dot, rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(x_dot[:, 3:], w_body, rtol=0, atol=1e-7 * scale)
    # Bdot is the time derivative of B along the trajectory q(t) = integrate(q, t v)
    b_dot = (plus.B - minus.B) / (2 * h)
    assert state.Bdot is not None
    np.testing.assert_allclose(state.Bdot, b_dot, rtol=0, atol=1e-7 * max(1.0, np.abs(b_dot).max()))


def test_b_matrix_of_111_equals_paper_eq_29() -> None:
    """Eq. 29-31, derived again: rows of float 2 and 3 from the lever arms s^(2/1), s^(h/2), s^(3/h)."""
    model = m4_111_like()
    rng = np.random.default_rng(7)
    q = rng.normal(size=4) * [0.05, 0.05, 0.3, 0.4]
    st = kinematics(model, q)
    theta, phi = q[2], q[3]
    e1, e2, e3 = np.eye(3)
    c1, c2, c3 = (b.center_of_mass for b in model.bodies)
    hinge = np.array([1.06, 0.0, 0.25])
    r1, r32 = so3_exp(theta * e2), so3_exp(phi * e2)
    s21, sh2, s3h = c2 - c1, hinge - c2, c3 - hinge  # frame offsets in the parent's frame (reference axes)
    zero = np.zeros(3)
    b53 = r1 @ ((hat(sh2).T + hat(s21).T) + r32 @ hat(s3h).T @ r32.T) @ e2
    b54 = r1 @ r32 @ hat(s3h).T @ e2
    paper = np.block(
        [
            [e1[:, None], e3[:, None], zero[:, None], zero[:, None]],
            [zero[:, None], zero[:, None], e2[:, None], zero[:, None]],
            [e1[:, None], e3[:, None], (r1 @ hat(s21).T @ e2)[:, None], zero[:, None]],
            [zero[:, None], zero[:, None], e2[:, None], zero[:, None]],
            [e1[:, None], e3[:, None], b53[:, None], b54[:, None]],
            [zero[:, None], zero[:, None], (r32.T @ e2)[:, None], e2[:, None]],
        ]
    )
    np.testing.assert_allclose(st.B, paper, atol=1e-14)


def test_se3_helpers() -> None:
    rng = np.random.default_rng(0)
    w = rng.normal(size=3)
    np.testing.assert_allclose(hat(w) @ np.array([1.0, 2.0, 3.0]), np.cross(w, [1.0, 2.0, 3.0]))
    np.testing.assert_allclose(vee(hat(w)), w)
    np.testing.assert_allclose(so3_log(so3_exp(w)), w, atol=1e-12)
    np.testing.assert_allclose(so3_log(so3_exp(1e-10 * w)), 1e-10 * w, atol=1e-20)
    xi = rng.normal(size=6)
    np.testing.assert_allclose(se3_log(se3_exp(xi)), xi, atol=1e-12)
    e = se3_exp(xi)
    np.testing.assert_allclose(frame_inverse(e), np.linalg.inv(e), atol=1e-12)  # Eq. 8

    # Ad(E) xi is the twist whose hat is E hat(xi) E^-1
    def twist_hat(t: np.ndarray) -> np.ndarray:
        out = np.zeros((4, 4))
        out[:3, :3], out[:3, 3] = hat(t[3:]), t[:3]
        return out

    other = rng.normal(size=6)
    np.testing.assert_allclose(twist_hat(adjoint(e) @ other), e @ twist_hat(other) @ frame_inverse(e), atol=1e-12)
    bracket = twist_hat(xi) @ twist_hat(other) - twist_hat(other) @ twist_hat(xi)
    np.testing.assert_allclose(twist_hat(twist_bracket(xi, other)), bracket, atol=1e-12)
    with pytest.raises(ValueError, match="rotation matrix"):
        so3_log(np.ones((3, 3)))
    np.testing.assert_allclose(frame(np.eye(3), [1.0, 2.0, 3.0])[:3, 3], [1.0, 2.0, 3.0])


def test_cross3_is_np_cross_bit_for_bit() -> None:
    """The loads' recovery relies on it: the rigid loads stay the same numbers."""
    rng = np.random.default_rng(3)
    left = rng.normal(size=(200, 3)) * 10.0 ** rng.integers(-6, 6, (200, 1))
    for a, b in zip(left, rng.normal(size=(200, 3)), strict=True):
        np.testing.assert_array_equal(cross3(a, b), np.cross(a, b))


def test_integrate_and_difference_are_inverse() -> None:
    model = mixed_chain("free")
    rng = np.random.default_rng(1)
    q0 = integrate(model, model.neutral_configuration(), rng.normal(size=model.nv))
    dv = 0.3 * rng.normal(size=model.nv)
    np.testing.assert_allclose(difference(model, q0, integrate(model, q0, dv)), dv, atol=1e-12)


def test_wrong_sizes_are_explained() -> None:
    model = m4_111_like()
    with pytest.raises(ValueError, match="q must have 4 entries"):
        kinematics(model, np.zeros(3))
    with pytest.raises(ValueError, match="v must have 4 entries"):
        kinematics(model, np.zeros(4), np.zeros(5))
