"""Run every study with ``--quick`` (what ``make studies-quick`` and CI do): each ``studies/[a-z]*.py`` (the
``_``-prefixed modules are helpers), in name order, each in its own process, stopping at the first that fails.

    python studies/_quick.py                    # every study
    python studies/_quick.py m4_paper notc      # some of them
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

STUDIES = Path(__file__).resolve().parent


def studies() -> list[Path]:
    """Every study script: ``studies/[a-z]*.py``, in name order."""
    return sorted(STUDIES.glob("[a-z]*.py"))


def main(argv: list[str] | None = None) -> int:
    known = {path.stem: path for path in studies()}
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help=f"studies to run (default: all): {', '.join(known)}")
    args = parser.parse_args(argv)
    unknown = sorted(set(args.names) - set(known))
    if unknown:
        parser.error(f"unknown studies: {', '.join(unknown)}; known: {', '.join(known)}")
    chosen = [known[name] for name in args.names] if args.names else list(known.values())
    times = []
    for path in chosen:
        script = path.relative_to(STUDIES.parent)
        print(f"== {script} --quick", flush=True)
        start = time.perf_counter()
        status = subprocess.run([sys.executable, str(path), "--quick"]).returncode
        times.append((script, time.perf_counter() - start))
        if status != 0:
            print(f"studies-quick: {script} --quick failed (exit status {status})", file=sys.stderr, flush=True)
            return 1
    print("\n".join(["== studies --quick: wall time", *(f"{t:7.1f} s  {s}" for s, t in times)]), flush=True)
    print(f"{sum(t for _, t in times):7.1f} s  in all ({len(times)} studies)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
