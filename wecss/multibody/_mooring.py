"""A linear mooring: springs and dampers on a body's rigid-body DOFs, about its centre of mass.

A mooring on body i applies the world-axes load -K d - C u at its centre of mass, where d is the displacement of
the centre of mass from its reference position and the rotation vector from the reference attitude (the same
displacement the linear hydrostatic stiffness acts on) and u the velocity of the centre of mass and the world
angular velocity. K and C are diagonal: one stiffness [N/m or N m/rad] and one damping [N s/m or N m s/rad] per
DOF. The mooring is slack in the reference configuration (no pretension): it carries no static load when the
reference configuration is the equilibrium, as for a body floating in its own equilibrium.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..constants import RIGID_BODY_DOFS
from ._tree import Multibody

MOORING_KEYS = ("body", "stiffness", "damping")


def _per_dof(body: str, label: str, values: Mapping[str, Any]) -> dict[str, float]:
    if not isinstance(values, Mapping):
        raise ValueError(
            f"mooring of body {body!r}: {label} must be a table of DOF name -> value, such as "
            f"{{Surge = 1e4}}; got {values!r}"
        )
    out = {}
    names = {d.lower(): d for d in RIGID_BODY_DOFS}
    for dof, value in values.items():
        name = names.get(str(dof).lower())
        if name is None:
            raise ValueError(
                f"mooring of body {body!r}: unknown DOF {dof!r} in {label}; accepted: {', '.join(RIGID_BODY_DOFS)}"
            )
        if isinstance(value, bool) or not isinstance(value, int | float) or not (np.isfinite(value) and value >= 0):
            raise ValueError(f"mooring of body {body!r}: {label} of {name} must be a finite number >= 0; got {value!r}")
        out[name] = float(value)
    return out


@dataclass(frozen=True)
class Mooring:
    """Linear springs and dampers on one body's DOFs (see the module docstring).

    Parameters
    ----------
    body : str
        The model body it holds.
    stiffness : mapping of DOF name to float
        Stiffness per rigid-body DOF (``Surge`` ... ``Yaw``, any case) [N/m or N m/rad]; DOFs not named have none.
    damping : mapping of DOF name to float
        Damping per DOF [N s/m or N m s/rad].

    Raises
    ------
    ValueError
        On unknown DOF names, negative or non-finite values, or a mooring with neither stiffness nor damping.
    """

    body: str
    stiffness: Mapping[str, float] = field(default_factory=dict)
    damping: Mapping[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.body, str):
            raise ValueError(f"a mooring's body must be a body name; got {self.body!r}")
        object.__setattr__(self, "stiffness", _per_dof(self.body, "stiffness", self.stiffness))
        object.__setattr__(self, "damping", _per_dof(self.body, "damping", self.damping))
        if not any(self.stiffness.values()) and not any(self.damping.values()):
            raise ValueError(f"mooring of body {self.body!r}: give a positive stiffness or damping on some DOF")

    @classmethod
    def from_spec(cls, entry: Mapping[str, Any]) -> Mooring:
        """A mooring from a device spec's ``[[moorings]]`` entry (keys ``body``, ``stiffness``, ``damping``).

        Raises
        ------
        ValueError
            On unknown or missing keys or bad values.
        """
        unknown = sorted(set(entry) - set(MOORING_KEYS))
        if unknown:
            raise ValueError(f"unknown keys {unknown}; accepted: {list(MOORING_KEYS)}")
        if "body" not in entry:
            raise ValueError("missing key 'body'")
        return cls(entry["body"], entry.get("stiffness", {}), entry.get("damping", {}))

    def to_dict(self) -> dict[str, Any]:
        return {"body": self.body, "stiffness": dict(self.stiffness), "damping": dict(self.damping)}


def mooring_matrices(model: Multibody, moorings: tuple[Mooring, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and damping (n_cart, n_cart) of ``moorings`` in the model's Cartesian coordinates (the rigid rows
    of each body, about the centres of mass, world axes; none on the modes) [SI].

    Raises
    ------
    ValueError
        If a mooring names a body the model does not have.
    """
    n_cart = model.n_cart
    stiffness, damping = np.zeros((n_cart, n_cart)), np.zeros((n_cart, n_cart))
    for mooring in moorings:
        if mooring.body not in model.body_names:
            raise ValueError(f"mooring: unknown body {mooring.body!r}; the model has {', '.join(model.body_names)}")
        i = list(model.body_names).index(mooring.body)
        for matrix, values in ((stiffness, mooring.stiffness), (damping, mooring.damping)):
            for dof, value in values.items():
                k = model.cart_start[i] + RIGID_BODY_DOFS.index(dof)
                matrix[k, k] += value
    return stiffness, damping
