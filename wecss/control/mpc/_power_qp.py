"""The quadratic programme of power-maximising model predictive control, built once per run; only its linear
term and its bounds change from one control step to the next.

With the forces f_k held over each period, the work the PTOs do on the device over period k is exactly
f_k . (s_{k+1} - s_k) (zero-order hold; s the strokes), so the energy absorbed over the horizon is

    E = -sum_k f_k . (s_{k+1} - s_k) = -(f' L f + f' a(x_0, d)),

quadratic in the forces through the prediction model (``HorizonModel``; L and a below). For a passive plant at
rest the PTOs cannot take energy out by their own forcing, so L + L' is positive semidefinite; a force penalty
T sum_k f_k' R f_k (PTO losses, and strict convexity) is added, and where a fit that is not quite passive makes
L + L' indefinite, the smallest diagonal shift that makes the Hessian positive semidefinite is added as well
(reported as ``convexity_shift``). The programme minimises

    (f' L f + f' a + T sum_k f_k' R f_k + E_ref sum_i (w1 e_i + w2 e_i^2)) / E_ref

over f and stroke slacks e_i >= 0 (one per PTO with a stroke limit, relative to the limit), with the force limit
hard (|f| <= F_max), the stroke limit soft (|s_k + s_eq| <= Z_max (1 + e)) and an optional rate limit
(|f_k - f_{k-1}| <= R_max T, f_{-1} the force applied now). Variables are scaled: u = f / f_ref per PTO, and the
objective is divided by the reference energy E_ref, so that OSQP's tolerances mean the same on every device.

Electrical energy (``loss_weight`` w > 0). With the conversion efficiency eta, the electrical energy of a PTO over
period k is eta W_k when it absorbs the work W_k = -f_k (s_{k+1} - s_k) and W_k / eta when it supplies it, so

    -E_elec / eta = sum_k (-W_k) + w sum_k max(-W_k, 0),   w = 1 / eta^2 - 1,

per PTO. The supplied energy -W_k = f_k Delta s_k is bilinear in the forces (Delta s_k depends on them through
the plant), so max(-W_k, 0) is not convex. The programme takes it sequentially convex: -W_k linearised about a
planned trajectory f_bar (the last plan, shifted by one period),

    -W_k ~ f_bar_k Delta s_k(f) + f_k Delta s_k(f_bar) - f_bar_k Delta s_k(f_bar),

exact to first order (the error is (f - f_bar)_k (Delta s(f) - Delta s(f_bar))_k), and max(., 0) taken by a
slack sigma_k >= 0 above it: min ... + w sum_k sigma_k over sigma >= 0 with sigma_k >= the linearisation. The
loss rows' coefficients change with f_bar every period (``loss_coefficients``), their bound with it too.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ._horizon import HorizonModel


@dataclass(frozen=True)
class PowerQP:
    """The programme's fixed data (module docstring): ``hessian`` P and ``constraints`` A (scipy sparse, CSC)
    of min 0.5 z' P z + q' z subject to l <= A z <= u, over z = (u_0 ... u_{N-1}, e); :meth:`vectors` gives q,
    l and u for a state, a disturbance and the force applied now.

    Attributes
    ----------
    force_scale : ndarray (n_pto,)
        f_ref [N or N m].
    energy_scale : float
        E_ref [J].
    convexity_shift : float
        Diagonal shift added to the scaled Hessian (0 for a passive plant).
    slack_pto : ndarray of int
        The PTOs with a stroke limit (one slack each).
    """

    horizon: HorizonModel
    hessian: sp.csc_matrix
    constraints: sp.csc_matrix
    force_scale: np.ndarray
    energy_scale: float
    convexity_shift: float
    slack_pto: np.ndarray
    slack_weights: tuple[float, float]
    force_limit: np.ndarray
    stroke_limit: np.ndarray
    stroke_at_equilibrium: np.ndarray
    rate_limit: np.ndarray | None
    # the maps vectors() applies each step, made once: the linear term from the state and the disturbance, the
    # stroke rows' free strokes (relative to their limits) from both, and the constant bounds
    _q_state: np.ndarray
    _q_disturbance: np.ndarray
    _stroke_state: np.ndarray
    _stroke_disturbance: np.ndarray
    _stroke_offset: np.ndarray
    _force_bound: np.ndarray
    _rate_bound: np.ndarray | None
    # the electrical loss (module docstring): its weight w (0: none), the scaled energy map M (the supplied energy
    # of the forces u is u_i (M u)_i + u_i b_i, b the linear term's force part), the loss rows' place in the
    # constraints, and their coefficients' (row, column) in the force block and positions in the CSC data
    loss_weight: float = 0.0
    _energy: np.ndarray | None = None
    _loss_rows: slice = field(default_factory=lambda: slice(0, 0))
    _loss_pattern: tuple[np.ndarray, np.ndarray] | None = None
    _loss_index: np.ndarray | None = None

    @classmethod
    def build(
        cls,
        horizon: HorizonModel,
        *,
        force_limit: np.ndarray,
        stroke_limit: np.ndarray,
        stroke_at_equilibrium: np.ndarray,
        force_penalty: np.ndarray,
        force_scale: np.ndarray,
        energy_scale: float,
        rate_limit: np.ndarray | None = None,
        slack_weights: tuple[float, float] = (1e2, 1e3),
        loss_weight: float = 0.0,
    ) -> PowerQP:
        """The programme for PTO limits ``force_limit`` [N or N m], ``stroke_limit`` (from rest) [m or rad] and
        ``rate_limit`` [N/s or N m/s] (inf or None: none), the strokes at the equilibrium (from rest), the force
        penalty R per PTO [1/(N s/m) or 1/(N m s/rad): W per N^2], the scales f_ref and E_ref, the slack
        weights (w1, w2) [-] and the weight w of the supplied energy (module docstring: 1 / eta^2 - 1 for the
        electrical energy at efficiency eta; 0, the default: the absorbed energy).

        Raises
        ------
        ValueError
            On non-positive scales, negative penalties or limits, or shapes that disagree.
        """
        n_pto, steps, period = horizon.n_pto, horizon.steps, horizon.period
        arrays = {}
        for label, value in (
            ("force_limit", force_limit),
            ("stroke_limit", stroke_limit),
            ("stroke_at_equilibrium", stroke_at_equilibrium),
            ("force_penalty", force_penalty),
            ("force_scale", force_scale),
        ):
            array = np.broadcast_to(np.asarray(value, dtype=float), (n_pto,)).copy()
            if label != "stroke_at_equilibrium" and not np.all(array >= 0):
                raise ValueError(f"{label} must be >= 0; got {array.tolist()}")
            arrays[label] = array
        rate = None if rate_limit is None else np.broadcast_to(np.asarray(rate_limit, dtype=float), (n_pto,)).copy()
        if rate is not None and not np.all(rate > 0):
            raise ValueError(f"rate_limit must be positive [N/s or N m/s]; got {rate.tolist()}")
        fs = arrays["force_scale"]
        if not (np.all(fs > 0) and np.all(np.isfinite(fs)) and energy_scale > 0 and np.isfinite(energy_scale)):
            raise ValueError(f"force_scale and energy_scale must be positive and finite; got {fs}, {energy_scale}")
        if not (len(slack_weights) == 2 and min(slack_weights) > 0):
            raise ValueError(f"slack_weights must be two positive numbers; got {slack_weights!r}")
        if not (np.isfinite(loss_weight) and loss_weight >= 0):
            raise ValueError(f"loss_weight must be >= 0 and finite; got {loss_weight!r}")
        # stroke differences s_{k+1} - s_k = difference @ (s_1 ... s_N) - first @ s_0
        m = steps * n_pto
        difference = np.eye(m) - np.eye(m, k=-n_pto)
        first = np.zeros((m, n_pto))
        first[:n_pto] = np.eye(n_pto)
        scale = np.tile(fs, steps)
        lmat = difference @ horizon.from_force * scale[None, :] * scale[:, None] / energy_scale
        hessian = (
            lmat + lmat.T + np.diag(2 * period * np.tile(arrays["force_penalty"], steps) * scale**2 / energy_scale)
        )
        lowest = float(np.linalg.eigvalsh(0.5 * (hessian + hessian.T))[0])
        floor = 1e-9 * float(np.max(np.abs(np.diag(hessian))))
        shift = floor - lowest if lowest < floor else 0.0
        hessian = hessian + shift * np.eye(m)
        slack_pto = np.flatnonzero(np.isfinite(arrays["stroke_limit"]))
        sel = np.concatenate([k * n_pto + slack_pto for k in range(steps)])  # stroke rows, step-major
        room = np.tile(arrays["stroke_limit"], steps)[sel]
        n_e = slack_pto.size
        n_s = m if loss_weight > 0 else 0  # loss slacks sigma
        size = m + n_e + n_s
        big = np.zeros((size, size))
        big[:m, :m] = 0.5 * (hessian + hessian.T)
        big[m : m + n_e, m : m + n_e] = 2 * slack_weights[1] * np.eye(n_e)
        # rows: finite force limits; strokes against their upper and their lower limit; slacks >= 0; rates
        rows = []
        force_rows = np.flatnonzero(np.tile(np.isfinite(arrays["force_limit"]), steps))
        if force_rows.size:
            block = np.zeros((force_rows.size, size))
            block[np.arange(force_rows.size), force_rows] = 1.0
            rows.append(block)
        if n_e:
            stroke = horizon.from_force[sel] * scale[None, :] / room[:, None]
            slack = np.zeros((sel.size, n_e))
            slack[np.arange(sel.size), np.tile(np.arange(n_e), steps)] = 1.0
            zero = np.zeros((sel.size, n_s))
            rows.append(np.hstack([stroke, -slack, zero]))  # s / Z - e <= upper
            rows.append(np.hstack([stroke, slack, zero]))  # s / Z + e >= lower
            rows.append(np.hstack([np.zeros((n_e, m)), np.eye(n_e), np.zeros((n_e, n_s))]))  # e >= 0
        if rate is not None:
            block = np.zeros((m, size))
            block[:, :m] = difference
            rows.append(block)
        n_fixed = sum(r.shape[0] for r in rows)
        pattern = None
        if n_s:
            # the supplied energy of (step k, PTO p) depends on the forces of steps <= k (Delta s_k = s_{k+1} - s_k)
            step = np.arange(m) // n_pto
            below_r, below_c = np.nonzero(step[None, :] <= step[:, None])
            pattern = (below_r, below_c)
            block = np.zeros((m, size))
            block[pattern] = 1.0  # placeholders: the coefficients come with each plan
            block[:, m + n_e :] = -np.eye(m)
            rows.append(block)  # linearised supplied energy - sigma <= bound
            block = np.zeros((m, size))
            block[:, m + n_e :] = np.eye(m)
            rows.append(block)  # sigma >= 0
        constraints = np.vstack(rows) if rows else np.zeros((0, size))
        csc = sp.csc_matrix(constraints)
        loss_index = None
        if pattern is not None:
            # positions of the loss coefficients in the CSC data (indices sorted within each column)
            csc.sort_indices()
            r, c = pattern[0] + n_fixed, pattern[1]
            loss_index = np.empty(r.size, dtype=np.int64)
            for column in np.unique(c):
                at = c == column
                begin, end = csc.indptr[column], csc.indptr[column + 1]
                loss_index[at] = begin + np.searchsorted(csc.indices[begin:end], r[at])
        # q = (difference (s_1 ... s_N) - first s_0) f_ref / E_ref, the strokes free of PTO forces
        to_q = scale[:, None] / energy_scale
        q_state = to_q * (difference @ horizon.from_state - first @ horizon.stroke_of_state)
        q_disturbance = to_q * (difference @ horizon.from_disturbance)
        return cls(
            horizon, sp.csc_matrix(np.triu(big)), csc, fs, float(energy_scale), shift,
            slack_pto, (float(slack_weights[0]), float(slack_weights[1])), arrays["force_limit"],
            arrays["stroke_limit"], arrays["stroke_at_equilibrium"], rate, q_state, q_disturbance,
            horizon.from_state[sel] / room[:, None], horizon.from_disturbance[sel] / room[:, None],
            np.tile(arrays["stroke_at_equilibrium"], steps)[sel] / room,
            np.tile(arrays["force_limit"] / fs, steps)[force_rows],
            None if rate is None else np.tile(rate * period / fs, steps), float(loss_weight),
            lmat if n_s else None, slice(n_fixed, n_fixed + n_s), pattern, loss_index,
        )  # fmt: skip

    @property
    def n_variables(self) -> int:
        """Number of decision variables (scaled forces and slacks)."""
        return self.hessian.shape[0]

    def vectors(
        self, state: np.ndarray, disturbance: np.ndarray, applied: np.ndarray, plan: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """q, l, u for the state x_0 now, the disturbance (N + 1, nv) over the horizon [N or N m per coordinate],
        the force applied now [N or N m] (for the rate limit) and, with a loss weight, the planned forces the
        supplied energy is linearised about ((N, n_pto) [N or N m]; None: zero)."""
        d = np.ravel(disturbance)
        n_pto = self.horizon.n_pto
        n_e = self.slack_pto.size
        n_s = self.n_variables - self.horizon.steps * n_pto - n_e
        q = np.concatenate(
            [
                self._q_state @ state + self._q_disturbance @ d,
                np.full(n_e, self.slack_weights[0]),
                np.full(n_s, self.loss_weight),
            ]
        )
        lower, upper = [-self._force_bound], [self._force_bound]
        if n_e:
            offset = self._stroke_state @ state + self._stroke_disturbance @ d + self._stroke_offset
            lower += [np.full(offset.size, -np.inf), -1.0 - offset, np.zeros(n_e)]
            upper += [1.0 - offset, np.full(offset.size, np.inf), np.full(n_e, np.inf)]
        if self._rate_bound is not None:
            centre = np.zeros(self._rate_bound.size)
            centre[:n_pto] = np.asarray(applied, dtype=float) / self.force_scale
            lower.append(centre - self._rate_bound)
            upper.append(centre + self._rate_bound)
        if n_s:
            planned = self._scaled(plan)
            assert self._energy is not None
            lower += [np.full(n_s, -np.inf), np.zeros(n_s)]
            upper += [planned * (self._energy @ planned), np.full(n_s, np.inf)]
        return q, np.concatenate(lower), np.concatenate(upper)

    def loss_coefficients(self, q: np.ndarray, plan: np.ndarray | None = None) -> np.ndarray:
        """The loss rows' coefficients (in the order of ``loss_index``) for the linear term ``q`` (from
        :meth:`vectors`: its force part is the supplied energy's linear part b) and the planned forces ``plan``
        ((N, n_pto) [N or N m]; None: zero): row i is u_bar_i M_i + (M u_bar + b)_i e_i (module docstring)."""
        if self._energy is None or self._loss_pattern is None:
            raise ValueError("the programme has no loss rows (built with loss_weight 0)")
        planned = self._scaled(plan)
        rows, columns = self._loss_pattern
        m = planned.size
        diagonal = self._energy @ planned + q[:m]
        return planned[rows] * self._energy[rows, columns] + np.where(rows == columns, diagonal[rows], 0.0)

    @property
    def loss_rows(self) -> slice:
        """The loss rows' place among the constraints' rows (an empty slice without them)."""
        return self._loss_rows

    @property
    def loss_pattern(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(row, column) in the (N n_pto)^2 force block of each loss coefficient, in the order of
        :meth:`loss_coefficients` (None without loss rows)."""
        return self._loss_pattern

    @property
    def loss_index(self) -> np.ndarray | None:
        """Positions of the loss rows' coefficients in the CSC data of ``constraints`` (None without them)."""
        return self._loss_index

    def _scaled(self, plan: np.ndarray | None) -> np.ndarray:
        """A plan (N, n_pto) [N or N m] as the scaled force vector u (zero for None)."""
        m = self.horizon.steps * self.horizon.n_pto
        if plan is None:
            return np.zeros(m)
        return (np.asarray(plan, dtype=float) / self.force_scale[None, :]).ravel()

    def forces(self, solution: np.ndarray) -> np.ndarray:
        """The planned forces (N, n_pto) [N or N m] of a solution z."""
        steps, n_pto = self.horizon.steps, self.horizon.n_pto
        return solution[: steps * n_pto].reshape(steps, n_pto) * self.force_scale[None, :]

    def slack(self, solution: np.ndarray) -> np.ndarray:
        """The stroke slack per PTO of a solution, relative to the stroke limit [-] (0 for PTOs without one)."""
        out = np.zeros(self.horizon.n_pto)
        start = self.horizon.steps * self.horizon.n_pto
        out[self.slack_pto] = solution[start : start + self.slack_pto.size]
        return out
