"""The ``wecss`` command.

``wecss info`` lists the shipped hydrodynamic databases; ``wecss info DEVICE`` (a catalogue name such as
``m4-134``, or a spec ``.toml``) prints bodies, joints, generalised coordinates, masses and the undamped natural
periods; ``wecss info FILE.nc`` or a database name describes a hydrodynamic database. Further sub-commands
(``run``, ``plot``) arrive with the simulator.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from . import __version__


def _info(target: str | None) -> int:
    from . import hydro

    if target is None:
        names = hydro.available()
        if not names:
            print("no shipped hydrodynamic databases found in", hydro._catalogue.DATA_DIR)
            return 1
        print(f"wecss {__version__}: shipped hydrodynamic databases ({len(names)})\n")
        for name in names:
            start = time.perf_counter()
            data = hydro.load(name)
            elapsed = time.perf_counter() - start
            print(f"[{name}] loaded in {elapsed * 1e3:.0f} ms")
            print(data.summary())
            print()
        return 0
    from . import devices

    path = Path(target)
    if path.suffix == ".toml" or target in devices.available():
        device = devices.Device.from_spec(path) if path.suffix == ".toml" else devices.load(target)
        print(device.info())
        return 0
    if path.suffix == ".nc" or path.exists():
        data = hydro.HydroData.from_netcdf(path)
    elif target in hydro.available():
        data = hydro.load(target)
    else:
        known = sorted(set(devices.available()) | set(hydro.available()))
        raise ValueError(f"{target!r} is neither a file nor a known device or database; known: {', '.join(known)}")
    print(data.summary())
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``wecss`` command."""
    parser = argparse.ArgumentParser(prog="wecss", description="Multi-body wave energy converter toolkit.")
    parser.add_argument("--version", action="version", version=f"wecss {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    info = sub.add_parser("info", help="describe a device, a shipped hydrodynamic database or a netCDF file")
    info.add_argument("target", nargs="?", help="device or database name, device spec (.toml) or database (.nc)")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``wecss`` command; returns the exit status."""
    args = build_parser().parse_args(argv)
    try:
        if args.command == "info":
            return _info(args.target)
    except (ValueError, FileNotFoundError) as err:
        print(f"wecss: error: {err}", file=sys.stderr)
        return 2
    return 0  # pragma: no cover - argparse rejects unknown commands


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
