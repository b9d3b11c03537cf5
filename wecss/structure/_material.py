"""Linear elastic isotropic materials: Young's modulus, shear modulus and density, and the named ones wecss ships."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

_KEYS = {"name", "E", "G", "nu", "density"}


@dataclass(frozen=True)
class Material:
    """A linear elastic isotropic material.

    Attributes
    ----------
    name : str
    youngs_modulus : float
        E [Pa].
    shear_modulus : float
        G [Pa].
    density : float
        rho [kg/m^3].
    source : str
        Where the numbers come from.

    Raises
    ------
    ValueError
        On a non-positive modulus or density, or a Poisson ratio E / (2 G) - 1 outside (-1, 0.5].
    """

    name: str
    youngs_modulus: float
    shear_modulus: float
    density: float
    source: str = ""

    def __post_init__(self) -> None:
        for key in ("youngs_modulus", "shear_modulus", "density"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int | float) or not (np.isfinite(value) and value > 0):
                raise ValueError(f"material {self.name!r}: {key} must be a positive number [SI], got {value!r}")
            object.__setattr__(self, key, float(value))
        nu = self.poisson_ratio
        if not -1.0 < nu <= 0.5:
            raise ValueError(
                f"material {self.name!r}: E = {self.youngs_modulus:g} Pa and G = {self.shear_modulus:g} Pa give a "
                f"Poisson ratio E / (2 G) - 1 = {nu:.4g}; accepted: -1 < nu <= 0.5"
            )

    @property
    def poisson_ratio(self) -> float:
        """nu = E / (2 G) - 1 [-]."""
        return self.youngs_modulus / (2 * self.shear_modulus) - 1

    @classmethod
    def from_spec(cls, where: str, value: Any) -> Material:
        """A material from a device spec: the name of a shipped one (:data:`MATERIALS`, such as ``"S355"``) or a
        table ``{E = 2.1e11, nu = 0.3, density = 7850.0}`` (E [Pa], G [Pa] or nu [-], density [kg/m^3], optionally
        a name).

        Raises
        ------
        ValueError
            On an unknown name, unknown or missing keys, both or neither of G and nu, or values the material
            refuses (the message says where, what was given and what is accepted).
        """
        if isinstance(value, Material):
            return value
        if isinstance(value, str):
            if value not in MATERIALS:
                raise ValueError(f"{where}: material {value!r} is not known; shipped: {sorted(MATERIALS)}, or give "
                                 "a table {E = ..., nu = ..., density = ...}")  # fmt: skip
            return MATERIALS[value]
        if not isinstance(value, Mapping):
            raise ValueError(
                f"{where}: material must be a name ({sorted(MATERIALS)}) or a table {{E, G or nu, density}}; "
                f"got {value!r}"
            )
        unknown = sorted(set(value) - _KEYS)
        if unknown or "E" not in value or "density" not in value or ("G" in value) == ("nu" in value):
            raise ValueError(
                f"{where}: material table has keys {sorted(value)}; it takes E [Pa], exactly one of G [Pa] and nu "
                "[-], density [kg/m^3] and optionally name"
            )
        numbers = {k: v for k, v in value.items() if k != "name"}
        for key, number in numbers.items():
            if isinstance(number, bool) or not isinstance(number, int | float):
                raise ValueError(f"{where}: material {key} must be a number, got {number!r}")
        e = float(value["E"])
        g = float(value["G"]) if "G" in value else e / (2 * (1 + float(value["nu"])))
        try:
            return cls(str(value.get("name", "given")), e, g, float(value["density"]), "device spec")
        except ValueError as err:
            raise ValueError(f"{where}: {err}") from None


MATERIALS: Mapping[str, Material] = {
    "S355": Material(
        "S355",
        200e9,
        200e9 / (2 * 1.3),
        7850.0,
        "paper 003 (Wang et al. 2018), Table 1: E 200 GPa, nu 0.3, 7850 kg/m^3",
    ),
}
"""Shipped materials by name."""
