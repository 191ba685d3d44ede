"""Readers for the source mesh formats: Wavefront OBJ and the Badin face mesh (face.node,
face.elem).

Every reader validates what it returns (finite numbers, at least one face, indices in range) and
raises ``MeshFormatError`` naming the file, so a corrupt input stops the build with a message a
person can act on instead of a traceback from deep inside numpy.
"""

import re
from pathlib import Path

import numpy as np

# A Fortran-style real. face.node is fixed width and its fields can abut with no space between
# them ("0.57E-01-0.40E-02"), so splitting on whitespace is wrong; a number regex is right.
_REAL = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eEdD][-+]?\d+)?")

#: Node ids per hexahedron in face.elem (wedges repeat ids, e.g. "a b c c d e f f").
HEX_NODES = 8


class MeshFormatError(ValueError):
    """A source mesh file that cannot be read or holds impossible values; names the file."""

    def __init__(self, path, reason):
        self.path = Path(path)
        super().__init__(f"{self.path}: {reason}")


def _read_text(path):
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8", errors="strict")
    except FileNotFoundError:
        raise MeshFormatError(path, "file not found") from None
    except (UnicodeDecodeError, OSError) as exc:
        raise MeshFormatError(path, f"cannot be read as text ({exc.__class__.__name__})") from None


def _check_points(path, points):
    if len(points) == 0:
        raise MeshFormatError(path, "no vertices")
    if not np.all(np.isfinite(points)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(points), axis=1))[0])
        raise MeshFormatError(path, f"vertex {bad + 1} is not finite (NaN or infinity)")


def read_obj(path):
    """Read a triangle or polygon mesh from a Wavefront OBJ file.

    Polygons are fan-triangulated. Texture and normal indices (``f 1/2/3``) are ignored; negative
    (relative) indices are resolved.

    Returns ``(vertices, faces)``: (n, 3) float64 and (m, 3) int64, zero-based.
    Raises ``MeshFormatError`` for unparseable lines, non-finite vertices, no faces or
    out-of-range indices.
    """
    text = _read_text(path)
    vertices: list[list[float]] = []
    faces: list[list[int]] = []
    for line_no, line in enumerate(text.splitlines(), start=1):
        fields = line.split()
        if not fields or fields[0] not in ("v", "f"):
            continue
        try:
            if fields[0] == "v":
                if len(fields) < 4:
                    raise ValueError("a vertex needs three coordinates")
                vertices.append([float(x) for x in fields[1:4]])
            else:
                ids = [int(token.split("/")[0]) for token in fields[1:]]
                if len(ids) < 3:
                    raise ValueError("a face needs at least three vertices")
                count = len(vertices)
                ids = [i - 1 if i > 0 else count + i for i in ids]
                faces.extend([ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1))
        except ValueError as exc:
            raise MeshFormatError(path, f"line {line_no}: cannot parse {line.strip()[:60]!r} "
                                        f"({exc})") from None
    points = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    _check_points(path, points)
    triangles = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    if len(triangles) == 0:
        raise MeshFormatError(path, "no faces")
    if triangles.min() < 0 or triangles.max() >= len(points):
        raise MeshFormatError(path, f"a face index is outside 1..{len(points)}")
    return points, triangles


def read_face_nodes(path):
    """Read the nodes of the Badin face mesh (``face.node``: index then x y z per line, metres).

    Returns ``(ids, points)``: (n,) int64 node ids as written in the file, and (n, 3) float64.
    """
    text = _read_text(path)
    id_list: list[int] = []
    point_list: list[list[float]] = []
    for line_no, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        numbers = _REAL.findall(line.replace("D", "E").replace("d", "e"))
        if len(numbers) != 4 or not re.fullmatch(r"[-+]?\d+", numbers[0]):
            raise MeshFormatError(path, f"line {line_no}: expected 'index x y z', got "
                                        f"{line.strip()[:60]!r}")
        id_list.append(int(numbers[0]))
        point_list.append([float(x) for x in numbers[1:]])
    points = np.asarray(point_list, dtype=np.float64).reshape(-1, 3)
    _check_points(path, points)
    ids = np.asarray(id_list, dtype=np.int64)
    if len(np.unique(ids)) != len(ids):
        raise MeshFormatError(path, "node ids are not unique")
    return ids, points


def read_face_elems(path, node_ids=None):
    """Read the hexahedra of the Badin face mesh (``face.elem``: 8 node ids, then flags).

    node_ids : optional (n,) int array of the valid node ids (from ``read_face_nodes``); when
    given, every element is checked against it.
    Returns (m, 8) int64 node ids in the file's order (the flags are dropped).
    """
    text = _read_text(path)
    rows: list[list[int]] = []
    for line_no, line in enumerate(text.splitlines(), start=1):
        fields = line.split()
        if not fields:
            continue
        try:
            rows.append([int(x) for x in fields[:HEX_NODES]])
        except ValueError:
            raise MeshFormatError(path, f"line {line_no}: node ids must be integers") from None
        if len(rows[-1]) != HEX_NODES:
            raise MeshFormatError(path, f"line {line_no}: expected {HEX_NODES} node ids")
    elems = np.asarray(rows, dtype=np.int64).reshape(-1, HEX_NODES)
    if len(elems) == 0:
        raise MeshFormatError(path, "no elements")
    if node_ids is not None:
        unknown = ~np.isin(elems, np.asarray(node_ids))
        if unknown.any():
            row = int(np.flatnonzero(unknown.any(axis=1))[0])
            raise MeshFormatError(path, f"element {row + 1} refers to a node id not in face.node")
    return elems
