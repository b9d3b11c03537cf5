"""Text parsing of WAMIT output files: the ``.out`` report and the numeric ``.1``, ``.2``/``.3``, ``.hst``, ``.mmx``.

Everything here returns values as WAMIT writes them: non-dimensional (length scale ULEN, rho, g), with
mode indices 1..N turned into 0-based positions. WAMIT numbers the modes of all bodies in one sequence: body k has
6 rigid-body modes and then its NEWMDS(k) generalised modes, so N = sum over bodies of 6 + NEWMDS(k).
Dimensions, units and the wecss schema are the business of :mod:`wecss.hydro.readers.wamit`.

Coefficient tables are parsed in bulk (all rows of all frequencies joined and converted by numpy at once);
only when that fails are the lines walked one by one, to name the file and line at fault.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

_NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[EeDd][-+]?\d+)?")
_SECTION_RULE = "*****"


class WamitFormatError(ValueError):
    """A WAMIT output file holds something the reader cannot interpret (the message names file and line)."""


@dataclass(frozen=True)
class BodyParameters:
    """What the ``.out`` header says about one body (lengths dimensional [m], as WAMIT prints them).

    ``center_of_buoyancy`` and ``center_of_gravity`` are in the body coordinate system (origin at XBODY).
    ``restoring`` holds the printed C(i, j) (non-dimensional, 1-based mode pairs within the body).
    """

    number: int
    origin: np.ndarray
    phibody_deg: float
    volumes: np.ndarray
    center_of_buoyancy: np.ndarray | None
    restoring: dict[tuple[int, int], float]
    restoring_includes_gravity: bool
    center_of_gravity: np.ndarray | None
    radii_of_gyration: np.ndarray | None
    line: int


@dataclass(frozen=True)
class OutFile:
    """The parsed ``.out`` report (coefficients non-dimensional, modes 0-based, N = sum of 6 + NEWMDS(k)).

    ``periods`` [s] are the finite wave periods in file order; the matrices follow that order.
    ``radiation_modes`` and ``excitation_modes`` flag the modes that appear in the tables;
    ``generalised_modes`` holds NEWMDS(k) per body (the counts given to :func:`read_out`).
    """

    path: Path
    version: str
    gravity: float
    length_scale: float
    water_depth: float
    geometry_files: tuple[str, ...]
    bodies: tuple[BodyParameters, ...]
    periods: np.ndarray
    added_mass: np.ndarray
    damping: np.ndarray
    added_mass_zero_frequency: np.ndarray | None
    added_mass_infinite_frequency: np.ndarray | None
    headings_deg: np.ndarray
    excitation: np.ndarray | None
    radiation_modes: np.ndarray
    excitation_modes: np.ndarray
    generalised_modes: tuple[int, ...] = ()

    @property
    def mode_start(self) -> np.ndarray:
        """0-based index of each body's first mode (its Surge) in WAMIT's sequence of modes."""
        sizes = [6 + m for m in self.generalised_modes] or [6] * len(self.bodies)
        return np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(int)

    @property
    def n_modes(self) -> int:
        """N, the number of modes of all bodies."""
        return sum(6 + m for m in self.generalised_modes) if self.generalised_modes else 6 * len(self.bodies)


def _error(path: Path, line: int, message: str) -> WamitFormatError:
    """An error naming ``path`` and the 1-based ``line`` (``line`` is a 0-based index)."""
    return WamitFormatError(f"{path}, line {line + 1}: {message}")


def _numbers(path: Path, lines: Sequence[str], index: int, after: str, count: int, what: str) -> np.ndarray:
    """The first ``count`` numbers after the text ``after`` on line ``index``."""
    text = lines[index]
    start = text.find(after)
    found = _NUMBER.findall(text[start + len(after) :] if start >= 0 else text)
    if len(found) < count:
        raise _error(path, index, f"expected {count} numbers for {what} after {after!r}; got {text.strip()!r}")
    return np.array([float(x.replace("D", "E").replace("d", "e")) for x in found[:count]])


def _next_nonblank(lines: Sequence[str], index: int) -> int:
    while index < len(lines) and not lines[index].strip():
        index += 1
    return index


def _end_of_rows(lines: Sequence[str], index: int) -> int:
    """Index of the first blank line (or section rule) at or after ``index``."""
    while index < len(lines) and lines[index].strip() and not lines[index].lstrip().startswith(_SECTION_RULE):
        index += 1
    return index


def parse_rows(path: Path, lines: Sequence[str], spans: Sequence[tuple[int, int]], ncols: int, what: str) -> np.ndarray:
    """Rows of ``ncols`` numbers from the line ranges ``spans``, as one ``(n_rows, ncols)`` array.

    The conversion is done by numpy on all lines at once; on failure the offending line is located.

    Raises
    ------
    WamitFormatError
        Naming the file and line of the first row that does not hold ``ncols`` numbers.
    """
    chunks = [lines[s:e] for s, e in spans]
    n_rows = sum(len(c) for c in chunks)
    if n_rows == 0:
        return np.zeros((0, ncols))
    joined = "\n".join(line for chunk in chunks for line in chunk)
    try:
        values = np.array(joined.split(), dtype=float)
    except ValueError:
        values = np.zeros(0)
    if values.size == n_rows * ncols:
        return values.reshape(n_rows, ncols)
    for start, end in spans:
        for index in range(start, end):
            tokens = lines[index].split()
            try:
                [float(t) for t in tokens]
            except ValueError:
                tokens = []
            if len(tokens) != ncols:
                raise _error(path, index, f"expected {ncols} numbers ({what}); got {lines[index].strip()!r}")
    raise WamitFormatError(f"{path}: could not read the {what} rows")  # pragma: no cover (unreachable)


def _mode_indices(
    path: Path, columns: np.ndarray, line_numbers: np.ndarray, n_modes: int, what: str
) -> tuple[np.ndarray, ...]:
    """0-based mode indices from 1-based float columns, checked against ``n_modes``."""
    out = []
    for col in columns:
        idx = np.rint(col).astype(int)
        bad = (idx < 1) | (idx > n_modes) | (np.abs(col - idx) > 1e-9)
        if np.any(bad):
            k = int(np.argmax(bad))
            raise _error(
                path,
                int(line_numbers[k]),
                f"mode index {col[k]:g} in the {what} is outside 1..{n_modes} (6 per body plus its generalised "
                "modes); generalised modes (NEWMDS) need their number per body: keep the run's .cfg beside the .out "
                "or pass mode_names",
            )
        out.append(idx - 1)
    return tuple(out)


def _line_numbers(spans: Sequence[tuple[int, int]]) -> np.ndarray:
    if not spans:
        return np.zeros(0, dtype=int)
    return np.concatenate([np.arange(s, e) for s, e in spans])


def read_out(path: Path, excitation: str = "diffraction", generalised_modes: dict[int, int] | None = None) -> OutFile:
    """Parse a WAMIT ``.out`` file.

    Parameters
    ----------
    path : pathlib.Path
        The ``.out`` file.
    excitation : {"diffraction", "haskind"}
        Which exciting-force tables to read.
    generalised_modes : dict of int to int, optional
        NEWMDS(k) by 1-based body number (bodies left out have none); default: no generalised modes.

    Raises
    ------
    WamitFormatError
        If a required item (gravity, length scale, water depth, body parameters, coefficient tables) is
        missing or a line cannot be read; the message names file and line.
    """
    title = {"diffraction": "DIFFRACTION EXCITING FORCES", "haskind": "HASKIND EXCITING FORCES"}[excitation]
    lines = path.read_text(errors="replace").splitlines()
    n_lines = len(lines)

    version = ""
    gravity: float | None = None
    length_scale: float | None = None
    water_depth: float | None = None
    geometry: list[str] = []
    bodies: list[BodyParameters] = []
    body: dict[str, object] | None = None

    periods: list[float] = []
    period_lines: list[int] = []
    kind = ""  # "", "zero" (omega = 0), "inf" (omega = inf) or "finite"
    ab_spans: list[tuple[int, int]] = []
    ab_period: list[int] = []
    special_spans: dict[str, tuple[int, int]] = {}
    ex_spans: list[tuple[int, int]] = []
    ex_period: list[int] = []
    ex_heading: list[float] = []
    ex_heading_lines: list[int] = []

    def finish_body() -> None:
        if body is not None:
            bodies.append(BodyParameters(**body))  # type: ignore[arg-type]

    i = 0
    while i < n_lines:
        line = lines[i]
        if "Wave period" in line:
            if "Wave period = infinite" in line:
                kind = "zero"
            elif "Wave period = zero" in line:
                kind = "inf"
            elif "Wave period (sec)" in line:
                kind = "finite"
                periods.append(float(_numbers(path, lines, i, "=", 1, "the wave period")[0]))
                period_lines.append(i)
            else:
                raise _error(path, i, f"unrecognised wave-period line {line.strip()!r}")
        elif "ADDED-MASS" in line and "COEFFICIENTS" in line:
            if not kind:
                raise _error(path, i, "added-mass table before any 'Wave period' line")
            head = _next_nonblank(lines, i + 1)
            if head >= n_lines or "A(I,J)" not in lines[head]:
                raise _error(path, head if head < n_lines else i, "expected the column header 'I J A(I,J) ...'")
            start = _next_nonblank(lines, head + 1)
            end = _end_of_rows(lines, start)
            if kind == "finite":
                ab_spans.append((start, end))
                ab_period.append(len(periods) - 1)
            else:
                special_spans[kind] = (start, end)
            i = end
            continue
        elif title in line:
            if kind != "finite":
                raise _error(path, i, "exciting forces outside a finite wave-period section")
            j = _next_nonblank(lines, i + 1)
            while j < n_lines and "Wave Heading" in lines[j]:
                heading = float(_numbers(path, lines, j, ":", 1, "the wave heading")[0])
                head = _next_nonblank(lines, j + 1)
                if head >= n_lines or "Mod[" not in lines[head]:
                    raise _error(path, min(head, n_lines - 1), "expected the column header 'I Mod[..] Pha[..]'")
                start = _next_nonblank(lines, head + 1)
                end = _end_of_rows(lines, start)
                ex_spans.append((start, end))
                ex_period.append(len(periods) - 1)
                ex_heading.append(heading)
                ex_heading_lines.append(j)
                j = _next_nonblank(lines, end)
            i = j
            continue
        elif not periods and kind == "":
            # header: run parameters and body parameters
            if "WAMIT  Version" in line or "WAMIT Version" in line:
                version = line.split("Version", 1)[1].strip()
            elif "Gravity:" in line:
                gravity = float(_numbers(path, lines, i, "Gravity:", 1, "gravity")[0])
                if "Length scale:" in line:
                    length_scale = float(_numbers(path, lines, i, "Length scale:", 1, "the length scale")[0])
            elif "Water depth:" in line:
                rest = line.split("Water depth:", 1)[1].strip().lower()
                if rest.startswith("infinite"):
                    water_depth = float("inf")
                else:
                    water_depth = float(_numbers(path, lines, i, "Water depth:", 1, "the water depth")[0])
            elif "Input from Geometric Data File:" in line:
                geometry.append(line.split(":", 1)[1].strip())
            elif re.match(r"^\s*N=\s*\d+\s+\S", line) and not bodies and body is None:
                geometry.append(line.split()[-1])
            elif "XBODY" in line:
                finish_body()
                values = []
                for key in ("XBODY", "YBODY", "ZBODY", "PHIBODY"):
                    values.append(float(_numbers(path, lines, i, key, 1, key)[0]) if key in line else np.nan)
                if np.any(np.isnan(values)):
                    raise _error(path, i, f"expected XBODY, YBODY, ZBODY and PHIBODY; got {line.strip()!r}")
                body = {
                    "number": len(bodies) + 1,
                    "origin": np.array(values[:3]),
                    "phibody_deg": values[3],
                    "volumes": np.full(3, np.nan),
                    "center_of_buoyancy": None,
                    "restoring": {},
                    "restoring_includes_gravity": False,
                    "center_of_gravity": None,
                    "radii_of_gyration": None,
                    "line": i,
                }
            elif body is not None and "Volumes (VOLX,VOLY,VOLZ):" in line:
                body["volumes"] = _numbers(path, lines, i, ":", 3, "the volumes")
            elif body is not None and "Center of Buoyancy" in line:
                body["center_of_buoyancy"] = _numbers(path, lines, i, ":", 3, "the centre of buoyancy")
            elif body is not None and "restoring coefficients" in line:
                body["restoring_includes_gravity"] = "gravitational" in line
                restoring: dict[tuple[int, int], float] = {}
                j = i + 1
                while j < n_lines and lines[j].lstrip().startswith("C("):
                    labels = lines[j].partition(":")[0]
                    pairs = re.findall(r"C\((\d+),(\d+)\)", labels)
                    vals = _numbers(path, lines, j, ":", len(pairs), "restoring coefficients")
                    for (a, b), v in zip(pairs, vals, strict=True):
                        restoring[(int(a), int(b))] = float(v)
                    j += 1
                if not restoring:
                    raise _error(path, i + 1, "expected lines 'C(3,3),C(3,4),C(3,5): ...' after the restoring header")
                body["restoring"] = restoring
                i = j
                continue
            elif body is not None and "Center of Gravity" in line:
                body["center_of_gravity"] = _numbers(path, lines, i, ":", 3, "the centre of gravity")
            elif body is not None and "Radii of gyration:" in line:
                radii = [_numbers(path, lines, i, ":", 3, "the radii of gyration")]
                for k in (1, 2):
                    if i + k >= n_lines:
                        raise _error(path, i, "radii of gyration: expected three lines of three numbers")
                    radii.append(_numbers(path, lines, i + k, "", 3, "the radii of gyration"))
                body["radii_of_gyration"] = np.vstack(radii)
                i += 3
                continue
        i += 1
    finish_body()

    if gravity is None or length_scale is None:
        raise WamitFormatError(f"{path}: no 'Gravity: ... Length scale: ...' line; is this a WAMIT .out file?")
    if water_depth is None:
        raise WamitFormatError(f"{path}: no 'Water depth:' line")
    if not bodies:
        raise WamitFormatError(f"{path}: no body parameters ('XBODY = ...' lines)")
    for b in bodies:
        if np.any(np.isnan(b.volumes)):
            raise _error(path, b.line, f"body {b.number}: no 'Volumes (VOLX,VOLY,VOLZ):' line")
    if not periods:
        raise WamitFormatError(f"{path}: no finite wave periods ('Wave period (sec) = ...' sections)")
    if len(ab_spans) != len(periods) or len(set(ab_period)) != len(periods):
        missing = sorted(set(range(len(periods))) - set(ab_period))
        where = period_lines[missing[0]] if missing else period_lines[0]
        raise _error(path, where, "each finite wave period needs one 'ADDED-MASS AND DAMPING COEFFICIENTS' table")

    per_body = dict(generalised_modes or {})
    beyond = sorted(k for k in per_body if not 1 <= k <= len(bodies))
    if beyond:
        raise WamitFormatError(f"{path}: generalised modes are given for body {beyond[0]}; the run has {len(bodies)}")
    generalised = tuple(int(per_body.get(k + 1, 0)) for k in range(len(bodies)))
    n_modes = sum(6 + m for m in generalised)
    n_per = len(periods)

    rows = parse_rows(path, lines, ab_spans, 4, "I J A(I,J) B(I,J)")
    line_numbers = _line_numbers(ab_spans)
    ii, jj = _mode_indices(path, rows[:, :2].T, line_numbers, n_modes, "added-mass table")
    block = np.repeat(np.asarray(ab_period), [e - s for s, e in ab_spans])
    added_mass = np.zeros((n_per, n_modes, n_modes))
    damping = np.zeros((n_per, n_modes, n_modes))
    added_mass[block, ii, jj] = rows[:, 2]
    damping[block, ii, jj] = rows[:, 3]
    radiation_modes = np.zeros(n_modes, dtype=bool)
    radiation_modes[ii] = True
    radiation_modes[jj] = True

    special: dict[str, np.ndarray | None] = {"zero": None, "inf": None}
    for key, span in special_spans.items():
        srows = parse_rows(path, lines, [span], 3, "I J A(I,J)")
        si, sj = _mode_indices(path, srows[:, :2].T, _line_numbers([span]), n_modes, "added-mass table")
        matrix = np.zeros((n_modes, n_modes))
        matrix[si, sj] = srows[:, 2]
        special[key] = matrix

    headings = np.zeros(0)
    excitation_array: np.ndarray | None = None
    excitation_modes = np.zeros(n_modes, dtype=bool)
    if ex_spans:
        headings = np.array(list(dict.fromkeys(ex_heading)))
        head_index = np.array([int(np.flatnonzero(headings == h)[0]) for h in ex_heading])
        seen = set(zip(ex_period, head_index.tolist(), strict=True))
        if len(seen) != len(ex_spans) or len(seen) != n_per * headings.size:
            raise _error(
                path,
                ex_heading_lines[0],
                f"expected one exciting-force table per period and heading ({n_per} x {headings.size}); "
                f"found {len(ex_spans)}",
            )
        erows = parse_rows(path, lines, ex_spans, 3, "I Mod Pha")
        (ei,) = _mode_indices(path, erows[:, :1].T, _line_numbers(ex_spans), n_modes, "exciting-force table")
        counts = [e - s for s, e in ex_spans]
        eper = np.repeat(np.asarray(ex_period), counts)
        ehead = np.repeat(head_index, counts)
        excitation_array = np.zeros((n_per, headings.size, n_modes), dtype=complex)
        excitation_array[eper, ehead, ei] = erows[:, 1] * np.exp(1j * np.deg2rad(erows[:, 2]))
        excitation_modes[ei] = True

    return OutFile(
        path=path,
        version=version,
        gravity=gravity,
        length_scale=length_scale,
        water_depth=water_depth,
        geometry_files=tuple(geometry),
        bodies=tuple(bodies),
        periods=np.asarray(periods),
        added_mass=added_mass,
        damping=damping,
        added_mass_zero_frequency=special["zero"],
        added_mass_infinite_frequency=special["inf"],
        headings_deg=headings,
        excitation=excitation_array,
        radiation_modes=radiation_modes,
        excitation_modes=excitation_modes,
        generalised_modes=generalised,
    )


def read_numeric(path: Path, ncols: Sequence[int], what: str) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """Rows of a numeric WAMIT file grouped by their number of columns.

    A first line that is not numeric (WAMIT's optional header) is skipped, as are blank lines.

    Returns
    -------
    dict
        For each accepted column count, ``(rows, line_numbers)`` with ``rows`` of shape ``(n, ncols)``
        and the 0-based line index of each row.

    Raises
    ------
    WamitFormatError
        If a line holds a number of columns not in ``ncols`` or something that is not a number.
    """
    lines = path.read_text(errors="replace").splitlines()
    start = 0
    if lines:
        first = lines[0].split()
        try:
            [float(t) for t in first[:1]]
        except ValueError:
            start = 1
    counts = np.array([len(line.split()) for line in lines[start:]], dtype=int)
    index = np.arange(start, len(lines))
    bad = ~np.isin(counts, [0, *ncols])
    if np.any(bad):
        k = int(index[np.argmax(bad)])
        raise _error(path, k, f"expected {' or '.join(map(str, ncols))} columns ({what}); got {lines[k].strip()!r}")
    out: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    for n in ncols:
        rows_at = index[counts == n]
        spans = _spans(rows_at)
        out[n] = (parse_rows(path, lines, spans, n, what), rows_at)
    return out


def _spans(indices: np.ndarray) -> list[tuple[int, int]]:
    """Contiguous ``(start, end)`` ranges covering sorted integer ``indices``."""
    if indices.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(indices) != 1)
    starts = np.concatenate([[indices[0]], indices[breaks + 1]])
    ends = np.concatenate([indices[breaks] + 1, [indices[-1] + 1]])
    return [(int(s), int(e)) for s, e in zip(starts, ends, strict=True)]


def read_mmx_mass(path: Path, n_bodies: int, generalised_modes: Sequence[int] = ()) -> list[np.ndarray]:
    """The 6x6 rigid-body block of the ``MASS(I,J)/RHO`` matrix of each body from a ``.mmx`` file (body coordinates,
    about XBODY); a body with ``generalised_modes[k]`` modes may list indices up to 6 + that number.

    Raises
    ------
    WamitFormatError
        If the file has no mass matrix for some body or a row cannot be read.
    """
    lines = path.read_text(errors="replace").splitlines()
    matrices: list[np.ndarray] = []
    i = 0
    while i < len(lines):
        if "mass matrix" in lines[i].lower():
            head = _next_nonblank(lines, i + 1)
            if head < len(lines) and "MASS(I,J)" in lines[head].upper():
                start = head + 1
                end = _end_of_rows(lines, start)
                rows = parse_rows(path, lines, [(start, end)], 3, "I J MASS(I,J)/RHO")
                k = len(matrices)
                size = 6 + (int(generalised_modes[k]) if k < len(generalised_modes) else 0)
                mi, mj = _mode_indices(path, rows[:, :2].T, _line_numbers([(start, end)]), size, "mass matrix")
                matrix = np.zeros((size, size))
                matrix[mi, mj] = rows[:, 2]
                matrices.append(matrix[:6, :6])
                i = end
                continue
        i += 1
    if len(matrices) != n_bodies:
        raise WamitFormatError(
            f"{path}: expected a normalised mass matrix for each of {n_bodies} bodies; found {len(matrices)}"
        )
    return matrices
