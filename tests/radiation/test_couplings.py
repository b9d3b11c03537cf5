"""One coupling rule for the convolution and the state-space fit, passed from the scene (issue 12)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.compiled import fit_request
from wecss.devices import load as load_device
from wecss.radiation import impulse_response, significant_couplings
from wecss.sim import compile_scene


def test_the_rule_is_scale_free():
    """A coupling is judged against sqrt(P_i P_j): rescaling a DOF's units (heave in N/m, pitch in N m/rad) does
    not change what is kept, while a rule against the largest diagonal would drop the small-unit DOF's entries."""
    peak = np.array([[100.0, 0.5, 2.0], [0.5, 0.01, 0.002], [2.0, 0.002, 80.0]])
    kept = significant_couplings(peak, 1e-2)
    # 0.5 >= 1e-2 sqrt(100 * 0.01) = 0.01; 0.002 >= 1e-2 sqrt(0.01 * 80) = 0.0089 is false
    expected = np.array([[True, True, True], [True, True, False], [True, False, True]])
    np.testing.assert_array_equal(kept, expected)
    scale = np.diag([1.0, 1e3, 1.0])  # the second DOF in other units
    np.testing.assert_array_equal(significant_couplings(scale @ peak @ scale, 1e-2), expected)
    assert not significant_couplings(np.zeros((2, 2)), 0.0).any()  # a zero entry is never kept
    with pytest.raises(ValueError, match=r"in \[0, 1\); got 1.5"):
        significant_couplings(peak, 1.5)


def test_a_pitch_coupling_survives_in_both_radiation_models():
    """m4-111: the heave-pitch coupling of the bow float and the pitch-pitch coupling between floats are kept by
    the convolution and judged by the shipped state-space fit, which the scene's threshold reaches."""
    sc = scene("m4-111", radiation={"method": "state_space"})
    hydro = load_device("m4-111").coupling().hydro
    settings, _ = fit_request(sc.radiation, hydro)
    assert settings.coupling_threshold == sc.radiation.coupling_threshold == 1e-3
    irf = impulse_response(hydro)
    dofs = list(irf.dofs)
    kept = significant_couplings(np.max(np.abs(irf.kernel), axis=0), sc.radiation.coupling_threshold)
    pitch_pairs = [("float_1__Heave", "float_1__Pitch"), ("float_1__Pitch", "float_3__Pitch")]
    for a, b in pitch_pairs:
        assert kept[dofs.index(a), dofs.index(b)], (a, b)
    fit = compile_scene(sc).radiation_fit
    assert fit is not None
    judged = {str(e) for e in fit.report.entry.values}
    for a, b in pitch_pairs:
        assert f"{a}|{b}" in judged
    convolution = compile_scene(scene("m4-111", radiation={"method": "convolution"}))
    dropped = set(convolution.radiation_summary.dropped_entries)
    expected = {f"{dofs[i]}|{dofs[j]}" for i, j in zip(*np.nonzero(~kept), strict=True)}
    assert dropped == expected
