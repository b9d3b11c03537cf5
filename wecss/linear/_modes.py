"""Modal table of a device about its static equilibrium in water, or about its rest in air: natural periods
(undamped, in water with the frequency-dependent added mass), damping ratios and mode shapes, on the nodes of its
elastic bodies too.

In water, the frequency-dependent added mass is resolved per mode by a fixed point: omega_j^2 = k_j / m_j(omega_j),
with k_j and m_j(omega) = phi' (M* + Bw' (A(omega) - A_inf) Bw) phi the modal stiffness and mass of the
undamped eigenvector phi of (K, M* + Bw' (A(omega_j) - A_inf) Bw); the damping ratio is
zeta_j = phi' (C + Bw' B(omega_j) Bw) phi / (2 m_j omega_j), with C the linear PTO damping, the joints' losses, the
moorings' dampers and the elastic bodies' structural damping. It uses the database's A(omega) and B(omega) directly
(no radiation fit) and neglects the modal coupling by damping. Outside the database's frequencies A(omega) and
B(omega) are held at their end values, as in the linear model's exact frequency response (an elastic mode far
above the waves gets the added mass and radiation damping of the database's highest frequency;
``wecss.devices.structural_modes`` takes A_inf and no radiation damping there). The matrices are the linear
model's (``wecss.linear.linearize``).

In air (``water=False``) there is no water and no gravity: no added mass, radiation, hydrostatics, buoyancy or
moorings; the device rests where its PTO springs (the device's and the controller's linear stiffness) and its
elastic bodies' stiffness hold it, found from its reference configuration (the reference itself when its springs
are at rest there). The equations are those of the compiled plant about that rest: M* = B' M B of the bodies' own
mass (a flexible body's M(xi) at its deflection), the static stiffness of the PTO springs and the structure
(``StaticModel`` without gravity and water) and the damping of the PTOs' linear gains, the joints and the
structure. As ``wecss.devices.structural_modes(device, water=False)``.

Modal coordinates held quasi-static (``flexible.quasi_static_above``) have no rate and no acceleration, as in the
linear model (``wecss.linear._model``): the table has a mode per kept coordinate, from the condensed pencil (not
symmetric: its damping ratios take the left and right eigenvectors), its shapes on every coordinate (the held ones'
values from their equations).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import xarray as xr
from scipy.linalg import eig, eigh

from ..compiled import CompiledScene, linear_damping
from ..compiled.kernels import kinematics, pto_strokes
from ..multibody import EquilibriumError, body_mass_matrix
from ._model import linearize
from ._node_shapes import PARTS, node_maps


@dataclass(frozen=True)
class _Matrices:
    """The undamped eigenproblem's matrices about the configuration ``q``: ``stiffness``, the mass the fixed point
    starts from (``start``: M* with the database's A_inf), and the ``mass`` and ``damping`` at a frequency [rad/s];
    ``band`` the frequencies the database knows A(omega) and B(omega) at (None: in air, no frequency dependence);
    ``held`` the generalised velocities held quasi-static (None: none)."""

    q: np.ndarray
    stiffness: np.ndarray
    start: np.ndarray
    mass: Callable[[float], np.ndarray]
    damping: Callable[[float], np.ndarray]
    band: tuple[float, float] | None
    held: np.ndarray | None = None


def _in_water(compiled: CompiledScene) -> _Matrices:
    """The linear model's matrices about the static equilibrium, with A(omega) and B(omega) of the database."""
    lin = linearize(compiled)
    bw = lin.hydro_jacobian
    data_omega = lin.hydro.omega

    def mass(omega: float) -> np.ndarray:
        return lin.database_mass + bw.T @ lin.hydro.at(np.array([omega]))[0][0] @ bw

    def damping(omega: float) -> np.ndarray:
        return lin.damping + bw.T @ lin.hydro.at(np.array([omega]))[1][0] @ bw

    return _Matrices(
        lin.q0,
        lin.stiffness,
        lin.database_mass,
        mass,
        damping,
        (float(data_omega[0]), float(data_omega[-1])),
        lin.held,
    )


def _in_air(compiled: CompiledScene) -> _Matrices:
    """The compiled plant's matrices in air, about the device's rest without gravity (see the module docstring)."""
    p, model = compiled.plant, compiled.device.model
    statics = dataclasses.replace(compiled.statics, g=0.0, coupling=None)
    try:
        q = statics.equilibrium(model.neutral_configuration())
    except EquilibriumError as err:
        raise ValueError(
            f"device {compiled.device.name!r} has no rest in air (no gravity, no water) near its reference "
            f"configuration, so no modal table in air: {err}"
        ) from None
    rot, pos, b, _, _ = kinematics(p, q, np.zeros(model.nv))
    _, g = pto_strokes(p, q, rot, pos, b)
    mass = b.T @ body_mass_matrix(model, q) @ b
    mass = 0.5 * (mass + mass.T)
    damping = linear_damping(p, g, np.zeros((p.hydro_index.size, model.nv)))  # no moorings: no water
    held = np.asarray(model.quasi_static_velocities, dtype=bool)
    return _Matrices(
        q, statics.stiffness(q), mass, lambda omega: mass, lambda omega: damping, None, held if held.any() else None
    )


def modal_table(compiled: CompiledScene, *, water: bool = True, iterations: int = 50) -> xr.Dataset:
    """Natural periods [s], damping ratios [-] and mode shapes (largest entry 1) of every mode, in water about the
    static equilibrium or in air (see the module docstring).

    Modes without stiffness (a free surge) get an infinite period and no damping ratio (NaN). ``converged`` says
    whether each mode's fixed point converged within ``iterations`` (always true in air, where the mass does not
    depend on the frequency). The scene's controller must have linear gains (its damping and stiffness are
    included).

    A device with elastic bodies (``flexible.dynamics = "elastic"``) also gets each mode's shape on the nodes of
    their structures (dims ``node``, ``part``, ``axis``): ``node_position`` (where the node is about the
    equilibrium or rest, deflection included) [m], ``node_body``, and ``node_displacement`` [m] and
    ``node_rotation`` [rad] of the mode shape ``shape`` as scaled there, world axes, split into the ``global``
    part (the rigid motion of the body's floating frame carried to the node) and the ``elastic`` part (the
    Craig-Bampton basis Phi times the mode's modal coordinates); their sum over ``part`` is the node's motion
    (``wecss.linear._node_shapes``). Modal coordinates held quasi-static (``flexible.quasi_static_above``) are
    condensed (module docstring): one mode per kept coordinate, the shapes on every coordinate.

    Parameters
    ----------
    compiled : CompiledScene
    water : bool
        In water about the static equilibrium (default), or in air: no water, no gravity (as
        ``wecss.devices.structural_modes(device, water=False)``).
    iterations : int
        Fixed-point iterations per mode for A(omega) in water (to 1e-10 in the frequency; 0: the database's
        A_inf).

    Returns
    -------
    xarray.Dataset
        ``period``, ``converged``, ``damping_ratio``, ``shape`` (mode, dof) and, with elastic bodies, the node
        shapes above.

    Raises
    ------
    TypeError
        If ``compiled`` is not a CompiledScene.
    ValueError
        If the controller has no linear gains, ``water`` is not a bool, ``iterations`` not an integer >= 0, or (in
        air) the device has no rest without gravity and water.
    """
    if not isinstance(compiled, CompiledScene):
        raise TypeError(
            f"modal_table takes a CompiledScene (wecss.control.compile_scene(scene)); got {type(compiled).__name__}"
        )
    if not isinstance(water, bool | np.bool_):
        raise ValueError(
            f"water must be True (in water, about the static equilibrium) or False (in air: no water, no gravity); "
            f"got {water!r}"
        )
    if isinstance(iterations, bool) or not isinstance(iterations, int | np.integer) or iterations < 0:
        raise ValueError(f"iterations must be an integer >= 0 (0: the database's A_inf); got {iterations!r}")
    if not compiled.linear_controller:
        raise ValueError("the modal table needs a controller with linear gains (such as 'damping')")
    matrices = _in_water(compiled) if water else _in_air(compiled)
    solve = _modes if matrices.held is None else _condensed_modes
    periods, ratios, shapes, converged = solve(matrices, iterations)
    order = np.argsort(-periods, kind="stable")
    names = list(compiled.device.model.velocity_names)
    method = (
        "fixed point on A(omega); damping from B(omega) and PTO"
        if water
        else "in air: no water, no gravity, about the rest of the PTO springs and structure; damping from the PTO, "
        "the joints and the structure"
    )
    table = xr.Dataset(
        {
            "period": (
                ("mode",),
                periods[order],
                {
                    "long_name": "natural period (undamped, with the added mass at its own frequency)"
                    if water
                    else "natural period (undamped, in air)",
                    "units": "s",
                },
            ),
            "converged": (("mode",), converged[order], {"long_name": "fixed point converged"}),
            "damping_ratio": (("mode",), ratios[order], {"long_name": "modal damping ratio", "units": "1"}),
            "shape": (("mode", "dof"), shapes[order], {"long_name": "mode shape, largest entry 1", "units": "1"}),
        },
        coords={"mode": np.arange(periods.size), "dof": names},
        attrs={"device": compiled.device.name, "method": method},
    )
    if compiled.device.model.elastic_bodies:
        table = _with_nodes(table, compiled, matrices.q, shapes[order])
    return table


def _modes(matrices: _Matrices, iterations: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Periods [s], damping ratios, shapes (mode, dof) and convergence of every mode (see :func:`modal_table`)."""
    stiffness, mass, damping = matrices.stiffness, matrices.mass, matrices.damping
    values, vectors = eigh(stiffness, matrices.start)
    nv = values.size
    tiny = 1e-9 * max(1.0, float(np.max(np.abs(values))))
    periods = np.full(nv, np.inf)
    ratios = np.full(nv, np.nan)
    shapes = np.zeros((nv, nv))
    converged = np.ones(nv, dtype=bool)
    for j in range(nv):
        phi = vectors[:, j]
        if values[j] <= tiny:
            shapes[j] = phi / phi[np.argmax(np.abs(phi))]
            continue
        omega = float(np.sqrt(values[j]))
        if matrices.band is not None:
            converged[j] = False
            low, high = matrices.band
            for _ in range(iterations):
                w = float(np.clip(omega, low, high))
                vals, vecs = eigh(stiffness, mass(w))
                k = int(np.argmax(np.abs(vecs.T @ mass(w) @ phi)))  # the mode that continues phi
                phi = vecs[:, k]
                new = float(np.sqrt(max(vals[k], 0.0)))
                if abs(new - omega) <= 1e-10 * omega:
                    omega = new
                    converged[j] = True
                    break
                omega = new
            w = float(np.clip(omega, low, high))
        else:
            w = omega
        m_j = float(phi @ mass(w) @ phi)
        periods[j] = 2 * np.pi / omega
        ratios[j] = float(phi @ damping(w) @ phi) / (2 * m_j * omega)
        shapes[j] = phi / phi[np.argmax(np.abs(phi))]
    return periods, ratios, shapes, converged


def _condensed_modes(matrices: _Matrices, iterations: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """As :func:`_modes` with the coordinates ``matrices.held`` held quasi-static (no rate, no acceleration; the
    linear model's condensation, ``wecss.linear._model``): one mode per kept coordinate, the eigenvectors of the
    condensed pencil (P K[:, r], P M(omega)[:, r]) with P = [I, -K_rh K_hh^-1] (not symmetric: left and right
    vectors), the damping ratio psi' P C[:, r] phi / (2 omega psi' P M[:, r] phi) of the left and right vectors
    psi, phi, and the shape on every coordinate, the held ones' from their rows: phi_h = -K_hh^-1 (K_hr -
    omega^2 M_hr) phi_r."""
    assert matrices.held is not None
    stiffness, mass, damping = matrices.stiffness, matrices.mass, matrices.damping
    kept, out = np.flatnonzero(~matrices.held), np.flatnonzero(matrices.held)
    k_hh = stiffness[np.ix_(out, out)]
    transfer = np.linalg.solve(k_hh.T, stiffness[np.ix_(kept, out)].T).T  # K_rh K_hh^-1

    def condense(matrix: np.ndarray) -> np.ndarray:
        return matrix[np.ix_(kept, kept)] - transfer @ matrix[np.ix_(out, kept)]

    def pencil(m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Eigenvalues (ascending, real parts), left and right eigenvectors of (condensed K, m)."""
        values, left, right = eig(condense(stiffness), m, left=True, right=True)
        order = np.argsort(values.real)
        return values.real[order], left[:, order], right[:, order]

    values, lefts, rights = pencil(condense(matrices.start))
    n_r, nv = kept.size, stiffness.shape[0]
    tiny = 1e-9 * max(1.0, float(np.max(np.abs(values))))
    periods = np.full(n_r, np.inf)
    ratios = np.full(n_r, np.nan)
    shapes = np.zeros((n_r, nv))
    converged = np.ones(n_r, dtype=bool)
    for j in range(n_r):
        phi, psi = rights[:, j], lefts[:, j]
        omega = float(np.sqrt(max(values[j], 0.0)))
        w = omega
        if values[j] > tiny and matrices.band is not None:
            converged[j] = False
            low, high = matrices.band
            for _ in range(iterations):
                w = float(np.clip(omega, low, high))
                m = condense(mass(w))
                vals, lefts_w, rights_w = pencil(m)
                k = int(np.argmax(np.abs(lefts_w.conj().T @ m @ phi)))  # the mode that continues phi
                phi, psi = rights_w[:, k], lefts_w[:, k]
                new = float(np.sqrt(max(vals[k], 0.0)))
                if abs(new - omega) <= 1e-10 * omega:
                    omega = new
                    converged[j] = True
                    break
                omega = new
            w = float(np.clip(omega, low, high))
        phi = np.real(phi / phi[np.argmax(np.abs(phi))])  # a real vector of a real eigenvalue, scaled
        full = np.zeros(nv)
        full[kept] = phi
        if values[j] > tiny:
            rows = stiffness[np.ix_(out, kept)] - omega**2 * mass(w)[np.ix_(out, kept)]
            full[out] = -np.linalg.solve(k_hh, rows @ phi)
            periods[j] = 2 * np.pi / omega
            m_j = np.real(psi.conj() @ condense(mass(w)) @ phi)
            ratios[j] = float(np.real(psi.conj() @ condense(damping(w)) @ phi) / (2 * m_j * omega))
        else:
            full[out] = -np.linalg.solve(k_hh, stiffness[np.ix_(out, kept)] @ phi)
        shapes[j] = full / full[np.argmax(np.abs(full))]
    return periods, ratios, shapes, converged


def _with_nodes(table: xr.Dataset, compiled: CompiledScene, q: np.ndarray, shapes: np.ndarray) -> xr.Dataset:
    """``table`` with the mode shapes on the nodes of the device's elastic bodies (see :func:`modal_table`)."""
    nodes = node_maps(compiled.device, q)
    bodies = sorted(set(nodes.bodies), key=nodes.bodies.index)
    data = {
        "node_position": (("node", "axis"), nodes.position,
                          {"long_name": "structure node position about the equilibrium (world)", "units": "m"}),
        "node_body": (("node",), np.array(nodes.bodies, dtype=object), {"long_name": "elastic body of the node"}),
        "node_displacement": (("mode", "part", "node", "axis"), np.einsum("pnav,mv->mpna", nodes.displacement, shapes),
                              {"long_name": "mode shape: node translation (world) for the shape as scaled in "
                               "'shape', global (floating frame) and elastic parts", "units": "m"}),
        "node_rotation": (("mode", "part", "node", "axis"), np.einsum("pnav,mv->mpna", nodes.rotation, shapes),
                          {"long_name": "mode shape: node rotation (world) for the shape as scaled in 'shape', "
                           "global (floating frame) and elastic parts", "units": "rad"}),
    }  # fmt: skip
    out = table.assign(data).assign_coords(node=list(nodes.labels), part=list(PARTS), axis=["x", "y", "z"])
    out.attrs["elastic_bodies"] = ", ".join(bodies)
    return out


def format_modal_table(table: xr.Dataset) -> str:
    """The modal table as text lines (period, damping ratio, the three largest mode-shape entries)."""
    if str(table.attrs.get("method", "")).startswith("in air"):
        lines = ["natural periods in air (no water, no gravity), damping ratios (PTO, joints, structure), mode shapes:"]
    else:
        lines = [
            "natural periods with frequency-dependent added mass, damping ratios (radiation and PTO), mode shapes:"
        ]
    names = [str(n) for n in table.dof.values]
    for period, ratio, shape in zip(table.period.values, table.damping_ratio.values, table.shape.values, strict=True):
        top = np.argsort(np.abs(shape))[::-1][:3]
        entries = ", ".join(f"{names[k]} {shape[k]:+.2f}" for k in top if abs(shape[k]) > 0.05)
        text = "inf (no stiffness)" if np.isinf(period) else f"{period:8.3f} s  zeta {ratio:6.3f}"
        lines.append(f"  {text:>26s}  {entries}")
    return "\n".join(lines)
