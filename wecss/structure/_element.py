"""The 3D frame element: a straight beam between two nodes with six DOFs each (Euler-Bernoulli, or Timoshenko with
shear deformation).

Local axes (rows of ``axes``): x from node i to node j, y and z the section's principal axes (see
``wecss.structure._section``). Local DOFs, per node: u, v, w (displacements along x, y, z [m]) and theta_x,
theta_y, theta_z (rotations [rad]); node i's six, then node j's. Bending in the x-y plane uses v and theta_z
(theta_z = dv/ds for Euler-Bernoulli), in the x-z plane w and theta_y (theta_y = -dw/ds).

Interpolation, xi = s / L in [0, 1]: linear for u and theta_x; for bending, the interdependent interpolation of a
Timoshenko beam (exact for a beam loaded at its ends; cubic Hermite functions when the shear parameter
Phi = 12 E I / (G A_s L^2) is 0, the Euler-Bernoulli beam). Every matrix follows from these functions:

- stiffness: the closed form of the element (Przemieniecki), axial E A / L, torsion G J / L, bending with Phi;
- consistent mass: integral of mu N_u' N_u + N_theta' diag(rho Ip, rho Iy, rho Iz) N_theta over the element, with
  mu the mass per length (rho A plus non-structural mass) and the rotary inertia of bending optional (Euler-Bernoulli
  closed forms leave it out); the polar inertia rho Ip is always there;
- geometric stiffness per unit axial force: integral of N(s) (v'^2 + w'^2 + (Ip / A) theta_x'^2) (the transverse
  terms and Wagner's torsion term), for an axial force N(s) (tension positive) given at stations along the element;
- consistent loads: integral of N_u' q + N_theta' m for a line load q and a line moment m.

Integrals by 4-point Gauss-Legendre quadrature, exact for the element's polynomials (degree 6 at most; an axial
force varying at most quadratically along the element).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ._material import Material
from ._section import Section

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(4)
GAUSS_POINTS: np.ndarray = (np.asarray(_NODES) + 1) / 2
GAUSS_WEIGHTS: np.ndarray = np.asarray(_WEIGHTS) / 2
"""Stations xi in [0, 1] and weights (summing to 1) of the element's quadrature."""

NODE_DOFS = 6
"""DOFs per node: three displacements and three rotations."""

_XY = np.array([1, 5, 7, 11])  # v1, theta_z1, v2, theta_z2
_XZ = np.array([2, 4, 8, 10])  # w1, theta_y1, w2, theta_y2
_XZ_SIGN = np.array([1.0, -1.0, 1.0, -1.0])  # theta_y = -dw/ds


def _plane(xi: float, length: float, phi: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Deflection N, its slope dN/ds and the section rotation Theta (4,) of one bending plane at ``xi``, for the DOFs
    (deflection, rotation) at both ends, with the rotation positive along the slope (Theta = dN/ds when phi = 0)."""
    x2, x3 = xi * xi, xi * xi * xi
    c = 1.0 / (1.0 + phi)
    n = c * np.array(
        [
            1 - 3 * x2 + 2 * x3 + phi * (1 - xi),
            length * (xi - 2 * x2 + x3 + phi * (xi - x2) / 2),
            3 * x2 - 2 * x3 + phi * xi,
            length * (-x2 + x3 - phi * (xi - x2) / 2),
        ]
    )
    dn = (c / length) * np.array(
        [
            -6 * xi + 6 * x2 - phi,
            length * (1 - 4 * xi + 3 * x2 + phi * (1 - 2 * xi) / 2),
            6 * xi - 6 * x2 + phi,
            length * (-2 * xi + 3 * x2 - phi * (1 - 2 * xi) / 2),
        ]
    )
    theta = c * np.array(
        [
            6 * (x2 - xi) / length,
            1 - 4 * xi + 3 * x2 + phi * (1 - xi),
            6 * (xi - x2) / length,
            -2 * xi + 3 * x2 + phi * xi,
        ]
    )
    return n, dn, theta


def shape_functions(
    xi: float, length: float, phi_y: float = 0.0, phi_z: float = 0.0
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Interpolation at ``xi`` in local axes: displacement N_u (3, 12) [m per DOF], rotation N_theta (3, 12), the
    displacement's derivative along the element dN_u/ds (3, 12) and the twist rate dtheta_x/ds (12,).

    ``phi_y`` is the shear parameter of bending in the x-y plane (12 E Iz / (G A_sy L^2)), ``phi_z`` of the x-z
    plane (12 E Iy / (G A_sz L^2)); 0 for Euler-Bernoulli.
    """
    nu = np.zeros((3, 12))
    nth = np.zeros((3, 12))
    dnu = np.zeros((3, 12))
    twist = np.zeros(12)
    nu[0, [0, 6]] = (1 - xi, xi)
    dnu[0, [0, 6]] = (-1 / length, 1 / length)
    nth[0, [3, 9]] = (1 - xi, xi)
    twist[[3, 9]] = (-1 / length, 1 / length)
    n, dn, theta = _plane(xi, length, phi_y)
    nu[1, _XY], dnu[1, _XY], nth[2, _XY] = n, dn, theta
    n, dn, theta = _plane(xi, length, phi_z)
    nu[2, _XZ], dnu[2, _XZ], nth[1, _XZ] = n * _XZ_SIGN, dn * _XZ_SIGN, -theta * _XZ_SIGN
    return nu, nth, dnu, twist


def _bending_stiffness(ei: float, length: float, phi: float) -> np.ndarray:
    """(4, 4) stiffness of one bending plane on (deflection, rotation) at both ends, rotation along the slope."""
    c = ei / ((1 + phi) * length**3)
    L = length
    return c * np.array(
        [
            [12, 6 * L, -12, 6 * L],
            [6 * L, (4 + phi) * L**2, -6 * L, (2 - phi) * L**2],
            [-12, -6 * L, 12, -6 * L],
            [6 * L, (2 - phi) * L**2, -6 * L, (4 + phi) * L**2],
        ]
    )


THEORIES = ("euler-bernoulli", "timoshenko")
"""Beam theories: without and with shear deformation (Timoshenko adds the rotary inertia of bending too)."""


@dataclass(frozen=True, eq=False)
class BeamElement:
    """One frame element between nodes ``i`` and ``j`` (indices into its frame's nodes).

    Parameters
    ----------
    i, j : int
        Node indices.
    start, end : ndarray (3,)
        Node positions in body axes [m].
    axes : ndarray (3, 3)
        Rows x, y, z of the local axes in body axes (x along the element).
    section : Section
    material : Material
    nonstructural_mass : float
        Mass per length carried on the axis beyond rho A (fittings, paint, ballast) [kg/m].
    theory : str
        ``"euler-bernoulli"`` or ``"timoshenko"`` (needs the section's shear areas).
    rotary_inertia : bool
        Whether the rotary inertia of bending (rho Iy, rho Iz) is in the mass (always with Timoshenko). The polar
        inertia rho Ip is always in it.
    member : str
        Name of the member the element belongs to.
    station : float
        Distance of node i from the member's start [m].

    Raises
    ------
    ValueError
        On an unknown theory, a Timoshenko beam without shear areas, a section without a torsion constant, or axes
        that are not orthonormal with x along the element.
    """

    i: int
    j: int
    start: np.ndarray
    end: np.ndarray
    axes: np.ndarray
    section: Section
    material: Material
    nonstructural_mass: float = 0.0
    theory: str = "euler-bernoulli"
    rotary_inertia: bool = False
    member: str = ""
    station: float = 0.0

    def __post_init__(self) -> None:
        where = f"member {self.member!r} element at {self.station:.6g} m"
        if self.theory not in THEORIES:
            raise ValueError(f"{where}: theory {self.theory!r}; accepted: {list(THEORIES)}")
        if self.section.torsion_constant is None:
            raise ValueError(f"{where}: the {self.section.kind} section has no torsion_constant [m^4]; give one")
        if self.theory == "timoshenko" and (self.section.shear_area_y is None or self.section.shear_area_z is None):
            raise ValueError(f"{where}: a Timoshenko beam needs the section's shear_area_y and shear_area_z [m^2]")
        if not (np.isfinite(self.nonstructural_mass) and self.nonstructural_mass >= 0):
            raise ValueError(f"{where}: nonstructural_mass must be >= 0 [kg/m], got {self.nonstructural_mass!r}")
        axes = np.asarray(self.axes, dtype=float)
        d = np.asarray(self.end, dtype=float) - np.asarray(self.start, dtype=float)
        if not (
            np.allclose(axes @ axes.T, np.eye(3), atol=1e-12)
            and np.linalg.det(axes) > 0
            and np.allclose(axes[0] * np.linalg.norm(d), d, rtol=0, atol=1e-12 * max(1.0, float(np.abs(d).max())))
        ):
            raise ValueError(f"{where}: axes must be right-handed orthonormal rows with x from start to end")

    @property
    def length(self) -> float:
        """[m]."""
        return float(np.linalg.norm(np.asarray(self.end) - np.asarray(self.start)))

    @property
    def mass_per_length(self) -> float:
        """mu = rho A + non-structural mass [kg/m]."""
        return self.material.density * self.section.area + self.nonstructural_mass

    @property
    def shear_parameters(self) -> tuple[float, float]:
        """(Phi_y, Phi_z): 12 E Iz / (G A_sy L^2) for bending in x-y and 12 E Iy / (G A_sz L^2) in x-z [-]; zeros
        for Euler-Bernoulli."""
        if self.theory != "timoshenko":
            return 0.0, 0.0
        s, m, L = self.section, self.material, self.length
        assert s.shear_area_y is not None and s.shear_area_z is not None
        e, g = m.youngs_modulus, m.shear_modulus
        return 12 * e * s.iz / (g * s.shear_area_y * L**2), 12 * e * s.iy / (g * s.shear_area_z * L**2)

    @property
    def section_inertia(self) -> np.ndarray:
        """Rotary inertia per length about the local axes, diag(rho Ip, rho Iy, rho Iz) [kg m], with the bending
        terms zero when the rotary inertia is left out."""
        rho, s = self.material.density, self.section
        bending = 1.0 if (self.rotary_inertia or self.theory == "timoshenko") else 0.0
        return np.diag([rho * s.polar, bending * rho * s.iy, bending * rho * s.iz])

    @cached_property
    def transform(self) -> np.ndarray:
        """T (12, 12): local DOFs = T @ body-axes DOFs."""
        return np.kron(np.eye(4), np.asarray(self.axes, dtype=float))

    def functions(self, xi: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """:func:`shape_functions` of this element at ``xi``, in local axes."""
        phi_y, phi_z = self.shear_parameters
        return shape_functions(xi, self.length, phi_y, phi_z)

    @cached_property
    def local_stiffness(self) -> np.ndarray:
        """K_e (12, 12) in local axes [N/m, N, N m/rad]."""
        s, m, L = self.section, self.material, self.length
        assert s.torsion_constant is not None
        phi_y, phi_z = self.shear_parameters
        k = np.zeros((12, 12))
        ea = m.youngs_modulus * s.area / L
        k[np.ix_([0, 6], [0, 6])] = ea * np.array([[1, -1], [-1, 1]])
        gj = m.shear_modulus * s.torsion_constant / L
        k[np.ix_([3, 9], [3, 9])] = gj * np.array([[1, -1], [-1, 1]])
        k[np.ix_(_XY, _XY)] = _bending_stiffness(m.youngs_modulus * s.iz, L, phi_y)
        sign = np.outer(_XZ_SIGN, _XZ_SIGN)
        k[np.ix_(_XZ, _XZ)] = sign * _bending_stiffness(m.youngs_modulus * s.iy, L, phi_z)
        return k

    @cached_property
    def local_mass(self) -> np.ndarray:
        """Consistent mass M_e (12, 12) in local axes [kg, kg m, kg m^2]."""
        mu, inertia, L = self.mass_per_length, self.section_inertia, self.length
        out = np.zeros((12, 12))
        for xi, w in zip(GAUSS_POINTS, GAUSS_WEIGHTS, strict=True):
            nu, nth, _, _ = self.functions(xi)
            out += w * L * (mu * nu.T @ nu + nth.T @ inertia @ nth)
        return 0.5 * (out + out.T)

    def local_geometric_stiffness(self, axial_force: np.ndarray | float) -> np.ndarray:
        """Geometric stiffness (12, 12) in local axes for the axial force N(s) [N] (tension positive): one value
        (constant) or values at equally spaced stations from node i to node j (2: linear, 3: quadratic)."""
        values = np.atleast_1d(np.asarray(axial_force, dtype=float))
        if values.ndim != 1 or values.size < 1:
            raise ValueError(f"axial_force must be one value or values at stations along the element; got {values!r}")
        stations = np.linspace(0.0, 1.0, values.size) if values.size > 1 else np.zeros(1)
        s, L = self.section, self.length
        wagner = s.polar / s.area
        out = np.zeros((12, 12))
        for xi, w in zip(GAUSS_POINTS, GAUSS_WEIGHTS, strict=True):
            n = _lagrange(stations, values, xi)
            _, _, dnu, twist = self.functions(xi)
            out += w * L * n * (dnu[1:].T @ dnu[1:] + wagner * np.outer(twist, twist))
        return 0.5 * (out + out.T)

    @property
    def stiffness(self) -> np.ndarray:
        """K_e (12, 12) in body axes."""
        t = self.transform
        return t.T @ self.local_stiffness @ t

    @property
    def mass(self) -> np.ndarray:
        """M_e (12, 12) in body axes."""
        t = self.transform
        return t.T @ self.local_mass @ t

    def geometric_stiffness(self, axial_force: np.ndarray | float) -> np.ndarray:
        """K_G (12, 12) in body axes (see :meth:`local_geometric_stiffness`)."""
        t = self.transform
        return t.T @ self.local_geometric_stiffness(axial_force) @ t

    def quadrature(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The element as mass points of its quadrature, in body axes: positions (4, 3) [m], masses (4,) [kg],
        rotary inertias (4, 3, 3) [kg m^2] and the interpolation of displacement and rotation at the points on the
        element's body-axes DOFs, N_u and N_theta (4, 3, 12). Sums over them give the consistent mass exactly."""
        axes, L = np.asarray(self.axes, dtype=float), self.length
        t = self.transform
        start, end = np.asarray(self.start, dtype=float), np.asarray(self.end, dtype=float)
        positions = np.array([start + xi * (end - start) for xi in GAUSS_POINTS])
        masses = GAUSS_WEIGHTS * L * self.mass_per_length
        inertia = np.array([w * L * axes.T @ self.section_inertia @ axes for w in GAUSS_WEIGHTS])
        nu = np.zeros((4, 3, 12))
        nth = np.zeros((4, 3, 12))
        for k, xi in enumerate(GAUSS_POINTS):
            a, b, _, _ = self.functions(xi)
            nu[k] = axes.T @ a @ t
            nth[k] = axes.T @ b @ t
        return positions, masses, inertia, nu, nth


def _lagrange(stations: np.ndarray, values: np.ndarray, xi: float) -> float:
    """The polynomial through (stations, values) at xi (a constant for one value)."""
    if stations.size == 1:
        return float(values[0])
    out = 0.0
    for k, (sk, vk) in enumerate(zip(stations, values, strict=True)):
        others = np.delete(stations, k)
        out += vk * float(np.prod((xi - others) / (sk - others)))
    return out
