"""The PTO strokes over a receding horizon, as affine functions of the current state, the PTO forces and a
generalised disturbance force: the prediction model of model predictive control.

The plant is a device's linear model (``LinearModel``: x' = A x + F (d + G' f) with F = ``force_input``),
discretised exactly at the control period T: the PTO forces f held over each period (zero-order hold, as the
simulators apply a controller's force) and the disturbance d (the generalised excitation, nv) linear in time
between its samples (first-order hold):

    x_{k+1} = Phi x_k + Gf f_k + Gd0 d_k + Gd1 d_{k+1},   s_k = G xi_k   (strokes from the equilibrium).

Stacked over k = 1 ... N: s = Sx x_0 + Sf f + Sd d with f = (f_0 ... f_{N-1}) and d = (d_0 ... d_N).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...linear import LinearModel, exact_step


@dataclass(frozen=True)
class HorizonModel:
    """Prediction matrices of the strokes over ``steps`` control periods of ``period`` [s] (module docstring).

    Attributes
    ----------
    phi, force_step, disturbance_now, disturbance_next : ndarray
        Phi (n, n), Gf (n, n_pto), Gd0 and Gd1 (n, nv): one exact step.
    stroke_of_state : ndarray (n_pto, n)
        s = G xi as a map of the state.
    from_state : ndarray (N n_pto, n)
        Sx; rows are (step k = 1 ... N, PTO), step-major.
    from_force : ndarray (N n_pto, N n_pto)
        Sf (block lower triangular: strictly causal in the forces).
    from_disturbance : ndarray (N n_pto, (N + 1) nv)
        Sd.
    """

    period: float
    steps: int
    phi: np.ndarray
    force_step: np.ndarray
    disturbance_now: np.ndarray
    disturbance_next: np.ndarray
    stroke_of_state: np.ndarray
    from_state: np.ndarray
    from_force: np.ndarray
    from_disturbance: np.ndarray

    @classmethod
    def of(cls, model: LinearModel, period: float, steps: int) -> HorizonModel:
        """The prediction matrices of ``model`` (with a state-space system) over ``steps`` periods of ``period``
        [s].

        Raises
        ------
        ValueError
            For a non-positive period or fewer than one step, or a model with coordinates held quasi-static
            (``LinearModel.refuse_held``).
        """
        if not period > 0:
            raise ValueError(f"period must be positive [s]; got {period!r}")
        if not (isinstance(steps, int) and steps >= 1):
            raise ValueError(f"steps must be an integer >= 1; got {steps!r}")
        model.refuse_held("the MPC horizon model")
        a = np.asarray(model.state_space.A, dtype=float)
        inp = model.force_input  # generalised force -> state rate (n, nv)
        n, nv = inp.shape
        g = model.pto_jacobian
        n_pto = g.shape[0]
        phi, gd0, gd1 = exact_step(a, inp, period)
        gf = (gd0 + gd1) @ g.T  # held force: the zero-order-hold input matrix
        c = np.zeros((n_pto, n))
        c[:, :nv] = g
        # Markov parameters c Phi^m (Gf, Gd0, Gd1), m = 0 ... N-1, and c Phi^k, k = 1 ... N
        sx = np.zeros((steps, n_pto, n))
        hf = np.zeros((steps, n_pto, n_pto))
        h0 = np.zeros((steps, n_pto, nv))
        h1 = np.zeros((steps, n_pto, nv))
        row = c.copy()  # c Phi^m
        for m in range(steps):
            hf[m], h0[m], h1[m] = row @ gf, row @ gd0, row @ gd1
            row = row @ phi
            sx[m] = row
        sf = np.zeros((steps, n_pto, steps, n_pto))
        sd = np.zeros((steps, n_pto, steps + 1, nv))
        for k in range(1, steps + 1):  # s_k = c Phi^k x0 + sum_{j<k} c Phi^{k-1-j} (Gf f_j + Gd0 d_j + Gd1 d_{j+1})
            for j in range(k):
                sf[k - 1, :, j] = hf[k - 1 - j]
                sd[k - 1, :, j] += h0[k - 1 - j]
                sd[k - 1, :, j + 1] += h1[k - 1 - j]
        return cls(
            period, steps, phi, gf, gd0, gd1, c, sx.reshape(steps * n_pto, n),
            sf.reshape(steps * n_pto, steps * n_pto), sd.reshape(steps * n_pto, (steps + 1) * nv),
        )  # fmt: skip

    @property
    def n_pto(self) -> int:
        """Number of PTOs."""
        return self.stroke_of_state.shape[0]
