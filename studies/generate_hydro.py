"""Regenerate the shipped hydrodynamic databases ``wecss/data/hydro/<name>.nc`` from their geometry files.

Usage::

    python studies/generate_hydro.py m4-134            # one database (m4-134 takes about 20 minutes on 2 cores)
    python studies/generate_hydro.py --all             # all of them, one after the other
    python studies/generate_hydro.py --quick           # all of them, coarse, into a temporary folder (CI)
    python studies/generate_hydro.py m4-111 --quick    # one of them, coarse

Each run reads ``wecss/data/hydro/<name>.toml`` (floats, frequencies, mesh; every assumption is written there),
solves all floats together with Capytaine (``wecss.hydro.bem.run_bem``), stores the geometry file's text in the
``geometry_file_text`` attribute, writes the netCDF file atomically and checks that it loads and validates.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import tempfile
import time
import warnings
from pathlib import Path

from wecss.attributes import apply_attrs
from wecss.hydro import DATA_DIR, HydroData
from wecss.hydro.bem import BEMSpec, read_geometry, run_bem
from wecss.netcdf import write_netcdf

QUICK_PANEL_FACTOR = 4.0
"""--quick: panels this many times taller (the mesh keeps at least 24 sectors per float)."""

QUICK_FREQUENCIES = 8
"""--quick: number of frequencies kept, spread over the lower half of the file's range (the coarse mesh gives
negative heave damping near the top of the M4 range, where waves are a few panels long). --quick output only
tests the pipeline: on its sparse grid the irregular-frequency check flags the M4 arrays' genuine interference
peaks (they vary over 0.4-0.9 rad/s), which the script reports without failing."""


def available() -> list[str]:
    """Names of the geometry files in ``wecss/data/hydro``."""
    return sorted(p.stem for p in DATA_DIR.glob("*.toml"))


def quick_spec(spec: BEMSpec) -> BEMSpec:
    """A coarse version of ``spec`` for smoke runs: coarser mesh, a few frequencies."""
    lower = spec.omega[: max(QUICK_FREQUENCIES, len(spec.omega) // 2)]
    stride = max(1, len(lower) // QUICK_FREQUENCIES)
    return dataclasses.replace(
        spec,
        panel_size=spec.panel_size * QUICK_PANEL_FACTOR,
        omega=lower[stride - 1 :: stride],
        name=f"{spec.name} (quick)",
    )


def generate(name: str, output_dir: Path, *, quick: bool, n_jobs: int) -> Path:
    """Run the BEM for geometry file ``name``, write ``<output_dir>/<name>.nc`` and check it; return the path."""
    geometry = DATA_DIR / f"{name}.toml"
    spec = read_geometry(geometry)
    if quick:
        spec = quick_spec(spec)
    dataset = run_bem(
        spec,
        n_jobs=n_jobs,
        attrs={
            "geometry_file": geometry.name,
            "geometry_file_text": geometry.read_text(encoding="utf-8"),
            "generated_by": "studies/generate_hydro.py" + (" --quick" if quick else ""),
        },
    )
    path = write_netcdf(apply_attrs(dataset), output_dir / f"{name}.nc")  # long names and units on disk
    path.chmod(0o644)  # write_netcdf's temporary file is private (0600); shipped data are readable by all
    start = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        hydro = HydroData.from_netcdf(path)
    load_time = time.perf_counter() - start
    print(hydro.summary(), flush=True)
    print(
        f"{name}: wrote {path} ({path.stat().st_size / 1e6:.2f} MB), loads and validates in {load_time:.2f} s",
        flush=True,
    )
    for warning in caught:
        print(f"{name}: WARNING on validation: {warning.category.__name__}: {warning.message}", flush=True)
    return path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help=f"databases to generate, among: {', '.join(available())}")
    parser.add_argument("--all", action="store_true", help="generate every database that has a geometry file")
    parser.add_argument(
        "--quick",
        action="store_true",
        help="coarse smoke run written to a temporary folder (of every database unless names are given)",
    )
    parser.add_argument(
        "--output-dir",
        type=Path,
        help="folder for the .nc files (default: wecss/data/hydro, or a temporary one with --quick)",
    )
    parser.add_argument(
        "--n-jobs", type=int, default=1, help="Capytaine processes (default 1: it already uses all cores)"
    )
    args = parser.parse_args(argv)

    names = available() if args.all or (args.quick and not args.names) else args.names
    unknown = sorted(set(names) - set(available()))
    if not names or unknown:
        parser.error(
            f"give --all, --quick or names among {', '.join(available())}"
            + (f"; unknown: {', '.join(unknown)}" if unknown else "")
        )
    if args.n_jobs < 1:
        parser.error(f"--n-jobs must be at least 1; got {args.n_jobs}")
    output_dir = args.output_dir
    if output_dir is None:
        output_dir = Path(tempfile.mkdtemp(prefix="wecss-hydro-")) if args.quick else DATA_DIR
    output_dir.mkdir(parents=True, exist_ok=True)
    for name in names:
        generate(name, output_dir, quick=args.quick, n_jobs=args.n_jobs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
