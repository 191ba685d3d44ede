"""The reference data the anatomy build reads, checked before anything is built.

Every file is validated on reading (``geometry.meshio``); this module adds the checks that need
to know what a file is: that the data directory holds every expected file, and that each mesh is
in the units its source uses (Badin: metres; CBCT: millimetres).
"""

from pathlib import Path

import numpy as np

from glasshead.constants import BADIN_TO_PROJECT_AXES
from glasshead.geometry.frame import badin_to_project, fix_winding
from glasshead.geometry.meshio import MeshFormatError, read_obj

BADIN = Path("anatomy") / "artisynth-badin"
CBCT = Path("anatomy") / "artisynth-dynjaw"

#: Badin OBJ file stem -> project mesh name and role.
BADIN_MESHES = {
    "maxilla": ("maxilla", "bone"),
    "jaw": ("mandible", "bone"),
    "tongue": ("tongue_rest", "tongue"),
    "upperlip": ("upper_lip", "lip"),
    "lowerlip": ("lower_lip", "lip"),
    "cranium": ("cranium", "bone"),
}

EXPECTED_FILES = [
    *(BADIN / f"{stem}.obj" for stem in BADIN_MESHES),
    BADIN / "face.node",
    BADIN / "face.elem",
    BADIN / "face_jaw_attachments.txt",
    CBCT / "maxilla.obj",
]

#: Plausible largest extent of one head part, per unit: metres for Badin, mm for the CBCT.
#: A file outside its range is in the wrong units (or is not a head part at all).
EXTENT_RANGE = {"m": (0.005, 0.5), "mm": (5.0, 500.0)}


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


def input_files(data_dir):
    """Every data file the build reads, as absolute paths in a stable order."""
    return [Path(data_dir) / path for path in EXPECTED_FILES]
