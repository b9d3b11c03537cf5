"""STL files (ASCII and binary) read as a soup of triangles.

Binary: an 80-byte header, a little-endian uint32 count n, then n records of 50 bytes (normal and three corners as
float32, a uint16 attribute); a file of exactly 84 + 50 n bytes is read as binary, whatever its header says (binary
files made by some CAD programs start with "solid" too). ASCII: ``facet normal ... outer loop vertex x y z (three
times) endloop endfacet``; only the vertices are read.
"""

from __future__ import annotations

import os

import numpy as np

from ._errors import MeshError

_RECORD = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])


def read_stl(path: str | os.PathLike[str]) -> np.ndarray:
    """The triangles of an STL file, shape (n, 3, 3), in the file's units.

    Raises
    ------
    FileNotFoundError
        If the file does not exist.
    MeshError
        If it holds no triangles, a facet with other than three vertices, or numbers that do not parse.
    """
    file = os.fspath(path)
    if not os.path.isfile(file):
        raise FileNotFoundError(f"no STL file at {file!r}")
    data = np.fromfile(file, dtype=np.uint8)
    if data.size >= 84:
        count = int(data[80:84].view("<u4")[0])
        if data.size == 84 + 50 * count:
            if count == 0:
                raise MeshError(f"{file}: the binary STL holds no triangles")
            records = np.frombuffer(data[84:].tobytes(), dtype=_RECORD, count=count)
            corners = records["corners"].astype(float)
            if not np.all(np.isfinite(corners)):
                raise MeshError(f"{file}: the binary STL holds coordinates that are not finite")
            return corners
    text = data.tobytes().decode("ascii", errors="replace")
    tokens = np.array(text.split())
    if tokens.size == 0 or tokens[0].lower() != "solid":
        raise MeshError(
            f"{file}: neither a binary STL ({data.size} bytes is not 84 + 50 x the triangle count in its header) "
            "nor an ASCII STL (which starts with 'solid')"
        )
    lower = np.char.lower(tokens)
    at = np.flatnonzero(lower == "vertex")
    facets = int(np.count_nonzero(lower == "facet"))
    if at.size == 0:
        raise MeshError(f"{file}: the ASCII STL holds no vertices")
    if at.size != 3 * facets or at[-1] + 3 >= tokens.size + 1:
        raise MeshError(f"{file}: {facets} facets hold {at.size} vertices; each facet must be one triangle")
    try:
        values = tokens[at[:, None] + np.arange(1, 4)].astype(float)
    except ValueError:
        raise MeshError(f"{file}: a vertex line does not hold three numbers") from None
    if not np.all(np.isfinite(values)):
        raise MeshError(f"{file}: the ASCII STL holds coordinates that are not finite")
    return values.reshape(-1, 3, 3)


def write_stl(path: str | os.PathLike[str], triangles: np.ndarray, *, binary: bool = True, name: str = "wecss") -> None:
    """Write triangles (n, 3, 3) [m] as an STL file (binary by default; ASCII with ``binary=False``)."""
    triangles = np.asarray(triangles, dtype=float)
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    normal = np.cross(b - a, c - a)
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    if binary:
        records = np.zeros(triangles.shape[0], dtype=_RECORD)
        records["normal"] = normal
        records["corners"] = triangles
        with open(path, "wb") as fh:
            fh.write(name.encode("ascii", errors="replace")[:80].ljust(80, b" "))
            fh.write(np.array([triangles.shape[0]], dtype="<u4").tobytes())
            fh.write(records.tobytes())
        return
    lines = [f"solid {name}"]
    for n, tri in zip(normal, triangles, strict=True):
        lines.append(f"  facet normal {n[0]:.9e} {n[1]:.9e} {n[2]:.9e}")
        lines.append("    outer loop")
        lines.extend(f"      vertex {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}" for p in tri)
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append(f"endsolid {name}")
    with open(path, "w", encoding="ascii") as fh:
        fh.write("\n".join(lines) + "\n")
