"""Geometric stiffening: the flapwise frequencies of a uniform Euler-Bernoulli cantilever spinning about an axis
through its root (hub radius 0) against Wright et al. (1982) and Banerjee (2000).

The centrifugal axial force N(x) = rho A Omega^2 (L^2 - x^2) / 2 enters through the geometric stiffness (exact per
element: N is quadratic, given at both ends and the middle); flapwise, out of the plane of rotation, there is no
spin softening. 32 elements: the frequencies differ from those of 64 elements by at most 4.1e-6 (the discretisation
error), from the table (rounded to 4 decimals) by at most 4.5e-5.
"""

from __future__ import annotations

import numpy as np

from wecss.structure import Material, MemberLine, Section, build_frame, natural_modes

TABLE = [3.5160, 3.6816, 4.1373, 4.7973, 5.5850, 6.4495, 7.3604, 8.2996, 9.2568, 10.2257, 11.2023, 12.1843, 13.1702]
"""omega_1 sqrt(rho A L^4 / E I) at lambda = Omega sqrt(rho A L^4 / E I) = 0, 1, ..., 12."""


def _flapwise(n: int) -> np.ndarray:
    e, rho, length = 2.1e11, 7850.0, 2.0
    section = Section.tube(0.1, 0.005)
    frame = build_frame(
        [MemberLine("blade", np.zeros(3), np.array([length, 0.0, 0.0]), section, Material("s", e, e / 2.6, rho))],
        elements=n,
        rotary_inertia=False,
    )
    mu, ei = rho * section.area, e * section.iy
    scale = np.sqrt(mu * length**4 / ei)
    # flapwise (z) bending alone: w and theta_y free, the root clamped
    fixed = [int(d) for d in frame.node_dofs(0)]
    fixed += [int(d) for k in range(frame.n_nodes) for j, d in enumerate(frame.node_dofs(k)) if j not in (2, 4)]
    # N is proportional to Omega^2: the geometric stiffness of Omega = 1 rad/s, scaled
    unit = frame.geometric_stiffness(
        [mu * (length**2 - np.array([el.station, el.station + el.length / 2, el.station + el.length]) ** 2) / 2
         for el in frame.elements]
    )  # fmt: skip
    out = []
    for lam in range(len(TABLE)):
        spin = lam / scale
        omega, _ = natural_modes(frame.stiffness + spin**2 * unit, frame.mass, fixed, n_modes=1)
        out.append(omega[0] * scale)
    return np.array(out)


def test_flapwise_frequency_of_a_rotating_cantilever_matches_the_table():
    coarse, fine = _flapwise(32), _flapwise(64)
    assert np.max(np.abs(coarse - fine)) < 1e-5  # discretisation error of 32 elements
    assert np.max(np.abs(coarse - np.array(TABLE))) < 1e-4
    assert np.all(np.diff(coarse) > 0)  # stiffening with the speed
