"""A sweep: a base scene and axes of dotted scene paths with their values, expanded to cases (a full grid or a list).

A sweep file (TOML)::

    [sweep]
    name = "m4-134 power matrix"
    mode = "grid"                      # or "list": the i-th values of every axis make case i

    [sweep.axes]
    "sea.period" = [0.8, 1.0, 1.2]
    "sea.height" = [0.04, 0.06]

    [scene]                            # the base scene, as a scene file's sections (or scene = "file.toml")
    device.name = "m4-134"
    solver.method = "frequency"

Every case is the base scene with the axes' values set (:func:`set_path`) and is validated by the scene itself, so a
bad path or value fails with the scene's own message before any run.
"""

from __future__ import annotations

import itertools
import math
import re
import sys
import tomllib
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..limits import SWEEP_ANNOUNCE_CASES, SWEEP_CASES, beyond
from ..scene import Scene, SceneError, default_scene_path, plain_copy, set_path
from ..tomlfile import read_toml

SWEEP_MODES = ("grid", "list")


def parse_value(text: str) -> Any:
    """A command-line value read as TOML (``1.4``, ``true``, ``"m4-111"``, ``[1, 2]``); bare words stay strings."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def apply_overrides(scene: Scene, assignments: Sequence[str]) -> Scene:
    """``scene`` with ``path=value`` assignments (``wecss run --set sea.period=1.4``) applied and validated.

    Raises
    ------
    SceneError
        On an assignment without ``=``, an unknown path or a bad value (the scene's own message).
    """
    data = plain_copy(scene.to_dict())
    for text in assignments:
        path, sep, value = text.partition("=")
        if not sep:
            raise SceneError(f"--set takes path=value (such as sea.period=1.4); got {text!r}")
        data = set_path(data, path.strip(), parse_value(value.strip()))
    return Scene.from_dict(data)


def _label(value: Any) -> str:
    text = repr(value) if isinstance(value, float) else str(value)
    return re.sub(r"[^A-Za-z0-9.+-]+", "_", text)[:40]


@dataclass(frozen=True)
class Case:
    """One case of a sweep: its index, its values on the axes and its scene."""

    index: int
    values: tuple[tuple[str, Any], ...]
    scene: Scene

    @property
    def name(self) -> str:
        """File stem: the index and the values (``c0003_sea.period=1.4``)."""
        return f"c{self.index:04d}_" + "_".join(f"{p}={_label(v)}" for p, v in self.values)


@dataclass(frozen=True)
class Sweep:
    """A base scene (as a dict) and axes; :attr:`cases` expands them and validates every case.

    Attributes
    ----------
    base : dict
        The base scene's sections (``Scene.to_dict`` layout; missing keys take the scene's defaults).
    axes : tuple of (str, tuple)
        Dotted scene paths and their values.
    mode : {"grid", "list"}
        "grid": every combination (the axes become the combined dataset's dimensions); "list": the i-th value of
        every axis makes case i (all axes of one length; dimension ``case``).
    name : str
    allow_large : bool
        Expand more than ``wecss.limits.SWEEP_CASES`` (10,000) cases all the same (default False: refused before
        any case is made). A sweep of more than ``SWEEP_ANNOUNCE_CASES`` (1000) cases says its size on standard
        error before its cases are validated.
    """

    base: dict[str, Any]
    axes: tuple[tuple[str, tuple[Any, ...]], ...]
    mode: str = "grid"
    name: str = "sweep"
    allow_large: bool = False

    def __post_init__(self) -> None:
        if self.mode not in SWEEP_MODES:
            raise SceneError(f"sweep.mode: unknown {self.mode!r}; accepted: {', '.join(SWEEP_MODES)}")
        if not self.axes:
            raise SceneError("sweep.axes is empty: give at least one scene path and its values")
        seen = set()
        for path, values in self.axes:
            if path in seen:
                raise SceneError(f"sweep.axes: {path!r} is given twice")
            seen.add(path)
            if not isinstance(values, tuple) or not values:
                raise SceneError(f"sweep.axes.{path}: give a non-empty list of values; got {values!r}")
            if len(set(map(repr, values))) != len(values):
                raise SceneError(f"sweep.axes.{path}: values repeat: {list(values)}")
        if self.mode == "list":
            lengths = {p: len(v) for p, v in self.axes}
            if len(set(lengths.values())) != 1:
                raise SceneError(f"sweep.mode 'list' needs axes of one length; got {lengths}")
        self._check_size()
        self.cases  # noqa: B018 (every case validated on construction)

    def _check_size(self) -> None:
        """Refuse more than SWEEP_CASES cases without ``allow_large``; say the size of a large sweep at once."""
        if not isinstance(self.allow_large, bool):
            raise SceneError(f"sweep.allow_large must be true or false; got {self.allow_large!r}")
        n = math.prod(self.shape)
        grid = " x ".join(str(k) for k in self.shape) if self.mode == "grid" else f"a list of {n}"
        if n > SWEEP_CASES and not self.allow_large:
            raise SceneError(
                beyond(
                    f"sweep {self.name!r}: cases",
                    f"{n} ({grid})",
                    SWEEP_CASES,
                    "each case's scene is checked before the first runs and each case is a file",
                    "give allow_large = true in the [sweep] table (Sweep(..., allow_large=True))",
                )
            )
        if n > SWEEP_ANNOUNCE_CASES:
            print(f"sweep {self.name!r}: {n} cases ({grid}); checking every case's scene", file=sys.stderr, flush=True)

    @property
    def cases(self) -> tuple[Case, ...]:
        """Every case, validated (cached)."""
        cached = self.__dict__.get("_cases")
        if cached is None:
            paths = [p for p, _ in self.axes]
            columns = [v for _, v in self.axes]
            rows = itertools.product(*columns) if self.mode == "grid" else zip(*columns, strict=True)
            out = []
            for index, row in enumerate(rows):
                data = self.base
                for path, value in zip(paths, row, strict=True):
                    data = set_path(data, path, value)
                values = tuple(zip(paths, row, strict=True))
                try:
                    scene = Scene.from_dict(data)
                except SceneError as err:
                    raise SceneError(f"case {index} ({dict(values)}): {err}") from None
                out.append(Case(index, values, scene))
            cached = tuple(out)
            object.__setattr__(self, "_cases", cached)
        return cached

    @property
    def shape(self) -> tuple[int, ...]:
        """Sizes of the combined dataset's sweep dimensions."""
        return tuple(len(v) for _, v in self.axes) if self.mode == "grid" else (len(self.axes[0][1]),)

    @classmethod
    def from_dict(cls, data: dict[str, Any], *, base: Path | None = None) -> Sweep:
        """From the tables of a sweep file: ``[sweep]`` (name, mode, axes) and ``[scene]`` (a table or a file).

        Raises
        ------
        SceneError
            On unknown keys, bad axes, or any case the scene refuses.
        """
        unknown = sorted(set(data) - {"sweep", "scene"})
        if unknown:
            raise SceneError(f"unknown tables {unknown} in the sweep file; accepted: sweep, scene")
        table = data.get("sweep")
        if not isinstance(table, dict):
            raise SceneError("the sweep file needs a [sweep] table with its axes")
        extra = sorted(set(table) - {"name", "mode", "axes", "allow_large"})
        if extra:
            raise SceneError(f"[sweep]: unknown keys {extra}; accepted: name, mode, axes, allow_large")
        axes_table = table.get("axes", {})
        if not isinstance(axes_table, dict):
            raise SceneError(f"sweep.axes must be a table of path = [values]; got {axes_table!r}")
        axes = []
        for path, values in _flatten(axes_table):
            if not isinstance(values, list):
                raise SceneError(f"sweep.axes.{path}: give a list of values; got {values!r}")
            axes.append((path, tuple(values)))
        scene = data.get("scene", {})
        if isinstance(scene, str):
            file = Path(scene) if base is None or Path(scene).is_absolute() else base / scene
            scene_obj = Scene.from_toml(file)
        elif isinstance(scene, dict):
            scene_obj = Scene.from_dict(scene, base=base)
        else:
            raise SceneError(f"scene: give a table of scene sections or a scene file; got {scene!r}")
        return cls(
            base=plain_copy(scene_obj.to_dict()),
            axes=tuple(axes),
            mode=table.get("mode", "grid"),
            name=str(table.get("name", "sweep")),
            allow_large=table.get("allow_large", False),
        )

    @classmethod
    def from_toml(cls, path: str | Path) -> Sweep:
        """Read a sweep file (relative paths from its folder).

        Raises
        ------
        FileNotFoundError
        SceneError
        """
        path = Path(path)
        if not path.is_file():
            raise FileNotFoundError(f"no sweep file at {str(path)!r}")
        try:
            data = read_toml(path)
        except tomllib.TOMLDecodeError as err:
            raise SceneError(f"{path}: not valid TOML: {err}") from None
        except UnicodeDecodeError as err:
            raise SceneError(
                f"{path}: not a text file (byte {err.start} is {err.object[err.start : err.start + 1]!r}, not "
                "UTF-8); a sweep file is a UTF-8 TOML file"
            ) from None
        return cls.from_dict(data, base=path.parent)

    @classmethod
    def of(
        cls,
        scene: Scene | None,
        axes: dict[str, Sequence[Any]],
        *,
        mode: str = "grid",
        name: str = "sweep",
        allow_large: bool = False,
    ) -> Sweep:
        """From a scene (default: the embedded default) and ``{path: values}``."""
        scene = scene if scene is not None else Scene.from_toml(default_scene_path())
        axes_ = tuple((p, tuple(v)) for p, v in axes.items())
        return cls(plain_copy(scene.to_dict()), axes_, mode=mode, name=name, allow_large=allow_large)


def _flatten(table: dict[str, Any], prefix: str = "") -> list[tuple[str, Any]]:
    """Axes written as nested TOML tables (``sea.period = [...]`` without quotes) back to dotted paths."""
    out = []
    for key, value in table.items():
        path = f"{prefix}{key}"
        if isinstance(value, dict):
            out.extend(_flatten(value, f"{path}."))
        else:
            out.append((path, value))
    return out
