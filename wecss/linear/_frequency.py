"""The exact frequency-domain steady state of the linearised MFM equations on a scene's waves (the reference the
nonlinear simulator must reproduce in small waves: same hydro data, same record)."""

from __future__ import annotations

import numpy as np

from ..compiled import CompiledScene
from ..waves import evaluate
from ._model import linearize


def steady_state(compiled: CompiledScene, time: np.ndarray) -> dict[str, np.ndarray]:
    """Steady-state linear response to the scene's waves (no ramp) at ``time`` [s].

    Returns
    -------
    dict
        ``displacement`` (n_t, nv) generalised displacements from the equilibrium; ``pto`` (n_t, n_pto) PTO
        strokes from the equilibrium; ``amplitudes`` (nv, n_components) complex.

    Raises
    ------
    ValueError
        In calm water, or for a controller without linear gains.
    """
    if compiled.excitation is None:
        raise ValueError("calm water: the steady state is the equilibrium")
    if not compiled.linear_controller:
        raise ValueError("the frequency-domain solution needs a controller with linear gains (such as 'damping')")
    exc = compiled.excitation
    model = linearize(compiled)
    h = model.frequency_response(exc.omega)
    amplitudes = np.einsum("wvj,jw->vw", h, exc.coefficients)
    xi = np.real(evaluate(amplitudes, exc.omega, np.asarray(time, dtype=float))).T
    return {"displacement": xi, "pto": xi @ model.pto_jacobian.T, "amplitudes": amplitudes}
