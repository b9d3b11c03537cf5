"""The files a scene's run reads, each under the field that names it: what no output of the run may overwrite
(``wecss.files.refuse_overwrite``) and what the per-process caches of :func:`compile_plant` watch."""

from __future__ import annotations

from pathlib import Path

from ..devices import spec_inputs
from ..radiation import SHIPPED_FITS_DIR, cache_dir
from ..scene import Scene

SHIPPED_DATA_DIR = SHIPPED_FITS_DIR.parent
"""The package's data folder (``wecss/data``): the catalogue's specs and databases, the shipped fits and scenes."""

SEA_FILES = {"elevation": "measured elevation record", "tabulated": "tabulated spectrum"}
"""What ``sea.file`` holds, by ``sea.kind``."""


def device_inputs(name: str, hydro: str | None) -> dict[str, Path]:
    """The user's files a device is read from: the spec file ``name`` (when it is one, with the database and meshes
    it names) and the database file ``hydro``; catalogue names stand for files shipped with wecss (none listed)."""
    files: dict[str, Path] = {}
    if name.endswith(".toml") and Path(name).is_file():
        files.update({f"{label} of device.name": path for label, path in spec_inputs(name).items()})
    if hydro is not None and Path(hydro).is_file():
        files["hydrodynamic database (device.hydro)"] = Path(hydro).resolve()
    return files


def scene_inputs(scene: Scene) -> dict[str, Path]:
    """Every file and folder a run of ``scene`` reads, under the field that names it: the device spec and the files
    it names, the database, ``sea.file``, the user's radiation-fit cache folder and the data shipped with wecss
    (catalogue devices' specs and databases, fits), inside which no result belongs."""
    files = device_inputs(scene.device.name, scene.device.hydro)
    if scene.sea.file is not None:
        what = SEA_FILES.get(scene.sea.kind, "sea file")
        files[f"{what} (sea.file)"] = Path(scene.sea.file).resolve()
    files["radiation-fit cache folder ($WECSS_CACHE_DIR/radiation)"] = cache_dir()
    files["data shipped with wecss (catalogue specs, databases, fits)"] = SHIPPED_DATA_DIR
    return files
