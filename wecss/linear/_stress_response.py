"""Stress transfer functions of a device's elastic bodies: the linearised stress at every fibre point per wave
component, from the exact frequency-domain solution.

An elastic body's stress at a fibre point (``wecss.sim._fibre_field``) is
sigma = S xi + S_a xi_ddot + S_r r + (S_m r) xi + (S_c w) xi_dot + xi' S_g xi, with xi its modal coordinates and r
the rigid-motion load coordinates of its floating frame: g - a_o (gravity less the acceleration of the frame's
origin, body axes), the angular acceleration alpha and the products of the angular velocity w. About the static
equilibrium (xi0, frame rotation R0, g_b0 = R0' g, the static deflection's shift d0 = Ct xi0 / m of the centre of
mass) a wave component of frequency omega moves the frame by the small rotation theta (body axes) and the centre of
mass by c (world), the modal coordinates by xi_hat; to first order

    g_b  = g_b0 + g_b0 x theta,     alpha = -omega^2 theta,     a_o = -omega^2 (R0' c - theta x d0 - d),

(d = Ct xi_hat / m; a_o is the acceleration of the frame's point c0, carried to the stress modes' origin by
alpha x (o - c0)) and the angular-velocity products are of second order. Hence the complex amplitude

    sigma_hat = (S - omega^2 S_a + 2 sym(S_g) xi0) xi_hat + S_r r_hat + (S_m alpha_hat) xi0,

per wave component, exact for the linearised equations (alpha_hat acting on the static deflection xi0; the terms of
w are of second order). The static value is sigma0 = S xi0 + S_r (g_b0, 0, 0) +
xi0' S_g xi0. Modal coordinates held quasi-static (``flexible.quasi_static_above``) have no acceleration, as in a
run: the terms of the accelerations (-omega^2 S_a xi_hat, alpha, a_o) leave out their part (the condensed linear
model of ``wecss.linear._model``); theta in the gravity term and xi_hat in S xi_hat are the displacements.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..compiled import CompiledScene
from ..compiled.kernels import kinematics
from ..structure import rigid_load_coordinates
from ._frequency import _moving, _wave_amplitudes, frequency_domain_waves, response_amplitudes
from ._model import equilibrium_maps, linearize


def stress_response(compiled: CompiledScene) -> xr.Dataset:
    """The normal and shear stress at every fibre point of the device's elastic bodies (see the module docstring):
    complex amplitudes per wave component of the scene (Re[X e^{+i omega t}] about the equilibrium) and their values
    at the equilibrium.

    Returns
    -------
    Dataset
        Dimensions ``omega`` (the scene's wave components) and ``fibre_point`` (per body its hot spots, then every
        node's default fibres, as a run's ``fibre_*`` variables): ``normal_stress_amplitude``,
        ``shear_stress_amplitude`` [Pa] (complex), ``normal_stress_equilibrium``, ``shear_stress_equilibrium``
        [Pa], ``normal_stress_rao`` [Pa/m] (the amplitude per unit wave amplitude, a stress transfer function for
        spectral fatigue) and ``wave_amplitude`` [m] (complex).

    Raises
    ------
    ValueError
        In calm water, for a controller without linear gains, for a device without elastic bodies, and
        in a directional sea (``sea.spreading``: several components per frequency, no response per unit wave).
    TypeError
        If ``compiled`` is not a CompiledScene.
    """
    exc = frequency_domain_waves(compiled, "stress_response")
    model = compiled.device.model
    if not model.elastic_bodies:
        raise ValueError(
            f"device {compiled.device.name!r} has no elastic bodies (flexible.dynamics = 'elastic'): no stress modes "
            "in its equations"
        )
    omega = exc.omega
    linear = linearize(compiled)
    amplitudes = response_amplitudes(linear, omega, exc.coefficients)  # (nv, n_w)
    moving = _moving(linear, amplitudes)  # the accelerations' amplitudes / -omega^2: none of a held coordinate
    b0 = equilibrium_maps(compiled)[0]
    q0 = compiled.q0
    names: list[str] = []
    normal: list[np.ndarray] = []
    shear: list[np.ndarray] = []
    normal0: list[np.ndarray] = []
    shear0: list[np.ndarray] = []
    for i in model.elastic_bodies:
        body = model.bodies[i]
        elastic = body.elastic
        assert elastic is not None
        structure = compiled.device.flexible_body(body.name)
        modes = structure.stresses
        rot0 = _rotation(compiled, i)
        xi0 = q0[model.mode_coordinate_start[i] : model.mode_coordinate_start[i + 1]]
        own = slice(model.mode_velocity_start[i], model.mode_velocity_start[i + 1])
        inv = elastic.invariants
        shift = inv.translational_coupling / inv.mass
        s = model.cart_start[i]
        xi_hat = amplitudes[own]  # (n, n_w)
        theta = b0[s + 3 : s + 6] @ amplitudes  # body axes
        turning = b0[s + 3 : s + 6] @ moving  # the rotation the accelerations see
        centre = rot0.T @ (b0[s : s + 3] @ moving)  # body axes
        g_b0 = rot0.T @ np.array([0.0, 0.0, -compiled.hydro.g])
        d0 = shift @ xi0
        arm = structure.invariants.origin - inv.origin  # the stress modes' origin from the frame's c0
        w2 = omega**2
        alpha = -w2 * turning
        origin_acc = -w2 * (centre - np.cross(turning, d0, axis=0) - shift @ moving[own]) + np.cross(alpha, arm, axis=0)
        gravity = np.cross(g_b0, theta, axis=0)
        r_hat = np.concatenate([gravity - origin_acc, alpha, np.zeros((6, omega.size))])  # (12, n_w): RIGID_LOADS
        r0 = rigid_load_coordinates(g_b0, np.zeros(3), np.zeros(3))
        # alpha's loads on the static deflection, (n_point, n_w) each
        turning_sag = modes.at_points(np.einsum("sjkn,n,kw->wsj", modes.section_motion[:, :, :3], xi0, alpha))
        for lin, acc, rig, geo, sag, out, out0 in (
            (modes.normal, modes.normal_acceleration, modes.normal_rigid, modes.normal_geometric, turning_sag[0],
             normal, normal0),
            (modes.shear, modes.shear_acceleration, modes.shear_rigid, modes.shear_geometric, turning_sag[1], shear,
             shear0),
        ):  # fmt: skip
            tangent = lin if geo is None else lin + np.einsum("pmk,m->pk", geo + geo.transpose(0, 2, 1), xi0)
            out.append(tangent @ xi_hat - (acc @ moving[own]) * w2 + rig @ r_hat + sag.T)
            static = lin @ xi0 + rig @ r0
            out0.append(static if geo is None else static + np.einsum("m,pmk,k->p", xi0, geo, xi0))
        names += [p.name for p in modes.points]
    wave = _wave_amplitudes(compiled, omega)
    sigma = np.concatenate(normal).T  # (n_w, n_point)
    tau = np.concatenate(shear).T
    with np.errstate(divide="ignore", invalid="ignore"):
        rao = sigma / wave[:, None]
    return xr.Dataset(
        {
            "normal_stress_amplitude": (("omega", "fibre_point"), sigma, {"units": "Pa"}),
            "shear_stress_amplitude": (("omega", "fibre_point"), tau, {"units": "Pa"}),
            "normal_stress_equilibrium": (("fibre_point",), np.concatenate(normal0), {"units": "Pa"}),
            "shear_stress_equilibrium": (("fibre_point",), np.concatenate(shear0), {"units": "Pa"}),
            "normal_stress_rao": (("omega", "fibre_point"), rao, {"units": "Pa/m"}),
            "wave_amplitude": (("omega",), wave, {"units": "m"}),
        },
        coords={"omega": omega, "fibre_point": names},
        attrs={
            "title": f"stress transfer functions of {compiled.device.name}'s elastic bodies (exact frequency domain)",
            "convention": "complex amplitudes X of Re[X exp(+i omega t)], about the static equilibrium",
        },
    )


def _rotation(compiled: CompiledScene, i: int) -> np.ndarray:
    """Body ``i``'s rotation (3, 3) at the equilibrium."""
    p = compiled.plant
    return kinematics(p, compiled.q0, np.zeros(p.twists.shape[0]))[0][i]
