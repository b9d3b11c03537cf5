"""Generate the state-space radiation fits shipped with wecss (``wecss/data/radiation``): the band-limited MIMO
Hankel-SVD fits that ``radiation.method = "state_space"`` (the default) uses with its defaults, for the shipped
databases.

A scene finds them through the radiation cache (same key: a hash of the radiation data, the fit settings and the
band), so that the first state-space run of a shipped layout does not spend minutes fitting. The key does not
change when the fitting code does: rerun this script after changing ``wecss.radiation._fit``. They are stored in
real modal form (block-diagonal A, same kernel to rounding), compressed.

    python studies/generate_fits.py           # fit m4-111, m4-132, m4-134 afresh (minutes each)
    python studies/generate_fits.py m4-134    # one of them
    python studies/generate_fits.py --quick   # check that every shipped fit matches today's data and settings
"""

from __future__ import annotations

import argparse
import time

from wecss.compiled import fit_request
from wecss.devices import load as load_device
from wecss.radiation import SHIPPED_FITS_DIR, fit_cache_key, fit_radiation, load_cached_fit, store_fit
from wecss.scene import Scene

DATABASES = ("m4-111", "m4-132", "m4-134", "notc-10kw")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("names", nargs="*", help=f"databases to fit, of {', '.join(DATABASES)} (default: all)")
    args = parser.parse_args()
    unknown = sorted(set(args.names) - set(DATABASES))
    if unknown:
        parser.error(f"unknown databases {unknown}; choose from {', '.join(DATABASES)}")
    for name in args.names or DATABASES:
        hydro = load_device(name).coupling().hydro
        settings, band = fit_request(
            Scene().radiation, hydro
        )  # what a default scene with state-space radiation asks for
        key = fit_cache_key(hydro, settings, band)
        shipped = SHIPPED_FITS_DIR / f"{key}.nc"
        if args.quick:
            if not shipped.is_file():
                raise SystemExit(f"{name}: no shipped fit for today's data and settings ({shipped.name})")
            model, _ = load_cached_fit(key)  # type: ignore[misc]
            print(f"{name}: shipped fit {shipped.name}, {model.n_states} states, {shipped.stat().st_size / 1e3:.0f} kB")
            continue
        start = time.perf_counter()
        fit = fit_radiation(hydro, settings, band=band)  # a fresh fit: the cache would return the shipped one
        path = store_fit(key, fit.model.real_modal(), fit.report, folder=SHIPPED_FITS_DIR)
        print(
            f"{name}: {fit.model.n_states} states in {time.perf_counter() - start:.1f} s -> {path} "
            f"({path.stat().st_size / 1e3:.0f} kB)"
        )


if __name__ == "__main__":
    main()
