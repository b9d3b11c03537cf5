"""Scenes the benchmark studies share: the embedded default scene on another layout, radiation method and duration."""

from __future__ import annotations

import dataclasses

from wecss.sim import Scene, default_scene_path


def layout_scene(device: str, radiation: str, duration: str | float, ramp: str | float = "5 Tp") -> Scene:
    """The default scene on another layout, radiation method and duration."""
    base = Scene.from_toml(default_scene_path())
    return dataclasses.replace(
        base,
        device=dataclasses.replace(base.device, name=device),
        sea=dataclasses.replace(base.sea, duration=duration, ramp=ramp),
        radiation=dataclasses.replace(base.radiation, method=radiation),
    )
