"""Beam frequencies against closed forms: a cantilever (beta_1 L = 1.87510), a pinned-pinned beam (pi^2), and a
cantilever with a tip mass against the root of its frequency equation."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from wecss.devices import beam_frequencies

L, EI, MU = 2.0, 2.7e6, 125.0


def _f(beta_l: float) -> float:
    return beta_l**2 / (2 * np.pi * L**2) * np.sqrt(EI / MU)


def test_cantilever_and_pinned_beams():
    assert beam_frequencies(L, EI, MU, clamped=(0.0,))[0] == pytest.approx(_f(1.875104069), rel=1e-6)
    assert beam_frequencies(L, EI, MU, pinned=(0.0, L))[0] == pytest.approx(_f(np.pi), rel=1e-6)


def test_cantilever_with_a_tip_mass_matches_its_frequency_equation():
    tip = 300.0
    ratio = tip / (MU * L)

    def equation(x: float) -> float:  # 1 + cos cosh + (M / m L) x (cos sinh - sin cosh) = 0
        return 1 + np.cos(x) * np.cosh(x) + ratio * x * (np.cos(x) * np.sinh(x) - np.sin(x) * np.cosh(x))

    root = brentq(equation, 0.1, 1.875)
    assert beam_frequencies(L, EI, MU, clamped=(0.0,), tip_mass=tip)[0] == pytest.approx(_f(root), rel=1e-6)


def test_a_stiff_beam_on_a_pin_and_a_spring_is_a_rigid_pendulum():
    k, tip = 4e4, 500.0  # spring at L / 2, mass at the tip; rigid rotation about the pin
    inertia = tip * L**2 + MU * L**3 / 3
    rigid = np.sqrt(k * (L / 2) ** 2 / inertia) / (2 * np.pi)
    stiff = 100 * EI
    # the beam's own flexibility lowers it by about (f / f_bending)^2, f_bending of the pinned-free beam with its tip
    # mass on a rigid support at L / 2: well over 100 times f, so the correction is below 1e-4
    bending = beam_frequencies(L, stiff, MU, pinned=(0.0, L / 2), tip_mass=tip)[0]
    assert (rigid / bending) ** 2 < 1e-4
    f = beam_frequencies(L, stiff, MU, pinned=(0.0,), springs=((L / 2, k),), tip_mass=tip)[0]
    assert f == pytest.approx(rigid, rel=1e-4)
    assert f < rigid  # flexibility only lowers it


def test_bad_inputs():
    with pytest.raises(ValueError, match="bending_stiffness"):
        beam_frequencies(L, 0.0, MU, clamped=(0.0,))
    with pytest.raises(ValueError, match="off the beam"):
        beam_frequencies(L, EI, MU, pinned=(3.0,))
    with pytest.raises(ValueError, match="rigid-body motion"):
        beam_frequencies(L, EI, MU, pinned=(0.0,))
