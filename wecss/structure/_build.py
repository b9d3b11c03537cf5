"""A frame from straight members: nodes at the members' ends, at every named point and station on them and evenly in
between; the members joined where they share a point; named points and lumped masses off the members riding on the
nearest node by a rigid offset."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ._element import BeamElement
from ._frame import Frame, PointMass
from ._material import Material
from ._section import Section, member_axes


@dataclass(frozen=True)
class MemberLine:
    """A straight member to mesh.

    Attributes
    ----------
    name : str
    start, end : ndarray (3,)
        Body axes [m].
    section : Section
    material : Material
    nonstructural_mass : float
        Mass per length beyond rho A [kg/m].
    stations : tuple of float
        Distances from the start where a node must be (hot spots) [m].
    """

    name: str
    start: np.ndarray
    end: np.ndarray
    section: Section
    material: Material
    nonstructural_mass: float = 0.0
    stations: tuple[float, ...] = ()


@dataclass(frozen=True)
class LumpedMass:
    """A lumped mass to place: ``name``, ``position`` (3,) of its centre [m], ``mass`` [kg] and ``inertia`` (3, 3)
    about its centre [kg m^2], body axes."""

    name: str
    position: np.ndarray
    mass: float
    inertia: np.ndarray


def _on_line(point: np.ndarray, start: np.ndarray, axis: np.ndarray, length: float, tol: float) -> float | None:
    """Station of ``point`` on the segment, or None if it is farther than ``tol`` from it."""
    s = float((point - start) @ axis)
    if -tol <= s <= length + tol and np.linalg.norm(point - start - s * axis) <= tol:
        return min(max(s, 0.0), length)
    return None


def build_frame(
    members: Sequence[MemberLine],
    *,
    elements: int = 8,
    points: Mapping[str, np.ndarray] | None = None,
    masses: Sequence[LumpedMass] = (),
    theory: str = "euler-bernoulli",
    rotary_inertia: bool = True,
    tolerance: float | None = None,
) -> Frame:
    """Mesh straight members into a frame.

    Each member gets nodes at its ends, at its ``stations``, at every named point, lumped mass and other member's
    end that lies on it (within ``tolerance``), and at ``elements`` equal divisions of its length in between (a
    division closer than a quarter of an element to one of those nodes is dropped). Nodes closer than
    ``tolerance`` are one node, so members that share a point are joined there. A named point or lumped mass off
    every member rides on the nearest node.

    Parameters
    ----------
    members : sequence of MemberLine
    elements : int
        Elements per member at least (more where points fall between divisions).
    points : mapping of str to array_like (3,)
        Named points [m] (joint points, PTO attachments, a clamp).
    masses : sequence of LumpedMass
    theory, rotary_inertia :
        See :class:`BeamElement`.
    tolerance : float, optional
        [m]; default 1e-6 times the size of the structure.

    Raises
    ------
    ValueError
        On no members, fewer than one element per member, or members that do not form one connected structure.
    """
    if not members:
        raise ValueError("a frame needs at least one member")
    if isinstance(elements, bool) or not isinstance(elements, int) or elements < 1:
        raise ValueError(f"elements must be an integer >= 1 (per member); got {elements!r}")
    named = {k: np.asarray(v, dtype=float) for k, v in (points or {}).items()}
    ends = np.array([p for m in members for p in (m.start, m.end)], dtype=float)
    size = float(np.ptp(ends, axis=0).max()) or 1.0
    tol = size * 1e-6 if tolerance is None else float(tolerance)
    marks = [*named.values(), *(m.position for m in masses), *ends]
    nodes: list[np.ndarray] = []

    def node_at(p: np.ndarray) -> int:
        for k, q in enumerate(nodes):
            if np.linalg.norm(q - p) <= tol:
                return k
        nodes.append(p)
        return len(nodes) - 1

    out: list[BeamElement] = []
    for m in members:
        start, end = np.asarray(m.start, dtype=float), np.asarray(m.end, dtype=float)
        axes = member_axes(start, end)
        length = float(np.linalg.norm(end - start))
        keys = {0.0, length}
        for s in m.stations:
            if not 0.0 <= s <= length:
                raise ValueError(f"member {m.name!r}: station {s} m is off the member (0 .. {length:.6g} m)")
            keys.add(float(s))
        for p in marks:
            s_on = _on_line(np.asarray(p, dtype=float), start, axes[0], length, tol)
            if s_on is not None:
                keys.add(s_on)
        unique: list[float] = []
        for s in sorted(keys):
            if not unique or s - unique[-1] > tol:
                unique.append(s)
        h = length / elements
        even = [k * h for k in range(1, elements) if min(abs(k * h - s) for s in unique) > 0.25 * h]
        stations = sorted(unique + even)
        ids = [node_at(start + s * axes[0]) for s in stations]
        for a, b, s in zip(ids[:-1], ids[1:], stations[:-1], strict=True):
            if a == b:
                continue
            out.append(
                BeamElement(
                    a,
                    b,
                    nodes[a],
                    nodes[b],
                    axes,
                    m.section,
                    m.material,
                    m.nonstructural_mass,
                    theory,
                    rotary_inertia,
                    m.name,
                    float(s),
                )
            )
    positions = np.array(nodes)

    def nearest(p: np.ndarray) -> int:
        return int(np.argmin(np.linalg.norm(positions - p, axis=1)))

    _check_connected(positions, out)
    lumped = [
        PointMass(m.name, nearest(np.asarray(m.position, dtype=float)), np.asarray(m.position, dtype=float), m.mass,
                  np.asarray(m.inertia, dtype=float))
        for m in masses
    ]  # fmt: skip
    located = {k: (nearest(p), p) for k, p in named.items()}
    return Frame(positions, tuple(out), tuple(lumped), located)


def _check_connected(nodes: np.ndarray, elements: list[BeamElement]) -> None:
    """Raise ValueError naming the members of each piece if the elements do not join every node into one piece."""
    parent = list(range(len(nodes)))

    def root(k: int) -> int:
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for e in elements:
        parent[root(e.i)] = root(e.j)
    pieces: dict[int, set[str]] = {}
    for e in elements:
        pieces.setdefault(root(e.i), set()).add(e.member)
    if len(pieces) > 1:
        listed = "; ".join(", ".join(sorted(p)) for p in pieces.values())
        raise ValueError(
            f"the members form {len(pieces)} separate pieces ({listed}); members join only where they share a point "
            "(an end, or an end on another member)"
        )
