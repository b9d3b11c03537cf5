"""Prediction of a signal over a horizon by an autoregressive model fitted on its past: x_t = sum_i a_i x_{t-i},
per component, least squares with a small ridge; the preview comes from iterating the model forward."""

from __future__ import annotations

import numpy as np


class ARPredictor:
    """An autoregressive predictor per component.

    Parameters
    ----------
    order : int
        Number of past samples in each prediction (>= 1).
    ridge : float
        Tikhonov regularisation of the least squares, relative to the data's energy [-].

    Raises
    ------
    ValueError
        For an order below 1 or a negative ridge.
    """

    def __init__(self, order: int, *, ridge: float = 1e-8) -> None:
        if not (isinstance(order, int) and order >= 1):
            raise ValueError(f"order must be an integer >= 1; got {order!r}")
        if not ridge >= 0:
            raise ValueError(f"ridge must be >= 0; got {ridge!r}")
        self.order = order
        self.ridge = ridge
        self.coefficients: np.ndarray | None = None

    def fit(self, series: np.ndarray) -> ARPredictor:
        """Fit the coefficients (order, n_components) on samples at a constant step (n_samples, n_components).

        Raises
        ------
        ValueError
            With fewer than 2 x order + 1 samples, or non-finite values.
        """
        x = np.asarray(series, dtype=float)
        x = x[:, None] if x.ndim == 1 else x
        if x.shape[0] < 2 * self.order + 1 or not np.all(np.isfinite(x)):
            raise ValueError(
                f"fit needs at least {2 * self.order + 1} finite samples for order {self.order}; got {x.shape[0]}"
            )
        n = x.shape[0]
        coefficients = np.zeros((self.order, x.shape[1]))
        for j in range(x.shape[1]):
            lagged = np.stack([x[self.order - i - 1 : n - i - 1, j] for i in range(self.order)], axis=1)
            target = x[self.order :, j]
            gram = lagged.T @ lagged
            if np.trace(gram) == 0:  # a component that is zero throughout: predicted zero
                continue
            gram += self.ridge * np.trace(gram) / self.order * np.eye(self.order)
            coefficients[:, j] = np.linalg.solve(gram, lagged.T @ target)
        self.coefficients = coefficients
        return self

    def predict(self, history: np.ndarray, steps: int) -> np.ndarray:
        """The next ``steps`` samples (steps, n_components) after ``history`` (its last ``order`` rows, newest
        last).

        Raises
        ------
        ValueError
            Before :meth:`fit`, for fewer than ``order`` rows of history, or fewer than 1 step.
        """
        if self.coefficients is None:
            raise ValueError("fit the predictor before predicting")
        h = np.asarray(history, dtype=float)
        h = h[:, None] if h.ndim == 1 else h
        if h.shape[0] < self.order or h.shape[1] != self.coefficients.shape[1]:
            raise ValueError(
                f"history must hold at least {self.order} rows of {self.coefficients.shape[1]} components; "
                f"got shape {h.shape}"
            )
        if not (isinstance(steps, int) and steps >= 1):
            raise ValueError(f"steps must be an integer >= 1; got {steps!r}")
        window = list(h[-self.order :][::-1])  # newest first
        out = np.empty((steps, h.shape[1]))
        for k in range(steps):
            out[k] = np.sum(self.coefficients * np.array(window[: self.order]), axis=0)
            window.insert(0, out[k])
        return out
