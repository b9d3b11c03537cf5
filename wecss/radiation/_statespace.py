"""State-space radiation models K(t) = C exp(A t) B, their frequency response and their checks.

The radiation force is F = -C x with x_dot = A x + B v (v the body velocities). In frequency,
K_hat(omega) = C (i omega I - A)^-1 B = B(omega) + i omega (A(omega) - A_inf) (e^{+i omega t} convention).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

MAX_REPAIR_VARIABLES: int = 1000
"""Passivity repair is a semidefinite program in the non-zero residues up to this many; above, a first-order
least-norm iteration (cheaper, and not always able to reach a non-negative margin: the report says)."""

MAX_REPAIR_STATES: int = 500
"""Above this many states no repair is attempted (the report says so): fit fewer states instead."""

MAX_LMI_FREQUENCIES: int = 12
"""Frequencies added to the passivity LMIs per round (the worst local minima of the margin)."""

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


def _state_response(model: RadiationStateSpace, omega: np.ndarray) -> np.ndarray:
    """G(omega) = (i omega I - A)^-1 B for every omega, (n_omega, n_x, n_dof), block by block."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components

    out = np.zeros((omega.size, model.n_states, len(model.dofs)), dtype=complex)
    _, labels = connected_components(csr_matrix((model.A != 0) | (model.A.T != 0)), directed=False)
    for label in np.unique(labels):
        idx = np.flatnonzero(labels == label)
        lam, vec = np.linalg.eig(model.A[np.ix_(idx, idx)])
        right = np.linalg.solve(vec, model.B[idx])
        out[:, idx, :] = np.einsum("ak,wk,kj->waj", vec, 1.0 / (1j * omega[:, None] - lam[None, :]), right)
    return out


def passivity_grid(omega_max_data: float, n: int = 4000) -> np.ndarray:
    """Frequencies for the passivity check: 0 to ten times the highest data frequency, denser at low omega."""
    top = 10 * omega_max_data
    return np.unique(np.concatenate([np.linspace(0.0, top, n // 2), np.geomspace(1e-4, top, n // 2)]))


@dataclass(frozen=True)
class Repair:
    """What :func:`enforce_stability` and :func:`enforce_passivity` changed."""

    reflected_poles: int = 0
    passivity_iterations: int = 0
    residue_change: float = 0.0
    margin_before: float = float("nan")
    margin_after: float = float("nan")
    skipped: int = 0

    def __str__(self) -> str:
        parts = []
        if self.skipped:
            parts.append(
                f"NOT PASSIVE (margin {self.margin_before:.3g}); repair not attempted: {self.skipped} states "
                f"exceed MAX_REPAIR_STATES = {MAX_REPAIR_STATES}"
            )
        if self.reflected_poles:
            parts.append(f"reflected {self.reflected_poles} unstable poles")
        if self.passivity_iterations and not self.margin_after >= 0:
            parts.append(
                f"NOT PASSIVE: repair failed after {self.passivity_iterations} rounds (margin "
                f"{self.margin_before:.3g} -> {self.margin_after:.3g})"
            )
        elif self.passivity_iterations:
            parts.append(
                f"restored passivity in {self.passivity_iterations} iterations (residues changed by "
                f"{self.residue_change:.2e} relative; margin {self.margin_before:.3g} -> {self.margin_after:.3g})"
            )
        return "; ".join(parts) if parts else "no repair needed"


def _local_minima_below(margin: np.ndarray, target: float) -> tuple[np.ndarray, list[int]]:
    """Indices where the passivity margin is below ``target``, and those among them that are local minima."""
    bad = np.flatnonzero(margin < target)
    last = margin.size - 1
    local = [
        int(k) for k in bad if (k == 0 or margin[k] <= margin[k - 1]) and (k == last or margin[k] <= margin[k + 1])
    ]
    return bad, local


def _hermitian_part_eigh(c: np.ndarray, g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigen-decomposition of (K_hat + K_hat^H)/2 with K_hat = C G(omega), at every omega."""
    h = np.einsum("ia,waj->wij", c, g)
    return np.linalg.eigh(0.5 * (h + np.conj(np.swapaxes(h, 1, 2))))


def _repair_target(model: RadiationStateSpace, omega: np.ndarray) -> float:
    """Small positive margin the repairs aim at: 1e-6 of the largest diagonal damping on the grid."""
    diag = np.real(np.diagonal(model.frequency_response(omega), axis1=1, axis2=2))
    return 1e-6 * float(np.max(np.abs(diag)))


def _repaired(
    model: RadiationStateSpace, c: np.ndarray, omega: np.ndarray, before: float, rounds: int
) -> tuple[RadiationStateSpace, Repair]:
    """The model with output matrix ``c`` and the report of what the repair changed."""
    repaired = model.with_matrices(C=c)
    after = float(repaired.passivity(omega).min())
    change = float(np.linalg.norm(c - model.C)) / max(float(np.linalg.norm(model.C)), 1e-300)
    return repaired, Repair(0, rounds, change, before, after)


def enforce_passivity(
    model: RadiationStateSpace, omega: np.ndarray, *, max_rounds: int = 12
) -> tuple[RadiationStateSpace, Repair]:
    """Perturb the output matrix C (the residues) as little as possible (Frobenius norm, within C's sparsity
    pattern) until the smallest eigenvalue of (K_hat + K_hat^H)/2 is non-negative at every ``omega``.

    K_hat(omega) = C G(omega) with G = (i omega I - A)^-1 B is linear in C, so the condition at one frequency is a
    linear matrix inequality in C. Each round solves the convex problem with the LMIs at the frequencies found
    violated so far (cvxpy), then checks the whole grid and adds the new local minima of the margin.
    """
    import cvxpy as cp

    before = float(model.passivity(omega).min())
    if before >= 0:
        return model, Repair(margin_before=before, margin_after=before)
    if model.n_states > MAX_REPAIR_STATES:
        return model, Repair(margin_before=before, margin_after=before, skipped=model.n_states)
    if int(np.count_nonzero(model.C)) > MAX_REPAIR_VARIABLES:
        return _enforce_passivity_linearised(model, omega, before)
    g = _state_response(model, omega)  # (w, nx, n)
    n = model.C.shape[0]
    mask = model.C != 0
    target = _repair_target(model, omega)
    chosen: list[int] = []
    c = model.C
    rounds = 0
    for rounds in range(1, max_rounds + 1):  # noqa: B007 - reported below
        margin = _hermitian_part_eigh(c, g)[0][:, 0]
        if margin.min() >= 0:
            break
        _, local = _local_minima_below(margin, target)
        worst = sorted(local, key=lambda k: margin[k])[:MAX_LMI_FREQUENCIES]
        chosen = sorted({*chosen, *worst})
        delta = cp.Variable(model.C.shape)
        c_var = model.C + cp.multiply(mask.astype(float), delta)
        constraints = []
        for k in chosen:
            re_x = c_var @ g[k].real
            im_x = c_var @ g[k].imag
            re_h = (re_x + re_x.T) / 2
            im_h = (im_x - im_x.T) / 2
            block = cp.bmat([[re_h, -im_h], [im_h, re_h]])
            constraints.append((block + block.T) / 2 >> 2 * target * np.eye(2 * n))
        problem = cp.Problem(cp.Minimize(cp.sum_squares(cp.multiply(mask.astype(float), delta))), constraints)
        try:
            problem.solve(solver=cp.CLARABEL)
        except cp.error.SolverError:
            problem.solve(solver=cp.SCS)
        if delta.value is None:  # the solver failed: fall back on the first-order iteration
            return _enforce_passivity_linearised(model, omega, before)
        c = model.C + mask * delta.value
    return _repaired(model, c, omega, before, rounds)


def _enforce_passivity_linearised(
    model: RadiationStateSpace, omega: np.ndarray, before: float, *, max_iterations: int = 40
) -> tuple[RadiationStateSpace, Repair]:
    """First-order passivity repair for models too large for the LMIs: at the worst local minima of the margin,
    d lambda_min = u' Re(dC G u) is linear in dC; each iteration takes the least-norm dC (within C's pattern) that
    lifts them to a small positive margin, halving the step until the total squared violation decreases."""
    g = _state_response(model, omega)
    mask = model.C != 0
    target = _repair_target(model, omega)

    c = model.C.copy()
    vals, vecs = _hermitian_part_eigh(c, g)
    iterations = 0
    for iterations in range(1, max_iterations + 1):  # noqa: B007 - reported below
        margin = vals[:, 0]
        if margin.min() >= 0:
            break
        bad, local = _local_minima_below(margin, target)
        picks = sorted({*local, *bad[:: max(1, bad.size // 40)].tolist()})
        rows = np.array([np.real(np.outer(vecs[k, :, 0].conj(), g[k] @ vecs[k, :, 0]))[mask] for k in picks])
        rhs = np.array([2 * target - margin[k] for k in picks])
        delta = rows.T @ np.linalg.lstsq(rows @ rows.T, rhs, rcond=None)[0]
        violation = float(np.sum(np.minimum(margin, 0.0) ** 2))
        step = 1.0
        for _ in range(12):  # accept the first step that lowers the total violation
            trial = c.copy()
            trial[mask] += step * delta
            trial_vals, trial_vecs = _hermitian_part_eigh(trial, g)
            if float(np.sum(np.minimum(trial_vals[:, 0], 0.0) ** 2)) < violation:
                break
            step /= 2
        else:
            break
        c, vals, vecs = trial, trial_vals, trial_vecs
    return _repaired(model, c, omega, before, iterations)
