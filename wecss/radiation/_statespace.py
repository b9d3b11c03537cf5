"""State-space radiation models K(t) = C exp(A t) B, their frequency response and their checks.

The radiation force is F = -C x with x_dot = A x + B v (v the body velocities). In frequency,
K_hat(omega) = C (i omega I - A)^-1 B = B(omega) + i omega (A(omega) - A_inf) (e^{+i omega t} convention).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

STABILITY_DAMPING: float = 1e-3
"""Smallest accepted damping ratio -Re(s)/|s| of a pole."""


@dataclass(frozen=True)
class RadiationStateSpace:
    """A state-space realisation of the radiation kernel of ``dofs``.

    Attributes
    ----------
    A : ndarray (n_x, n_x)
    B : ndarray (n_x, n_dof)
        Input: the velocities of the DOFs [m/s, rad/s].
    C : ndarray (n_dof, n_x)
        Output: the memory force is -C x [N, N m].
    dofs : tuple of str
    method : str
        How it was made (``"prony"``, ``"era"``, ``"era-mimo"``, or given).
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    dofs: tuple[str, ...]
    method: str = "given"

    def __post_init__(self) -> None:
        nx = self.A.shape[0]
        if self.A.shape != (nx, nx) or self.B.shape[0] != nx or self.C.shape[1] != nx:
            raise ValueError(f"inconsistent shapes A {self.A.shape}, B {self.B.shape}, C {self.C.shape}")
        if self.B.shape[1] != len(self.dofs) or self.C.shape[0] != len(self.dofs):
            raise ValueError(f"B and C must have one column / row per DOF ({len(self.dofs)})")

    @property
    def n_states(self) -> int:
        """Number of radiation states."""
        return int(self.A.shape[0])

    def poles(self) -> np.ndarray:
        """Eigenvalues of A [1/s]."""
        return self.modal()[0]

    def modal(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Modal form (poles, C V, V^-1 B) with A = V diag(poles) V^-1, computed once.

        A is split into its independent diagonal blocks first (connected components of its sparsity pattern), so
        that the many small blocks of a per-entry fit cost one small eigen-decomposition each.
        """
        cached = self.__dict__.get("_modal")
        if cached is not None:
            return cached
        nx = self.n_states
        poles = np.zeros(nx, dtype=complex)
        left = np.zeros((len(self.dofs), nx), dtype=complex)
        right = np.zeros((nx, len(self.dofs)), dtype=complex)
        if nx:
            from scipy.sparse import csr_matrix
            from scipy.sparse.csgraph import connected_components

            _, labels = connected_components(csr_matrix((self.A != 0) | (self.A.T != 0)), directed=False)
            for label in np.unique(labels):
                idx = np.flatnonzero(labels == label)
                lam, vec = np.linalg.eig(self.A[np.ix_(idx, idx)])
                poles[idx] = lam
                left[:, idx] = self.C[:, idx] @ vec
                right[idx] = np.linalg.solve(vec, self.B[idx])
        result = (poles, left, right)
        object.__setattr__(self, "_modal", result)
        return result

    def min_damping_ratio(self) -> float:
        """Smallest -Re(s)/|s| over the poles (inf without states)."""
        s = self.poles()
        if s.size == 0:
            return float("inf")
        return float(np.min(-s.real / np.maximum(np.abs(s), 1e-300)))

    def is_stable(self, damping: float = STABILITY_DAMPING) -> bool:
        """All poles in the left half-plane with damping ratio at least ``damping``."""
        return self.min_damping_ratio() >= damping

    def kernel(self, time: np.ndarray) -> np.ndarray:
        """K(t) (n_t, n_dof, n_dof) at ``time`` [s], through the eigen-decomposition of A."""
        time = np.atleast_1d(np.asarray(time, dtype=float))
        n = len(self.dofs)
        if self.n_states == 0:
            return np.zeros((time.size, n, n))
        lam, left, right = self.modal()
        return np.real(np.einsum("ik,tk,kj->tij", left, np.exp(np.outer(time, lam)), right, optimize=True))

    def frequency_response(self, omega: np.ndarray) -> np.ndarray:
        """K_hat(omega) = C (i omega I - A)^-1 B (n_omega, n_dof, n_dof), complex."""
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        n = len(self.dofs)
        if self.n_states == 0:
            return np.zeros((omega.size, n, n), dtype=complex)
        lam, left, right = self.modal()
        return np.einsum("ik,wk,kj->wij", left, 1.0 / (1j * omega[:, None] - lam[None, :]), right, optimize=True)

    def passivity(self, omega: np.ndarray) -> np.ndarray:
        """Smallest eigenvalue of (K_hat + K_hat^H) / 2 at each ``omega`` [N s/m and N m s/rad mixed]."""
        h = self.frequency_response(omega)
        return np.linalg.eigvalsh(0.5 * (h + np.conj(np.swapaxes(h, 1, 2))))[:, 0]

    def half_modal(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """One complex mode per conjugate pair (upper half-plane) and per real pole: (poles, C V, V^-1 B, pair),
        ``pair`` True for the pairs. The kernel is sum over these modes of Re or 2 Re of C V e^{pole t} V^-1 B."""
        lam, left, right = self.modal()
        tol = 1e-9 * np.maximum(np.abs(lam), 1e-300)
        keep = lam.imag >= -tol
        return lam[keep], left[:, keep], right[keep], (lam.imag > tol)[keep]

    def real_modal(self) -> RadiationStateSpace:
        """The same kernel in real modal form: A block-diagonal with [[s, -w], [w, s]] per conjugate pair s +- i w
        (and s per real pole), so that A is sparse and the model is small to store."""
        lam, left, right, pair = self.half_modal()
        blocks, b_rows, c_cols = [], [], []
        for k in range(lam.size):
            if pair[k]:
                # z = x_re + i x_im per pair; K = 2 Re(left z)
                s, w = lam[k].real, lam[k].imag
                blocks.append(np.array([[s, -w], [w, s]]))
                b_rows += [right[k].real, right[k].imag]
                c_cols += [2 * left[:, k].real, -2 * left[:, k].imag]
            else:
                blocks.append(np.array([[lam[k].real]]))
                b_rows.append(right[k].real)
                c_cols.append(left[:, k].real)
        n = sum(b.shape[0] for b in blocks)
        a = np.zeros((n, n))
        i = 0
        for block in blocks:
            m = block.shape[0]
            a[i : i + m, i : i + m] = block
            i += m
        b = np.array(b_rows).reshape(n, len(self.dofs))
        c = np.array(c_cols).reshape(n, len(self.dofs)).T
        return replace(self, A=a, B=b, C=c)

    def with_matrices(
        self, *, A: np.ndarray | None = None, B: np.ndarray | None = None, C: np.ndarray | None = None
    ) -> RadiationStateSpace:
        """A copy with some of A, B, C replaced."""
        return replace(
            self,
            A=self.A if A is None else A,
            B=self.B if B is None else B,
            C=self.C if C is None else C,
        )
