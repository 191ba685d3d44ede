"""The reference data the anatomy build reads, checked before anything is built.

Every file is validated on reading (``geometry.meshio``); this module adds the checks that need
to know what a file is: that the data directory holds every expected file, that each mesh is
in the units its source uses (Badin: metres, except the velum poses; CBCT: millimetres), and that
no vocal tract or neck mesh has lost the end of its face list.
"""

from pathlib import Path

import numpy as np

from glasshead.constants import BADIN_TO_PROJECT_AXES, M_TO_MM
from glasshead.geometry.frame import badin_to_project, fix_winding
from glasshead.geometry.meshio import MeshFormatError, read_obj

BADIN = Path("anatomy") / "artisynth-badin"
CBCT = Path("anatomy") / "artisynth-dynjaw"
TRACT = Path("anatomy") / "artisynth-badin-tract"
#: Peterson & Barney's (1952) vowel measurements: the norms of the listening displays.
PETERSON_BARNEY = Path("speech") / "peterson-barney-1952" / "pb1952.csv"

#: Badin OBJ file stem -> project mesh name and role.
BADIN_MESHES = {
    "maxilla": ("maxilla", "bone"),
    "jaw": ("mandible", "bone"),
    "tongue": ("tongue_rest", "tongue"),
    "upperlip": ("upper_lip", "lip"),
    "lowerlip": ("lower_lip", "lip"),
    "cranium": ("cranium", "bone"),
}

#: Badin vocal tract OBJ file stem -> project mesh name, role and the unit the file is in (the
#: velum poses are in millimetres, the other files in metres; all in Badin's axes).
TRACT_MESHES = {
    "airway": ("airway", "air", "m"),
    "palate": ("palate", "soft", "m"),
    "pharynx": ("pharynx", "soft", "m"),
    "hyoid": ("hyoid", "bone", "m"),
    "velum_raised": ("velum_raised", "soft", "mm"),
    "velum_rest": ("velum_rest", "soft", "mm"),
    "velum_lowered": ("velum_lowered", "soft", "mm"),
}

#: The velum's poses from closed (raised) to open (lowered): one mesh, one topology.
VELUM_POSES = ("velum_raised", "velum_rest", "velum_lowered")

#: CBCT subject's larynx and neck (mm, the CBCT's own axes): OBJ stem -> project name and role.
CBCT_NECK_MESHES = {
    "thyroid": ("thyroid", "cartilage"),
    "cricoid": ("cricoid", "cartilage"),
    "ltarytenoid": ("arytenoid_left", "cartilage"),
    "rtarytenoid": ("arytenoid_right", "cartilage"),
    "hyoid": ("hyoid_cbct", "bone"),
    "vertebrae": ("vertebrae", "bone"),
}

#: The Amira transform written for the vertebrae mesh (see ``read_amira_transform``).
VERTEBRAE_TRANSFORM = CBCT / "vertebrae.transform"

EXPECTED_FILES = [
    *(BADIN / f"{stem}.obj" for stem in BADIN_MESHES),
    BADIN / "face.node",
    BADIN / "face.elem",
    BADIN / "face_jaw_attachments.txt",
    CBCT / "maxilla.obj",
    *(TRACT / f"{stem}.obj" for stem in TRACT_MESHES),
    *(CBCT / f"{stem}.obj" for stem in CBCT_NECK_MESHES),
    VERTEBRAE_TRANSFORM,
    PETERSON_BARNEY,
]

#: Plausible largest extent of one head part, per unit: metres for Badin, mm for the CBCT.
#: A file outside its range is in the wrong units (or is not a head part at all).
EXTENT_RANGE = {"m": (0.005, 0.5), "mm": (5.0, 500.0)}

#: Largest fraction of a mesh's vertices that no face may use. A face list cut short (a truncated
#: file) leaves the vertices that only its lost faces used; the sources have at most 1 in 1,258.
UNUSED_VERTEX_FRACTION = 0.002


class DataDirError(RuntimeError):
    """The reference data directory is missing or incomplete."""


def check_data_dir(data_dir):
    """Raise ``DataDirError`` naming the expected path and files when anything is missing."""
    data_dir = Path(data_dir)
    listing = "\n".join(f"  {path}" for path in EXPECTED_FILES)
    if not data_dir.is_dir():
        raise DataDirError(
            f"reference data not found: expected the directory {data_dir} "
            f"(set GLASSHEAD_DATA_DIR to its location), holding:\n{listing}"
        )
    missing = [path for path in EXPECTED_FILES if not (data_dir / path).is_file()]
    if missing:
        raise DataDirError(
            f"reference data in {data_dir} is incomplete; missing:\n"
            + "\n".join(f"  {data_dir / path}" for path in missing)
        )


def check_units(path, vertices, unit):
    """Raise ``MeshFormatError`` when the mesh's largest extent is implausible in ``unit``."""
    extent = float(np.ptp(vertices, axis=0).max())
    low, high = EXTENT_RANGE[unit]
    if not low <= extent <= high:
        raise MeshFormatError(
            path, f"largest extent {extent:g} is not plausible for a head part in {unit} "
                  f"(expected {low:g} to {high:g}); wrong units?")


def read_badin_mesh(data_dir, stem):
    """A Badin OBJ in the project frame: (vertices (n, 3) float64 mm, faces (m, 3) int64)."""
    path = Path(data_dir) / BADIN / f"{stem}.obj"
    vertices, faces = read_obj(path)
    check_units(path, vertices, "m")
    return badin_to_project(vertices), fix_winding(faces, BADIN_TO_PROJECT_AXES)


def read_cbct_maxilla(data_dir):
    """The CBCT maxilla in its own axes: (vertices (n, 3) float64 mm, faces (m, 3) int64)."""
    path = Path(data_dir) / CBCT / "maxilla.obj"
    vertices, faces = read_obj(path)
    check_units(path, vertices, "mm")
    return vertices, faces


def check_faces_use_vertices(path, vertices, faces):
    """Raise ``MeshFormatError`` when more than ``UNUSED_VERTEX_FRACTION`` of the vertices (and
    more than one) belong to no face: the file has lost the end of its face list.

    vertices (n, 3) float; faces (m, 3) int, zero-based and in range (``read_obj`` checks that).
    """
    used = np.zeros(len(vertices), dtype=bool)
    used[np.asarray(faces).ravel()] = True
    unused = int(len(vertices) - used.sum())
    if unused > max(1, UNUSED_VERTEX_FRACTION * len(vertices)):
        raise MeshFormatError(
            path, f"{unused} of {len(vertices)} vertices belong to no face; is the file cut "
                  f"short?")


def read_tract_mesh(data_dir, stem):
    """A Badin vocal tract OBJ (``TRACT_MESHES``) in the project frame.

    Returns (vertices (n, 3) float64 mm, faces (m, 3) int64 wound for the project frame).
    """
    path = Path(data_dir) / TRACT / f"{stem}.obj"
    vertices, faces = read_obj(path)
    unit = TRACT_MESHES[stem][2]
    check_units(path, vertices, unit)
    check_faces_use_vertices(path, vertices, faces)
    metres = vertices / M_TO_MM if unit == "mm" else vertices
    return badin_to_project(metres), fix_winding(faces, BADIN_TO_PROJECT_AXES)


def read_cbct_mesh(data_dir, stem):
    """A CBCT neck OBJ (``CBCT_NECK_MESHES``) in its own axes: (vertices (n, 3) float64 mm,
    faces (m, 3) int64)."""
    path = Path(data_dir) / CBCT / f"{stem}.obj"
    vertices, faces = read_obj(path)
    check_units(path, vertices, "mm")
    check_faces_use_vertices(path, vertices, faces)
    return vertices, faces


def read_amira_transform(path):
    """The 4 x 4 matrix of an Amira ``setTransform`` file, as (4, 4) float64 acting on column
    vectors (p' = M @ [p, 1]).

    Amira writes the 16 numbers column by column (ArtiSynth's JawModel transposes them after
    reading), so the last four are the translation and the last row must read 0 0 0 1; read row
    by row, the translation would land in the last row instead. The translation is in Amira's
    units, centimetres (see ``pipeline.larynx``).
    """
    path = Path(path)
    try:
        fields = path.read_text(encoding="utf-8").split()
    except FileNotFoundError:
        raise MeshFormatError(path, "file not found") from None
    except (UnicodeDecodeError, OSError) as exc:
        raise MeshFormatError(path, f"cannot be read as text ({exc.__class__.__name__})") from None
    if not fields or fields[0] != "setTransform":
        raise MeshFormatError(path, "expected 'setTransform' followed by 16 numbers")
    try:
        numbers = np.array([float(x) for x in fields[1:]], dtype=np.float64)
    except ValueError:
        raise MeshFormatError(path, "the matrix holds something that is not a number") from None
    if numbers.shape != (16,) or not np.all(np.isfinite(numbers)):
        raise MeshFormatError(path, f"expected 16 finite numbers, got {len(numbers)}")
    matrix = numbers.reshape(4, 4).T  # column-major
    if not np.allclose(matrix[3], [0.0, 0.0, 0.0, 1.0], atol=1e-9):
        raise MeshFormatError(path, f"last row {matrix[3].tolist()} is not 0 0 0 1: not an "
                                    f"affine transform written column by column")
    return matrix


def input_files(data_dir):
    """Every data file the build reads, as absolute paths in a stable order."""
    return [Path(data_dir) / path for path in EXPECTED_FILES]
