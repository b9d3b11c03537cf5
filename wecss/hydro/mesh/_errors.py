"""The error of an unusable surface mesh."""

from __future__ import annotations


class MeshError(ValueError):
    """A surface mesh is not usable: the message names the mesh (its file) and the problem."""
