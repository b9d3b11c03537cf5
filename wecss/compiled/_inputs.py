"""The files a scene's run reads, each under the field that names it: what no output of the run may overwrite
(``wecss.files.refuse_overwrite``) and what the per-process caches of :func:`compile_plant` watch."""

from __future__ import annotations

from pathlib import Path

from ..devices import DEVICE_DIR, hydro_source, read_spec, spec_inputs
from ..hydro import DATA_DIR as HYDRO_DIR
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


def device_spec_path(scene: Scene) -> Path | None:
    """The spec file of the scene's device: the user's ``.toml`` or the catalogue's shipped spec (None when
    ``device.name`` is neither)."""
    name = scene.device.name
    path = Path(name) if name.endswith(".toml") else DEVICE_DIR / f"{name}.toml"
    return path.resolve() if path.is_file() else None


def _database(source: str | None) -> Path | None:
    """The file a database source (a path or a shipped name) stands for, or None."""
    if source is None:
        return None
    path = Path(source)
    if path.is_file():
        return path.resolve()
    shipped = HYDRO_DIR / f"{source}.nc"
    return shipped if "/" not in source and shipped.is_file() else None


def recorded_inputs(scene: Scene) -> dict[str, Path]:
    """Every file a run of ``scene`` reads, shipped ones included, under the field that names it: the device spec,
    the files it names (meshes), the database the device is read with (``device.hydro``, else the spec's
    ``hydro``) and ``sea.file``; what a result records with checksums (``wecss.provenance``)."""
    files: dict[str, Path] = {}
    spec = device_spec_path(scene)
    if spec is not None:
        for label, path in spec_inputs(spec).items():
            if not (label.startswith("hydrodynamic database") and scene.device.hydro is not None):
                files[f"{label} of device.name"] = path
        data, folder = read_spec(spec)
        database = None if scene.device.hydro is not None else _database(hydro_source(data, folder))
        if database is not None and database not in files.values():
            files["hydrodynamic database named by the device spec (hydro) of device.name"] = database
    database = _database(scene.device.hydro)
    if database is not None:
        files["hydrodynamic database (device.hydro)"] = database
    if scene.sea.file is not None:
        files[f"{SEA_FILES.get(scene.sea.kind, 'sea file')} (sea.file)"] = Path(scene.sea.file).resolve()
    return files
