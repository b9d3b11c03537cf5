"""The device catalogue: specs shipped in ``wecss/data/devices`` (``wecss.devices.load("m4-134")``)."""

from __future__ import annotations

from pathlib import Path

from ._device import Device

DEVICE_DIR = Path(__file__).resolve().parent.parent / "data" / "devices"


def available() -> list[str]:
    """Names of the catalogue devices."""
    return sorted(p.stem for p in DEVICE_DIR.glob("*.toml"))


def load(name: str) -> Device:
    """Build a catalogue device by name.

    Raises
    ------
    ValueError
        If the name is not in the catalogue (the message lists the names).
    """
    names = available()
    if name not in names:
        raise ValueError(f"no catalogue device {name!r}; available: {', '.join(names)}")
    return Device.from_spec(DEVICE_DIR / f"{name}.toml")
