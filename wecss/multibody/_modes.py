"""Generalised modes of a body: degrees of freedom beyond its six rigid-body ones (flexible or other user-defined
modes, such as WAMIT's modes 7.. or Capytaine's custom DOFs).

Each mode is one generalised coordinate xi of its body, dimensionless [1]: the mode shape (known to the BEM code
that made the hydrodynamic data, not to wecss) gives the displacement [m] per unit coordinate. Its rate is [1/s],
its acceleration [1/s^2], the generalised force on it [J] (work per unit coordinate), and the structural matrices
of a body's modes are the generalised mass [kg m^2], stiffness [J] = [N m] and damping [J s] = [N m s]: the
equations of the modes alone are M xi_ddot + C xi_dot + K xi = Q.

What is modelled here: each mode is one more Cartesian row of its body (after its six rigid rows) whose B-matrix
row is the identity on the mode's own generalised velocity (Bdot = 0, no gyroscopic term); the body's mass matrix
is block diagonal, diag(m I3, J, M); the structural stiffness and damping act on the modes; the hydrodynamic
database's coefficients of the DOFs ``<hydro_body>__<mode>`` act on them through the hydro index like those of the
rigid DOFs (with their couplings). Neglected for now: the inertial coupling between the rigid motion and the modes
(the floating frame's inertia invariants, a later issue), and elastic attachments (joints, PTOs and moorings act
on the rigid body).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..hydro import check_mode_name

MODE_KEYS = ("name", "mass", "stiffness", "damping")
"""Keys of one mode in a device spec's list form (``modes = [{name = ..., mass = ...}]``)."""
MATRIX_KEYS = ("names", "mass", "stiffness", "damping")
"""Keys of a body's modes in a device spec's matrix form (``modes = {names = [...], mass = [[...]]}``)."""
_UNITS = {"mass": "kg m^2", "stiffness": "N m", "damping": "N m s"}


def _matrix(body: str, field: str, value: Any, n: int, *, positive: bool) -> np.ndarray:
    """A symmetric (n, n) matrix from a matrix or n diagonal values, checked (positive definite or semi-definite)."""
    need = "positive definite" if positive else "positive semi-definite"
    accepted = f"{n} values (the diagonal) or a symmetric {n}x{n} {need} matrix [{_UNITS[field]}]"
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"body {body!r}: modes {field} must be {accepted}; got {value!r}") from None
    if array.ndim == 0 and n == 1:
        array = array.reshape(1)
    if array.shape == (n,):
        array = np.diag(array)
    if array.shape != (n, n) or not np.all(np.isfinite(array)):
        raise ValueError(f"body {body!r}: modes {field} must be {accepted}; got {value!r}")
    scale = max(1.0, float(np.abs(array).max())) if array.size else 1.0
    if not np.allclose(array, array.T, rtol=0, atol=1e-12 * scale):
        raise ValueError(f"body {body!r}: modes {field} must be symmetric [{_UNITS[field]}]; got {array.tolist()}")
    array = 0.5 * (array + array.T)
    smallest = float(np.min(np.linalg.eigvalsh(array))) if n else 1.0
    if (positive and not smallest > 0) or smallest < -1e-12 * scale:
        raise ValueError(
            f"body {body!r}: modes {field} must be {need} [{_UNITS[field]}]; got {array.tolist()} (smallest "
            f"eigenvalue {smallest:.3g})"
        )
    return array


@dataclass(frozen=True, eq=False)
class GeneralisedModes:
    """The generalised modes of one body (see the module docstring for what is modelled).

    Parameters
    ----------
    names : sequence of str
        One name per mode (``flex1``): the generalised coordinate is ``<body>__<name>`` and the hydrodynamic DOF
        ``<hydro_body>__<name>``. Not a rigid-body DOF name in any case, no ``__``.
    mass : array_like (n, n) or (n,)
        Generalised mass [kg m^2]: symmetric positive definite (n values: its diagonal).
    stiffness, damping : array_like (n, n) or (n,)
        Structural stiffness [N m] and damping [N m s]: symmetric positive semi-definite.
    body : str
        The body's name, for error messages.

    Raises
    ------
    ValueError
        On repeated or invalid names, or matrices of the wrong size, not symmetric or not (semi-)definite (the
        message names the body, the field, the value and what is accepted).
    """

    names: tuple[str, ...]
    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    body: str = ""

    def __post_init__(self) -> None:
        body = self.body
        names = (self.names,) if isinstance(self.names, str) else self.names
        if not isinstance(names, Sequence) or not all(isinstance(n, str) for n in names):
            raise ValueError(
                f"body {body!r}: modes names must be a list of mode names (such as 'flex1'); got {names!r}"
            )
        names = tuple(names)
        for name in names:
            try:
                check_mode_name(name)
            except ValueError as err:
                raise ValueError(f"body {body!r}: modes: {err}") from None
        if len(set(names)) != len(names):
            raise ValueError(f"body {body!r}: modes names must be distinct; got {list(names)}")
        n = len(names)
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "mass", _matrix(body, "mass", self.mass, n, positive=True))
        for field in ("stiffness", "damping"):
            object.__setattr__(self, field, _matrix(body, field, getattr(self, field), n, positive=False))

    @property
    def n(self) -> int:
        """Number of modes."""
        return len(self.names)

    @classmethod
    def from_spec(cls, body: str, value: Any) -> GeneralisedModes:
        """The modes of a device spec's body entry (``[[bodies]]`` key ``modes``), in either form:

        - a list of tables, one per mode: ``modes = [{name = "flex1", mass = 2.0, stiffness = 80.0, damping =
          0.1}]`` (uncoupled modes: diagonal matrices; ``stiffness`` and ``damping`` optional, default 0);
        - one table with the names and matrices (or diagonals): ``modes = {names = ["flex1", "flex2"], mass =
          [[2.0, 0.1], [0.1, 3.0]], stiffness = [80.0, 300.0]}``.

        Raises
        ------
        ValueError
            On another form, unknown or missing keys, or values :class:`GeneralisedModes` refuses (the message
            names the body, the field, the value and what is accepted).
        """
        if isinstance(value, GeneralisedModes):
            return value
        if isinstance(value, Mapping):
            unknown = sorted(set(value) - set(MATRIX_KEYS))
            if unknown or "names" not in value or "mass" not in value:
                raise ValueError(
                    f"body {body!r}: modes table has keys {sorted(value)}; accepted: {list(MATRIX_KEYS)} with names "
                    "and mass required"
                )
            names = value["names"]
            n = 1 if isinstance(names, str) else len(names) if isinstance(names, Sequence) else 0
            return cls(
                names, value["mass"], value.get("stiffness", np.zeros(n)), value.get("damping", np.zeros(n)), body
            )
        if isinstance(value, Sequence) and not isinstance(value, str):
            entries = list(value)
            for k, entry in enumerate(entries):
                if not isinstance(entry, Mapping):
                    raise ValueError(
                        f"body {body!r}: modes[{k}] must be a table such as {{name = 'flex1', mass = 2.0}}; "
                        f"got {entry!r}"
                    )
                unknown = sorted(set(entry) - set(MODE_KEYS))
                if unknown or "name" not in entry or "mass" not in entry:
                    raise ValueError(
                        f"body {body!r}: modes[{k}] has keys {sorted(entry)}; accepted: {list(MODE_KEYS)} with name "
                        "and mass required"
                    )
                for field in ("mass", "stiffness", "damping"):
                    number = entry.get(field, 0.0)
                    if isinstance(number, bool) or not isinstance(number, int | float):
                        raise ValueError(
                            f"body {body!r}: modes[{k}].{field} must be a number [{_UNITS[field]}]; got {number!r} "
                            "(give coupled modes as one table with matrices: modes = {names, mass, stiffness, damping})"
                        )
            diag = {f: np.array([float(e.get(f, 0.0)) for e in entries]) for f in ("mass", "stiffness", "damping")}
            return cls(tuple(e["name"] for e in entries), diag["mass"], diag["stiffness"], diag["damping"], body)
        raise ValueError(
            f"body {body!r}: modes must be a list of tables [{{name, mass, stiffness, damping}}] or a table "
            f"{{names, mass, stiffness, damping}}; got {value!r}"
        )


NO_MODES = GeneralisedModes((), np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0)))
"""A rigid body's (empty) modes."""
