"""Modal table of a device about its static equilibrium: natural periods (undamped, with the frequency-dependent
added mass), damping ratios and mode shapes.

For each mode, the frequency-dependent added mass is resolved by a fixed point: omega_j^2 = k_j / m_j(omega_j),
with k_j and m_j(omega) = phi' (M* + Bw' (A(omega) - A_inf) Bw) phi the modal stiffness and mass of the
undamped eigenvector phi of (K, M* + Bw' (A(omega_j) - A_inf) Bw); the damping ratio is
zeta_j = phi' (C + Bw' B(omega_j) Bw) phi / (2 m_j omega_j), with C the linear PTO damping. It uses the database's
A(omega) and B(omega) directly (no radiation fit) and neglects the modal coupling by damping.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from scipy.linalg import eigh

from ..compiled import CompiledScene
from ._model import linearize


def modal_table(compiled: CompiledScene, *, iterations: int = 50) -> xr.Dataset:
    """Natural periods [s], damping ratios [-] and mode shapes (largest entry 1) of every mode.

    Modes without stiffness (a free surge) get an infinite period and no damping ratio (NaN). ``converged`` says
    whether each mode's fixed point converged within ``iterations``. The scene's controller must have linear
    gains (its damping and stiffness are included).

    Raises
    ------
    ValueError
        If the controller has no linear gains.
    """
    if not compiled.linear_controller:
        raise ValueError("the modal table needs a controller with linear gains (such as 'damping')")
    lin = linearize(compiled)
    bw = lin.hydro_jacobian
    data_omega = lin.hydro.omega

    def mass(omega: float) -> np.ndarray:
        return lin.database_mass + bw.T @ lin.hydro.at(np.array([omega]))[0][0] @ bw

    def damping(omega: float) -> np.ndarray:
        return lin.damping + bw.T @ lin.hydro.at(np.array([omega]))[1][0] @ bw

    values, vectors = eigh(lin.stiffness, lin.database_mass)
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
        converged[j] = False
        for _ in range(iterations):
            w = float(np.clip(omega, data_omega[0], data_omega[-1]))
            vals, vecs = eigh(lin.stiffness, mass(w))
            k = int(np.argmax(np.abs(vecs.T @ mass(w) @ phi)))  # the mode that continues phi
            phi = vecs[:, k]
            new = float(np.sqrt(max(vals[k], 0.0)))
            if abs(new - omega) <= 1e-10 * omega:
                omega = new
                converged[j] = True
                break
            omega = new
        w = float(np.clip(omega, data_omega[0], data_omega[-1]))
        m_j = float(phi @ mass(w) @ phi)
        periods[j] = 2 * np.pi / omega
        ratios[j] = float(phi @ damping(w) @ phi) / (2 * m_j * omega)
        shapes[j] = phi / phi[np.argmax(np.abs(phi))]
    order = np.argsort(-periods, kind="stable")
    names = list(compiled.device.model.velocity_names)
    return xr.Dataset(
        {
            "period": (
                ("mode",),
                periods[order],
                {"long_name": "natural period (undamped, with the added mass at its own frequency)", "units": "s"},
            ),
            "converged": (("mode",), converged[order], {"long_name": "fixed point converged"}),
            "damping_ratio": (("mode",), ratios[order], {"long_name": "modal damping ratio", "units": "1"}),
            "shape": (("mode", "dof"), shapes[order], {"long_name": "mode shape, largest entry 1", "units": "1"}),
        },
        coords={"mode": np.arange(nv), "dof": names},
        attrs={"device": compiled.device.name, "method": "fixed point on A(omega); damping from B(omega) and PTO"},
    )


def format_modal_table(table: xr.Dataset) -> str:
    """The modal table as text lines (period, damping ratio, the three largest mode-shape entries)."""
    lines = ["natural periods with frequency-dependent added mass, damping ratios (radiation and PTO), mode shapes:"]
    names = [str(n) for n in table.dof.values]
    for period, ratio, shape in zip(table.period.values, table.damping_ratio.values, table.shape.values, strict=True):
        top = np.argsort(np.abs(shape))[::-1][:3]
        entries = ", ".join(f"{names[k]} {shape[k]:+.2f}" for k in top if abs(shape[k]) > 0.05)
        text = "inf (no stiffness)" if np.isinf(period) else f"{period:8.3f} s  zeta {ratio:6.3f}"
        lines.append(f"  {text:>26s}  {entries}")
    return "\n".join(lines)
