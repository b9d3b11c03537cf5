"""Exact discrete-time runs of a linear system x' = A x + B u in its modal coordinates.

A dense recursion x_{k+1} = Phi x_k + ... costs n^2 per step (n = 414 states for m4-134 with its radiation
states); in modal coordinates it costs n. The states split in two:

- free states: those no state depends on (A[:, free] = 0, such as a free surge displacement). They are pure
  integrators, x_free' = A[free, rest] x_rest + B[free] u, which would make A defective (a Jordan block with the
  velocity mode at zero); they are integrated over each step exactly instead;
- the rest, A[rest, rest] = V diag(poles) V^-1, diagonalisable (checked through the condition number of V).
  One mode of each conjugate pair is kept: x_rest = Re(shapes z), with the factor 2 of the pairs in ``shapes``.

With the phi-functions of ``wecss.compiled.phi_functions`` and s = pole h, over a step h with inputs linear
in time (first-order hold; zero-order hold keeps u_k):

    z_{k+1} = e^s z_k + h [(phi_1 - phi_2) u_k + phi_2 u_{k+1}] b                    (FOH)
    int_step z = h phi_1 z_k + h^2 [(phi_2 - phi_3) u_k + phi_3 u_{k+1}] b

with b = V^-1 B[rest] per mode; the free states gain A[free, rest] Re(shapes int_step z) + B[free] int_step u.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..compiled import JIT
from ..compiled.kernels import complex_columns, phi_functions, real_part_rows, reduction_kernel

CONDITION_LIMIT: float = 1e8
"""Largest accepted condition number of the eigenvector matrix (beyond it the modal form loses accuracy)."""


class NotDiagonalisable(ValueError):
    """The state matrix (without its free states) has no well-conditioned eigenvector basis."""


@dataclass(frozen=True)
class ModalForm:
    """A state matrix split into free states and modes (see the module docstring).

    Attributes
    ----------
    n_states : int
    free, rest : ndarray of int
        Indices of the free states and of the others.
    poles : complex ndarray (n_modes,)
        One pole per conjugate pair (upper half-plane) and the real poles [1/s].
    shapes : complex ndarray (n_rest, n_modes)
        x_rest = Re(shapes z).
    inverse : complex ndarray (n_modes, n_rest)
        Rows of V^-1 of the kept modes: z = inverse x_rest.
    coupling : ndarray (n_free, n_rest)
        A[free, rest].
    condition : float
        Condition number of V.
    """

    n_states: int
    free: np.ndarray
    rest: np.ndarray
    poles: np.ndarray
    shapes: np.ndarray
    inverse: np.ndarray
    coupling: np.ndarray
    condition: float

    @classmethod
    def of(cls, a: np.ndarray) -> ModalForm:
        """The modal form of the real state matrix ``a``.

        Raises
        ------
        NotDiagonalisable
            If the eigenvectors of A[rest, rest] are ill-conditioned (condition number above CONDITION_LIMIT).
        """
        a = np.asarray(a, dtype=float)
        n = a.shape[0]
        free = np.flatnonzero(~np.any(a != 0.0, axis=0))
        rest = np.setdiff1d(np.arange(n), free)
        lam, vec = np.linalg.eig(a[np.ix_(rest, rest)])
        condition = float(np.linalg.cond(vec)) if rest.size else 1.0
        if not condition <= CONDITION_LIMIT:
            raise NotDiagonalisable(
                f"the state matrix's eigenvectors have condition number {condition:.3g} (limit "
                f"{CONDITION_LIMIT:.0e}): repeated poles without a free state to split off"
            )
        inverse = np.linalg.inv(vec) if rest.size else vec
        tol = 1e-9 * np.maximum(np.abs(lam), 1e-300)
        keep = lam.imag >= -tol
        pair = (lam.imag > tol)[keep]
        if int(keep.sum() + pair.sum()) != rest.size:
            raise NotDiagonalisable("the complex poles do not come in conjugate pairs (is A real?)")
        shapes = vec[:, keep] * np.where(pair, 2.0, 1.0)[None, :]
        return cls(n, free, rest, lam[keep], shapes, inverse[keep], a[np.ix_(free, rest)], condition)

    @property
    def n_modes(self) -> int:
        """Number of kept modes."""
        return int(self.poles.size)

    def output_maps(self, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Real matrices (R_modes, R_free) with C x = z.view(float) @ R_modes + free @ R_free for the output
        matrix ``c`` (n_out, n_states)."""
        c = np.asarray(c, dtype=float)
        return real_part_rows((c[:, self.rest] @ self.shapes).T), c[:, self.free].T

    def steps(self, b: np.ndarray, dt: float, hold: str) -> ModalSteps:
        """The exact step of ``dt`` [s] for the input matrix ``b`` (n_states, m) under ``hold`` ("foh" or "zoh")."""
        if hold not in ("foh", "zoh"):
            raise ValueError(f"hold must be 'foh' or 'zoh'; got {hold!r}")
        b = np.asarray(b, dtype=float)
        modal_b = self.inverse @ b[self.rest]  # (n_modes, m)
        phi1, phi2, phi3 = phi_functions(self.poles * dt)
        if hold == "foh":
            w0, w1 = dt * (phi1 - phi2), dt * phi2
            i0, i1 = dt**2 * (phi2 - phi3), dt**2 * phi3
            u0, u1 = dt / 2, dt / 2
        else:
            w0, w1 = dt * phi1, np.zeros_like(phi1)
            i0, i1 = dt**2 * phi2, np.zeros_like(phi2)
            u0, u1 = dt, 0.0
        projected = self.coupling @ self.shapes  # (n_free, n_modes): A[free, rest] Re(shapes .)
        b_free = b[self.free]
        return ModalSteps(
            decay=np.exp(self.poles * dt),
            input0=w0[:, None] * modal_b,
            input1=w1[:, None] * modal_b,
            free_state=projected * (dt * phi1)[None, :],
            free_input0=np.real(projected @ (i0[:, None] * modal_b)) + u0 * b_free,
            free_input1=np.real(projected @ (i1[:, None] * modal_b)) + u1 * b_free,
        )


@dataclass(frozen=True)
class ModalSteps:
    """One exact step in modal coordinates: z_{k+1} = decay z_k + input0 u_k + input1 u_{k+1}, and the free states'
    increment Re(free_state z_k) + free_input0 u_k + free_input1 u_{k+1}."""

    decay: np.ndarray
    input0: np.ndarray
    input1: np.ndarray
    free_state: np.ndarray
    free_input0: np.ndarray
    free_input1: np.ndarray


BLOCK_STEPS: int = 512
"""Steps per block of :func:`run`: the block's modal coordinates stay in cache instead of filling memory."""


def input_forcing(steps: ModalSteps, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """What the inputs u (n, m) [one row per step] add over the n - 1 steps between them: to the modal
    coordinates (complex (n - 1, n_modes)) and to the free states ((n - 1, n_free))."""
    return _forcing(_input_maps(steps), u)


def _input_maps(steps: ModalSteps) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The real matrices of :func:`input_forcing` (made once per run, not per block)."""
    return complex_columns(steps.input0.T), complex_columns(steps.input1.T), steps.free_input0.T, steps.free_input1.T


def _forcing(maps: tuple[np.ndarray, ...], u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    u = np.ascontiguousarray(u, dtype=float)
    modes0, modes1, free0, free1 = maps
    modes = u[:-1] @ modes0
    modes += u[1:] @ modes1
    return modes.view(np.complex128), u[:-1] @ free0 + u[1:] @ free1


def run(form: ModalForm, steps: ModalSteps, u: np.ndarray, c: np.ndarray, x0: np.ndarray | None = None) -> np.ndarray:
    """Outputs y = C x (n_t, n_out) at every step for the inputs u (n_t, m) [one row per step], from the state x0
    (default zero), in blocks of BLOCK_STEPS steps.

    The recursion runs on the shifted coordinates s_k = z_k - input1 u_k, for which a step takes one input product
    instead of two: s_{k+1} = decay s_k + (decay input1 + input0) u_k; then z_k = s_k + input1 u_k in the outputs
    (a product with the small matrix Re(C input1)) and in the free states."""
    u = np.ascontiguousarray(u, dtype=float)
    x0 = np.zeros(form.n_states) if x0 is None else np.asarray(x0, dtype=float)
    # the complex coordinates as real parts then imaginary parts: Re(z @ M) = [Re z, Im z] @ [Re M; -Im M]
    free_modes = _split(steps.free_state).T * np.repeat([1.0, -1.0], form.n_modes)[:, None]
    out_modes, out_free = form.output_maps(c)
    out_modes = np.concatenate([out_modes[0::2], out_modes[1::2]])
    shifted = _split((steps.decay[:, None] * steps.input1 + steps.input0).T)  # (m, 2 n_modes)
    lead = _split(steps.input1.T)  # z_k - s_k = u_k @ lead
    out_input = lead @ out_modes  # (m, n_out): what u_k adds to the outputs through z_k - s_k
    # the free states' increment over a step, Re(free_state z_k) + free_input0 u_k + free_input1 u_{k+1}, on s_k
    free_input0 = lead @ free_modes + steps.free_input0.T
    free_input1 = steps.free_input1.T
    n_t, n_out, n_free = u.shape[0], out_free.shape[1], form.free.size
    # per step, from s_k: the outputs' modal part, then the modal part of the free states' increment
    both = np.empty((n_t, n_out + n_free))
    out_both = np.concatenate([out_modes, free_modes], axis=1)
    z0 = form.inverse @ x0[form.rest]
    s = np.concatenate([z0.real, z0.imag]) - u[0] @ lead
    block = np.empty((BLOCK_STEPS + 1, s.size))
    for k0 in range(0, n_t, BLOCK_STEPS):
        k1 = min(n_t, k0 + BLOCK_STEPS)  # block of steps k0 ... k1 - 1, started from s_k0
        n = k1 - k0
        shifted_recursion(steps.decay, u[k0:k1] @ shifted, s, block[: n + 1])  # s_k0 ... s_k1
        np.matmul(block[:n], out_both, out=both[k0:k1])
        s = block[n].copy()
    y = both[:, :n_out]
    y += u @ out_input
    if n_free:  # the free states do not act on the modes: summed once the modes are known
        increments = both[:-1, n_out:] + u[:-1] @ free_input0 + u[1:] @ free_input1
        frees = np.empty((n_t, n_free))
        frees[0] = x0[form.free]
        np.cumsum(increments, axis=0, out=frees[1:])
        frees[1:] += frees[0]
        y += frees @ out_free
    return y


def _numpy_recursion(decay: np.ndarray, forcing: np.ndarray, s0: np.ndarray, out: np.ndarray) -> None:
    """:func:`shifted_recursion` without numba: one vector operation per step (the loop over modes in numpy)."""
    n_modes = decay.size
    out[0] = s0
    z = s0[:n_modes] + 1j * s0[n_modes:]
    for k in range(forcing.shape[0]):
        z = decay * z + (forcing[k, :n_modes] + 1j * forcing[k, n_modes:])
        out[k + 1, :n_modes] = z.real
        out[k + 1, n_modes:] = z.imag


def _compiled_recursion(decay: np.ndarray, forcing: np.ndarray, s0: np.ndarray, out: np.ndarray) -> None:
    """s_{k+1} = decay s_k + forcing_k for k = 0 ... n - 1, complex values stored as their real parts, then their
    imaginary parts (forcing (n, 2 n_modes)); writes s_0 ... s_n into ``out`` (n + 1, 2 n_modes)."""
    n_modes = decay.size
    d_re, d_im = decay.real.copy(), decay.imag.copy()
    re, im = s0[:n_modes].copy(), s0[n_modes:].copy()
    out[0] = s0
    for k in range(forcing.shape[0]):
        for j in range(n_modes):
            r = d_re[j] * re[j] - d_im[j] * im[j] + forcing[k, j]
            im[j] = d_re[j] * im[j] + d_im[j] * re[j] + forcing[k, n_modes + j]
            re[j] = r
        out[k + 1, :n_modes] = re
        out[k + 1, n_modes:] = im


shifted_recursion = reduction_kernel(_compiled_recursion) if JIT else _numpy_recursion


def _split(matrix: np.ndarray) -> np.ndarray:
    """The real matrix [Re M, Im M] (columns) of a complex matrix M: u @ it holds the real parts of u @ M, then
    the imaginary parts."""
    return np.concatenate([matrix.real, matrix.imag], axis=1)


def outputs(form: ModalForm, c: np.ndarray, z: np.ndarray, free: np.ndarray) -> np.ndarray:
    """y = C x (n_t, n_out) from modal coordinates z (n_t, n_modes) and free states (n_t, n_free)."""
    out_modes, out_free = form.output_maps(c)
    return z.view(np.float64) @ out_modes + free @ out_free
