"""A smaller GLB for the same mesh: KHR_mesh_quantization, read natively by three's GLTFLoader.

The meshes of ``/`` are 1.86 MB as trimesh writes them (float32 positions and normals, uint32
indices), 1.14 MB gzipped: floats compress poorly. Quantised, as here, the same meshes are
0.93 MB, 0.72 MB gzipped (measured over the 17 scene meshes of the build):

- positions: uint16 on one lattice shared by every mesh, padded to 8 bytes a vertex as the
  extension requires: the step is ``STEP_MM`` (2^-8 mm, 0.0039 mm) and the node's
  ``translation`` a multiple of it, so no vertex moves by more than half a step along an axis
  (0.00195 mm; ``max_error_mm``), and a point two meshes share (the skin's rim on the head
  shell, the lips' corners) lands on the same lattice point in both, exactly: a power of two
  times an integer below 2^24 is exact in float32 as in float64, so readers that apply the
  node's transform get the same number for it in every file. A mesh wider than 65535 steps
  (256 mm) takes the next power of two that fits it (``lattice_step``): the head shell, whose
  neck makes it 290 mm tall, takes 2^-7 mm, and the meshes that share points with it (the face
  skin, and the lips with the skin) are written on that step too (``min_step_mm``);
- normals: int8, normalized (the extension's form for them), about 0.5 degree;
- indices: uint16 when the mesh has fewer than 65536 vertices (plain glTF), uint32 otherwise.

Khronos, KHR_mesh_quantization (glTF 2.0 extension), the attribute types and the node
transform that restores the positions. Other readers must apply the node's transform: three's
GLTFLoader does, and web/src/scene/gltfGeometry.js bakes ``matrixWorld`` into the geometry
(checked on the airway: positions within 0.0009 mm of the float32 file, normals within 0.8
degree); trimesh does too, so ``asset_store.read_glb_mesh`` and every build step that reads a
built mesh get the quantised positions, the ones the browser draws. The anatomy build writes
every mesh this way (``pipeline/anatomy.py`` ``write_glb``).
"""

import json
import struct

import numpy as np

MAGIC, VERSION = 0x46546C67, 2  # "glTF", version 2
JSON_CHUNK, BIN_CHUNK = 0x4E4F534A, 0x004E4942
UNSIGNED_SHORT, UNSIGNED_INT, BYTE = 5123, 5125, 5120
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
#: Positions become integers 0..GRID_MAX on the lattice.
GRID_MAX = 65535
#: The lattice step, mm: a power of two, so that lattice points are exact in float32.
STEP_MM = 2.0 ** -8


def _pad(data: bytes, fill: bytes) -> bytes:
    return data + fill * (-len(data) % 4)


def lattice_step(vertices, min_step_mm: float = STEP_MM) -> float:
    """The lattice step of a mesh, mm: ``min_step_mm`` (at least ``STEP_MM``), doubled until
    the mesh's extent fits in ``GRID_MAX`` steps."""
    vertices = np.asarray(vertices, dtype=np.float64)
    step = max(STEP_MM, float(min_step_mm))
    while True:
        low = np.floor(vertices.min(axis=0) / step) * step
        if np.rint((vertices - low) / step).max() <= GRID_MAX:
            return step
        step *= 2.0


def quantized_glb(vertices, faces, normals, min_step_mm: float = STEP_MM) -> tuple[bytes, float]:
    """(GLB bytes, largest position error in mm) of one mesh.

    vertices : (n, 3) float, mm
    faces : (m, 3) int, indices into vertices
    normals : (n, 3) float, unit vertex normals
    min_step_mm : the lattice step at the least (a power of two times ``STEP_MM``), for meshes
    that share points with a wider one
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    normals = np.asarray(normals, dtype=np.float64)
    if vertices.ndim != 2 or vertices.shape[1] != 3 or not len(vertices):
        raise ValueError(f"vertices must be (n, 3) with n > 0, not {vertices.shape}")
    if faces.ndim != 2 or faces.shape[1] != 3 or not len(faces):
        raise ValueError(f"faces must be (m, 3) with m > 0, not {faces.shape}")
    if normals.shape != vertices.shape:
        raise ValueError(f"normals must be {vertices.shape}, not {normals.shape}")
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise ValueError("faces index vertices that do not exist")
    step = lattice_step(vertices, min_step_mm)
    low = np.floor(vertices.min(axis=0) / step) * step
    grid = np.rint((vertices - low) / step).astype(np.uint16)
    error = float(np.abs(grid * step + low - vertices).max())
    positions = np.zeros((len(vertices), 4), dtype=np.uint16)
    positions[:, :3] = grid
    packed_normals = np.zeros((len(vertices), 4), dtype=np.int8)
    packed_normals[:, :3] = np.clip(np.rint(normals * 127), -127, 127)
    index_type = UNSIGNED_SHORT if len(vertices) <= 65535 else UNSIGNED_INT
    indices = faces.astype(np.uint16 if index_type == UNSIGNED_SHORT else np.uint32).ravel()

    views, blobs, offset = [], [], 0
    for blob, stride, target in ((positions.tobytes(), 8, ARRAY_BUFFER),
                                 (packed_normals.tobytes(), 4, ARRAY_BUFFER),
                                 (indices.tobytes(), None, ELEMENT_ARRAY_BUFFER)):
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(blob), "target": target}
        if stride:
            view["byteStride"] = stride
        views.append(view)
        blob = _pad(blob, b"\0")
        blobs.append(blob)
        offset += len(blob)
    document = {
        "asset": {"version": "2.0", "generator": "glasshead quantized_glb"},
        "extensionsUsed": ["KHR_mesh_quantization"],
        "extensionsRequired": ["KHR_mesh_quantization"],
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": low.tolist(), "scale": [step] * 3}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2,
                                    "mode": 4}]}],
        "accessors": [
            {"bufferView": 0, "componentType": UNSIGNED_SHORT, "count": len(vertices),
             "type": "VEC3", "min": grid.min(axis=0).tolist(), "max": grid.max(axis=0).tolist()},
            {"bufferView": 1, "componentType": BYTE, "normalized": True,
             "count": len(vertices), "type": "VEC3"},
            {"bufferView": 2, "componentType": index_type, "count": len(indices),
             "type": "SCALAR"},
        ],
        "bufferViews": views,
        "buffers": [{"byteLength": offset}],
    }
    text = _pad(json.dumps(document, separators=(",", ":")).encode(), b" ")
    binary = b"".join(blobs)
    length = 12 + 8 + len(text) + 8 + len(binary)
    glb = (struct.pack("<III", MAGIC, VERSION, length)
           + struct.pack("<II", len(text), JSON_CHUNK) + text
           + struct.pack("<II", len(binary), BIN_CHUNK) + binary)
    return glb, error
