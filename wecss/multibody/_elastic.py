"""A flexible body in a floating frame of reference: the Moving Frame Method's Cartesian equations of an elastic body.

The body frame is held at the body's clamp (its Craig-Bampton basis is zero there, ``wecss.structure``) and its
origin is the undeformed centre of mass c0, axes parallel to the world's at the reference configuration. A material
point at x (body axes, from c0) sits at x + u(x) with u = sum_k S_k(x) xi_k: the elastic coordinates xi [1] are
generalised coordinates of the body, after its six rigid ones.

Cartesian velocities. A flexible body has the rows (v_c, w, xi_dot): v_c the world velocity of its instantaneous
centre of mass c = c0 + s(xi) / m (s = s0 + Ct xi the first moment about c0), w the body-frame angular velocity, then
the modal rates. With them the kinetic energy splits (Koenig) into

    T = 1/2 m |v_c|^2 + 1/2 Y' M(xi) Y,   Y = (w, xi_dot),
    M(xi) = [[J_c, C_c], [C_c', M_c]],

about the instantaneous centre of mass: J_c = J(xi) - (|s|^2 I - s s') / m, C_c = Cr(xi) - hat(s) Ct / m with
Cr(xi) = Cr + sum_k xi_k G_k (the rotational coupling and the gyroscopic invariants), M_c = M_ee - Ct' Ct / m. The
translation is then decoupled (m dv_c/dt = F), the rotation follows Euler's equation of a deformable body about its
centre of mass and the modes Lagrange's (T does not depend on the pose):

    d/dt (dT/dw) + w x dT/dw = M_c (body axes),   d/dt (dT/dxi_dot) - dT/dxi = Q,

that is M(xi) dY/dt + h = (M_c, Q) with the quadratic-velocity vector h = Mdot Y + (w x (J_c w + C_c xi_dot),
-1/2 Y' dM/dxi_k Y). It does no work (Y' h = 1/2 Y' Mdot Y), so d/dt T = Y' (M_c, Q) + v_c . F. For a rigid body
(no modes) this is today's m dv/dt = F, J dw/dt + w x J w = M, bit for bit.

The elastic forces are the structural stiffness and damping and, optionally, the cubic strain energy of the basis's
own axial strain (geometric stiffening, ``wecss.structure.axial_geometric_stiffness``).

An elastic attachment is a point of the body (a child joint, a PTO end) that moves with its node: it is displaced by
u_P and rotated by theta_P per modal coordinate (``Attachment.shapes``). The kinematics carries a child body on it
through the product of exponentials prod_k exp(psi_k xi_k) of the attachment's twists psi_k = (u_k - theta_k x P,
theta_k) (world axes at the reference configuration): exact to first order in the deformation, and a holonomic map
whatever the deformation, so the equations keep their energy identity.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..structure import Invariants, ModalBasis, axial_geometric_stiffness, invariants
from ._modes import GeneralisedModes
from ._se3 import hat
from ._vectors import vector3

_LEVI_CIVITA = np.zeros((3, 3, 3))
_LEVI_CIVITA[0, 1, 2] = _LEVI_CIVITA[1, 2, 0] = _LEVI_CIVITA[2, 0, 1] = 1.0
_LEVI_CIVITA[0, 2, 1] = _LEVI_CIVITA[2, 1, 0] = _LEVI_CIVITA[1, 0, 2] = -1.0
"""eps_abc: hat(x) y = eps_abc x_b y_c."""


@dataclass(frozen=True, eq=False)
class Attachment:
    """A point of a flexible body that moves with the structure.

    Parameters
    ----------
    point : array_like (3,)
        Its position at the reference configuration, world axes [m].
    shapes : array_like (6, n)
        Its elastic displacement (rows 0-2) [m] and rotation (rows 3-5) [rad] per unit modal coordinate, body axes.
    """

    point: np.ndarray
    shapes: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "point", vector3(self.point, "attachment point"))
        shapes = np.asarray(self.shapes, dtype=float)
        if shapes.ndim != 2 or shapes.shape[0] != 6 or not np.all(np.isfinite(shapes)):
            raise ValueError(
                f"attachment shapes must be a finite (6, n) array (displacement [m], rotation [rad] per modal "
                f"coordinate); got shape {shapes.shape}"
            )
        object.__setattr__(self, "shapes", shapes)

    @cached_property
    def twists(self) -> np.ndarray:
        """(n, 6): the twist (u_k - theta_k x P, theta_k) of each modal coordinate (world axes at the reference)."""
        u, theta = self.shapes[:3].T, self.shapes[3:].T
        return np.concatenate([u - np.cross(theta, self.point), theta], axis=1)


@dataclass(frozen=True, eq=False)
class ElasticBody:
    """The floating-frame model of a flexible body (see the module docstring).

    Parameters
    ----------
    names : sequence of str
        One name per modal coordinate (``flex1``, ...): the generalised coordinate is ``<body>__<name>``.
    invariants : wecss.structure.Invariants
        About the body's undeformed centre of mass (``origin``), body axes; its modal mass, stiffness and damping
        are the modes' structural matrices.
    attachments : mapping of str to Attachment, optional
        Points of the body that move with the structure, by name: a child joint's name carries the child on it.
    geometric : array_like (n, n, n), optional
        The basis's geometric stiffness per unit modal coordinate's axial force
        (``wecss.structure.axial_geometric_stiffness``) [N m]; None: no geometric stiffening.
    quasi_static : array_like of bool (n,), optional
        The modal coordinates held quasi-static (condensed): their rates and accelerations are neglected and their
        equations of motion are algebraic (the structure's static response to the loads of the moment, the
        inertial loads of the rigid motion among them). Default: none.

    Raises
    ------
    ValueError
        On sizes that do not agree with the number of names, or a non-finite tensor.
    """

    names: tuple[str, ...]
    invariants: Invariants
    attachments: Mapping[str, Attachment] = field(default_factory=dict)
    geometric: np.ndarray | None = None
    quasi_static: np.ndarray | None = None

    def __post_init__(self) -> None:
        names = (self.names,) if isinstance(self.names, str) else tuple(self.names)
        object.__setattr__(self, "names", names)
        n = len(names)
        inv = self.invariants
        expected = {
            "translational_coupling": (3, n), "rotational_coupling": (3, n), "modal_mass": (n, n),
            "modal_stiffness": (n, n), "modal_damping": (n, n), "inertia_first": (n, 3, 3),
            "inertia_second": (n, n, 3, 3), "gyroscopic": (n, n, 3),
        }  # fmt: skip
        wrong = {k: np.shape(getattr(inv, k)) for k, shape in expected.items() if np.shape(getattr(inv, k)) != shape}
        if wrong:
            raise ValueError(
                f"elastic body with {n} modal coordinates {list(names)}: its invariants {sorted(wrong)} have the "
                f"shapes {list(wrong.values())}; accepted: {[expected[k] for k in sorted(wrong)]}"
            )
        attachments = dict(self.attachments)
        for name, a in attachments.items():
            if not isinstance(a, Attachment) or a.shapes.shape != (6, n):
                raise ValueError(
                    f"attachment {name!r} must be an Attachment with shapes (6, {n}); got "
                    f"{getattr(getattr(a, 'shapes', None), 'shape', a)!r}"
                )
        object.__setattr__(self, "attachments", attachments)
        if self.geometric is not None:
            geo = np.asarray(self.geometric, dtype=float)
            if geo.shape != (n, n, n) or not np.all(np.isfinite(geo)):
                raise ValueError(f"geometric must be a finite ({n}, {n}, {n}) array [N m]; got shape {geo.shape}")
            object.__setattr__(self, "geometric", geo)
        held = np.zeros(n, dtype=bool) if self.quasi_static is None else np.asarray(self.quasi_static)
        if held.shape != (n,) or held.dtype != bool:
            raise ValueError(
                f"quasi_static must be {n} booleans (one per modal coordinate {list(names)}); got {self.quasi_static!r}"
            )
        held = held.copy()
        held.flags.writeable = False
        object.__setattr__(self, "quasi_static", held)

    @classmethod
    def from_basis(
        cls,
        basis: ModalBasis,
        attachments: Mapping[str, str] | None = None,
        *,
        geometric: bool = True,
        names: Sequence[str] | None = None,
        quasi_static_above: float | None = None,
    ) -> ElasticBody:
        """The elastic model of a reduced structure: invariants about its centre of mass, the attachments at named
        points of its frame (``{attachment: frame point}``) and, with ``geometric``, the geometric tensor of its
        own axial strain. ``names`` default to ``flex1``, ``flex2``, ... ``quasi_static_above`` [Hz]: the basis
        coordinates whose natural frequency (clamped, ``basis.omega`` / 2 pi) is above it are held quasi-static
        (None: none; 0: all).

        Raises
        ------
        KeyError
            If a frame point does not exist (the message lists them).
        """
        frame, phi = basis.frame, basis.basis
        attached = {
            name: Attachment(frame.point(point)[1], frame.point_map(point) @ phi)
            for name, point in (attachments or {}).items()
        }
        names = tuple(names) if names is not None else tuple(f"flex{k + 1}" for k in range(basis.n))
        return cls(
            names,
            invariants(frame, phi, damping=basis.damping),
            attached,
            axial_geometric_stiffness(frame, phi) if geometric else None,
            None if quasi_static_above is None else basis.omega / (2 * np.pi) > quasi_static_above,
        )

    @property
    def n(self) -> int:
        """Number of modal coordinates."""
        return len(self.names)

    def modes(self, body: str) -> GeneralisedModes:
        """The modal coordinates as ``body``'s generalised modes (the invariants' modal mass, stiffness, damping)."""
        inv = self.invariants
        return GeneralisedModes(self.names, inv.modal_mass, inv.modal_stiffness, inv.modal_damping, body)

    # --- inertia ----------------------------------------------------------------------------------------------
    def first_moment(self, xi: np.ndarray) -> np.ndarray:
        """s(xi) = s0 + Ct xi about the undeformed centre of mass, body axes [kg m]."""
        return self.invariants.first_moment_at(xi)

    def centre_of_mass(self, xi: np.ndarray) -> np.ndarray:
        """The deformed body's centre of mass at the reference pose, world axes [m]."""
        inv = self.invariants
        return inv.origin + self.first_moment(xi) / inv.mass

    def relative_mass(self, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """M(xi) (3 + n, 3 + n) about the instantaneous centre of mass on Y = (w, xi_dot), and its derivatives
        dM/dxi_k (n, 3 + n, 3 + n) [kg m^2] (see the module docstring)."""
        inv = self.invariants
        xi = np.asarray(xi, dtype=float)
        n, m = self.n, inv.mass
        ct = inv.translational_coupling
        s = self.first_moment(xi)
        eye = np.eye(3)
        j_c = inv.inertia_at(xi) - (s @ s * eye - np.outer(s, s)) / m
        rot = inv.rotational_coupling + np.einsum("k,kla->al", xi, inv.gyroscopic)
        c_c = rot - hat(s) @ ct / m
        out = np.zeros((3 + n, 3 + n))
        out[:3, :3] = j_c
        out[:3, 3:] = c_c
        out[3:, :3] = c_c.T
        out[3:, 3:] = inv.modal_mass - ct.T @ ct / m
        d = np.zeros((n, 3 + n, 3 + n))
        p2 = inv.inertia_second
        dp = inv.inertia_first + inv.inertia_first.transpose(0, 2, 1)
        dp = dp + np.einsum("l,klab->kab", xi, p2) + np.einsum("l,lkab->kab", xi, p2)
        # per k (vectorised): d_j = tr(dP_k) I - dP_k - (2 (s . c_k) I - c_k s' - s c_k') / m with c_k = Ct[:, k], and
        # d_c = G_k' - hat(c_k) Ct / m
        sc = s @ ct
        outer = np.einsum("ak,b->kab", ct, s)
        d[:, :3, :3] = (
            (np.einsum("kaa->k", dp) - 2 * sc / m)[:, None, None] * eye - dp + (outer + outer.transpose(0, 2, 1)) / m
        )
        d_c = inv.gyroscopic.transpose(0, 2, 1) - np.einsum("abc,bk,cl->kal", _LEVI_CIVITA, ct, ct) / m
        d[:, :3, 3:] = d_c
        d[:, 3:, :3] = d_c.transpose(0, 2, 1)
        return 0.5 * (out + out.T), d

    # --- elastic forces ---------------------------------------------------------------------------------------
    def geometric_force(self, xi: np.ndarray) -> np.ndarray:
        """-dU3/dxi (n,) [J]: the geometric stiffening of the basis's own axial strain
        (``wecss.structure.axial_geometric_stiffness``); zero without the geometric tensor."""
        xi = np.asarray(xi, dtype=float)
        if self.geometric is None:
            return np.zeros(self.n)
        geo = self.geometric
        return -(np.einsum("m,mkl,l->k", xi, geo, xi) + 0.5 * np.einsum("k,jkl,l->j", xi, geo, xi))

    def elastic_force(self, xi: np.ndarray, xi_dot: np.ndarray | None = None) -> np.ndarray:
        """Generalised force (n,) of the structure on its modal coordinates [J]: -K xi - C xi_dot plus the
        :meth:`geometric_force`."""
        inv = self.invariants
        xi = np.asarray(xi, dtype=float)
        out = -inv.modal_stiffness @ xi + self.geometric_force(xi)
        if xi_dot is not None:
            out -= inv.modal_damping @ np.asarray(xi_dot, dtype=float)
        return out

    def elastic_energy(self, xi: np.ndarray) -> float:
        """Strain energy 1/2 xi' K xi + U3(xi) [J]."""
        xi = np.asarray(xi, dtype=float)
        out = 0.5 * float(xi @ self.invariants.modal_stiffness @ xi)
        if self.geometric is not None:
            out += 0.5 * float(np.einsum("m,k,l,mkl->", xi, xi, xi, self.geometric))
        return out

    def attachment(self, name: str) -> Attachment:
        """The attachment called ``name``.

        Raises
        ------
        KeyError
            If there is none (the message lists them).
        """
        if name not in self.attachments:
            raise KeyError(f"the elastic body has no attachment {name!r}; attachments: {sorted(self.attachments)}")
        return self.attachments[name]


def check_elastic_body(
    body: str, mass: float, inertia: np.ndarray, center_of_mass: np.ndarray, elastic: object
) -> None:
    """Refuse an elastic model whose invariants disagree with the body's mass, inertia about its centre of mass or
    centre of mass (relative 1e-9), or that is not an :class:`ElasticBody`."""
    if not isinstance(elastic, ElasticBody):
        raise ValueError(f"body {body!r}: elastic must be an ElasticBody; got {type(elastic).__name__}")
    inv = elastic.invariants
    scale = max(1.0, float(np.abs(inertia).max()))
    length = max(1.0, float(np.abs(center_of_mass).max()))
    problems: Sequence[tuple[str, bool]] = (
        (f"mass {inv.mass:.9g} kg (the body's {mass:.9g})", abs(inv.mass - mass) <= 1e-9 * mass),
        (
            f"origin {np.round(inv.origin, 9).tolist()} m (the body's centre of mass "
            f"{np.round(center_of_mass, 9).tolist()})",
            bool(np.allclose(inv.origin, center_of_mass, rtol=0, atol=1e-9 * length)),
        ),
        (
            f"first moment {np.round(inv.first_moment, 9).tolist()} kg m (zero about the centre of mass)",
            bool(np.allclose(inv.first_moment, 0.0, rtol=0, atol=1e-9 * mass * length)),
        ),
        (
            "inertia about the centre of mass (differs from the body's by "
            f"{float(np.abs(inv.inertia - inertia).max()):.3g} kg m^2)",
            bool(np.allclose(inv.inertia, inertia, rtol=0, atol=1e-9 * scale)),
        ),
    )
    bad = [what for what, ok in problems if not ok]
    if bad:
        raise ValueError(f"body {body!r}: its elastic model's invariants disagree with the body: {'; '.join(bad)}")
