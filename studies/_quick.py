"""Run every study with ``--quick`` (what ``make studies-quick`` and CI do): each ``studies/[a-z]*.py`` (the
``_``-prefixed modules are helpers), in name order, each in its own process, stopping at the first that fails.
With ``--jobs N`` up to N run at once, the next starting as soon as one ends: each one's output is printed whole, in
name order, and after a failure no further study starts (those already running end first).

    python studies/_quick.py                    # every study, one at a time
    python studies/_quick.py --jobs 2           # two at a time (what CI does on its two cores)
    python studies/_quick.py m4_paper notc      # some of them
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from collections import deque
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from pathlib import Path

STUDIES = Path(__file__).resolve().parent


def studies() -> list[Path]:
    """Every study script: ``studies/[a-z]*.py``, in name order."""
    return sorted(STUDIES.glob("[a-z]*.py"))


def run_one(path: Path, capture: bool) -> tuple[int, float, str]:
    """Run one study with ``--quick``: its exit status, its wall time [s] and, with ``capture``, its output (stdout
    then stderr; else it goes straight to this process's)."""
    start = time.perf_counter()
    done = subprocess.run([sys.executable, str(path), "--quick"], capture_output=capture, text=True)
    return done.returncode, time.perf_counter() - start, (done.stdout + done.stderr) if capture else ""


def main(argv: list[str] | None = None) -> int:
    known = {path.stem: path for path in studies()}
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help=f"studies to run (default: all): {', '.join(known)}")
    parser.add_argument("--jobs", type=int, default=1, help="studies run at once (default 1)")
    args = parser.parse_args(argv)
    unknown = sorted(set(args.names) - set(known))
    if unknown:
        parser.error(f"unknown studies: {', '.join(unknown)}; known: {', '.join(known)}")
    if args.jobs < 1:
        parser.error(f"--jobs must be a whole number of at least 1; got {args.jobs}")
    chosen = [known[name] for name in args.names] if args.names else list(known.values())
    times = []
    capture = args.jobs > 1
    begin = time.perf_counter()
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        # a study starts, in name order, as soon as a place is free; each output is printed once that study and all
        # before it have ended; after a failure none starts (those running end first: the pool waits for them)
        running: dict[Future[tuple[int, float, str]], int] = {}
        ended: dict[int, tuple[int, float, str]] = {}
        waiting = deque(range(len(chosen)))
        printed = 0  # chosen[:printed] are printed
        failed = False

        def start() -> None:
            index = waiting.popleft()
            if not capture:  # its output follows at once
                print(f"== {chosen[index].relative_to(STUDIES.parent)} --quick", flush=True)
            running[pool.submit(run_one, chosen[index], capture)] = index

        while waiting and len(running) < args.jobs:
            start()
        while running:
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            for future in done:
                index = running.pop(future)
                ended[index] = future.result()
                failed = failed or ended[index][0] != 0
            while printed in ended:
                status, seconds, output = ended.pop(printed)
                script = chosen[printed].relative_to(STUDIES.parent)
                printed += 1
                if capture:
                    print(f"== {script} --quick\n{output}", end="" if output.endswith("\n") else "\n", flush=True)
                times.append((script, seconds))
                if status != 0:
                    print(f"studies-quick: {script} --quick failed (exit status {status})", file=sys.stderr, flush=True)
                    return 1
            while not failed and waiting and len(running) < args.jobs:
                start()
    print("\n".join(["== studies --quick: wall time", *(f"{t:7.1f} s  {s}" for s, t in times)]), flush=True)
    print(f"{sum(t for _, t in times):7.1f} s  in all ({len(times)} studies)", flush=True)
    if capture:
        print(f"{time.perf_counter() - begin:7.1f} s  of wall time, {args.jobs} at once", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
