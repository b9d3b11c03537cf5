"""The body-exact hydrostatic and Froude-Krylov forces as a kernel term (``hydrodynamics.hydrostatics`` or
``froude_krylov = "body-exact"``): each hydro body's mesh under the free surface at every evaluation of
``configure`` (``wecss.compiled._pressure``), entering the equations as what it adds to the linear forces.

With H(pose) and K(pose, t) the mesh's hydrostatic and Froude-Krylov forces (world axes, about the centre of mass),
delta = (CoM displacement, rotation vector) from the reference pose (as the linear hydrostatics take it), and
F_lin(t) = Re sum_k c_k P_k(t) a linear Froude-Krylov force (P_k the ramped phasors of the incident field), the
term adds

    R = [H(pose) - H_ref - J (delta - delta_ref)] + [K(pose, t) - F_lin(t)]

(the first bracket with body-exact hydrostatics, the second with body-exact Froude-Krylov). In the "remainder"
formulation H_ref, J and delta_ref are the mesh's own value, tangent and pose at the equilibrium and c_k its linear
Froude-Krylov force on the mean wetted surface there, so R is of second order in the motion and the waves: the
equilibrium, the linear model and small waves are those of the linear forces. In the "replace" formulation H_ref is
the database's equilibrium buoyancy, J minus its hydrostatic stiffness, delta_ref zero and c_k its Froude-Krylov
coefficients: R takes the database's hydrostatics and Froude-Krylov force out and puts the mesh's in.

The per-body output rows (``TERM_ROWS``) get H (hydrostatic), K (froude_krylov) and R (remainder), and
``TermsWork.flags`` the flags of the mesh kernel, ORed over the run (DRY, SUBMERGED, OUTSIDE_TABLE).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._jit import step_kernel
from ._pressure import MeshArrays, mesh_pressure_force
from ._rotation import so3_log_into
from ._viscous import TERM_ROWS, TermsWork, add_generalised
from ._wave_field import FieldArrays, calm_field

HYDROSTATIC_ROW, FROUDE_KRYLOV_ROW, REMAINDER_ROW = (
    TERM_ROWS.index(k) for k in ("hydrostatic", "froude_krylov", "remainder")
)

SURFACE_MODE, WITH_HYDROSTATICS, WITH_FROUDE_KRYLOV = 0, 1, 2
"""Entries of :attr:`PressureArrays.settings`: the clipping surface (0: z = 0, 1: the incident surface), and
whether the hydrostatics and the Froude-Krylov force are body-exact (1) or linear (0)."""


class PressureArrays(NamedTuple):
    """The body-exact pressure forces of a plant (no bodies: none).

    Attributes
    ----------
    mesh : MeshArrays
        The meshes of the bodies with a body-exact force (mesh body b, one after the other).
    field : FieldArrays
        The incident wave field (calm: no waves).
    owner : int64 ndarray (n_mb,)
        The plant's body of mesh body b.
    settings : int64 ndarray (3,)
        See :data:`SURFACE_MODE`, :data:`WITH_HYDROSTATICS`, :data:`WITH_FROUDE_KRYLOV`.
    reference : ndarray (n_mb, 6)
        H_ref [N, N m] (see the module docstring).
    tangent : ndarray (n_mb, 6, 6)
        J [N/m, N/rad, N m/m, N m/rad].
    delta_ref : ndarray (n_mb, 6)
        delta_ref [m, rad].
    linear_fk : complex ndarray (n_mb, n_w, 6)
        c_k: the linear Froude-Krylov force per unit phasor [N/m, N m/m].
    water : ndarray (2,)
        rho [kg/m^3] and g [m/s^2].
    """

    mesh: MeshArrays
    field: FieldArrays
    owner: np.ndarray
    settings: np.ndarray
    reference: np.ndarray
    tangent: np.ndarray
    delta_ref: np.ndarray
    linear_fk: np.ndarray
    water: np.ndarray


@step_kernel
def configure_pressure(
    pa: PressureArrays, t: float, rot: np.ndarray, pos: np.ndarray, com0: np.ndarray, cart_start: np.ndarray,
    b_mat: np.ndarray, tw: TermsWork, gen: np.ndarray,
) -> None:  # fmt: skip
    """The body-exact term R (module docstring) at time ``t`` [s] and the bodies' frames ``rot``, ``pos`` (world;
    ``com0`` the reference positions of the centres of mass), added to the generalised force ``gen`` through B
    (``b_mat``), with H, K and R into ``tw.out`` and the mesh kernel's flags into ``tw.flags``."""
    n_mb = pa.owner.shape[0]
    mode = pa.settings[SURFACE_MODE]
    with_hs = pa.settings[WITH_HYDROSTATICS] == 1
    with_fk = pa.settings[WITH_FROUDE_KRYLOV] == 1
    rho_g = pa.water[0] * pa.water[1]
    total = tw.vec6
    acc = pa.mesh.acc
    delta = tw.delta
    for b in range(n_mb):
        i = pa.owner[b]
        tw.flags[i] |= mesh_pressure_force(
            pa.mesh, rot[i], pos[i], pa.field, t, mode, with_fk, pa.water[0], pa.water[1], total, b
        )
        r = rot[i]
        out = tw.out[i]
        for a in range(3):  # K: the kernel's Froude-Krylov sums (body axes, per rho g) to world axes
            kf = 0.0
            km = 0.0
            for c in range(3):
                kf += r[a, c] * acc[24 + c]
                km += r[a, c] * acc[27 + c]
            out[FROUDE_KRYLOV_ROW, a] = rho_g * kf if with_fk else 0.0
            out[FROUDE_KRYLOV_ROW, 3 + a] = rho_g * km if with_fk else 0.0
        for a in range(6):
            out[HYDROSTATIC_ROW, a] = total[a] - out[FROUDE_KRYLOV_ROW, a]
            out[REMAINDER_ROW, a] = 0.0
        if with_hs:
            so3_log_into(r, tw.axis)
            for a in range(3):
                delta[a] = pos[i, a] - com0[i, a] - pa.delta_ref[b, a]
                delta[3 + a] = tw.axis[a] - pa.delta_ref[b, 3 + a]
            for a in range(6):
                s = out[HYDROSTATIC_ROW, a] - pa.reference[b, a]
                for c in range(6):
                    s -= pa.tangent[b, a, c] * delta[c]
                out[REMAINDER_ROW, a] = s
        if with_fk:
            phasor = pa.field.phasor
            for a in range(6):
                s = out[FROUDE_KRYLOV_ROW, a]
                for k in range(phasor.shape[0]):
                    c = pa.linear_fk[b, k, a]
                    s -= c.real * phasor[k].real - c.imag * phasor[k].imag
                out[REMAINDER_ROW, a] += s
        # into the generalised force: the world force, the moment in body axes (B's rotation rows)
        for a in range(3):
            total[a] = out[REMAINDER_ROW, a]
            total[3 + a] = (
                r[0, a] * out[REMAINDER_ROW, 3] + r[1, a] * out[REMAINDER_ROW, 4] + r[2, a] * out[REMAINDER_ROW, 5]
            )
        add_generalised(b_mat, cart_start[i], total, gen)


def no_pressure() -> PressureArrays:
    """No body-exact forces (empty arrays, calm field)."""

    mesh = MeshArrays(
        vertices=np.zeros((0, 3)),
        faces=np.zeros((0, 3), dtype=np.int64),
        moments=np.zeros((0, 24)),
        vertex_start=np.zeros(1, dtype=np.int64),
        face_start=np.zeros(1, dtype=np.int64),
        cluster_start=np.zeros(1, dtype=np.int64),
        body_cluster_start=np.zeros(1, dtype=np.int64),
        cluster_box=np.zeros((0, 2, 3)),
        cluster_moments=np.zeros((0, 24)),
        world=np.zeros((0, 3)),
        height=np.zeros(0),
        head=np.zeros(0),
        gradient=np.zeros((0, 3)),
        acc=np.zeros(30),
    )
    return PressureArrays(
        mesh=mesh,
        field=calm_field(),
        owner=np.zeros(0, dtype=np.int64),
        settings=np.zeros(3, dtype=np.int64),
        reference=np.zeros((0, 6)),
        tangent=np.zeros((0, 6, 6)),
        delta_ref=np.zeros((0, 6)),
        linear_fk=np.zeros((0, 0, 6), dtype=complex),
        water=np.array([1000.0, 9.81]),
    )
