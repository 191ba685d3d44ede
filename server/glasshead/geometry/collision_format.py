"""The collision tables file: one little-endian binary with a JSON header inside.

Layout (all offsets in bytes):

    0   8 bytes   magic b"GHCOLTAB"
    8   uint32    format version (also in the JSON header; read first, so that a file of another
                  version is refused before anything else in it is interpreted)
    12  uint32    length L of the JSON header (UTF-8, padded with spaces to a multiple of 8)
    16  L bytes   JSON header
    16 + L        payload: the arrays, each starting on an 8-byte boundary

The header gives ``format``, ``format_version``, ``byte_order``, ``frame``, ``origin`` (O, mm),
``floor_y``, ``liner`` (grid), ``voxels`` (shape, bounds), the class and kind codes, and for every
array its ``dtype``, ``shape``, ``offset`` (from the payload start) and ``nbytes``;
``payload_bytes`` and ``payload_crc32`` (zlib CRC-32) guard against truncation and corruption.
A reader refuses a file whose magic, version, sizes, checksum or array shapes are not exactly
what it expects; it never guesses.
"""

import json
import zlib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from glasshead.constants import (
    COLLISION_TABLES_ARRAYS,
    COLLISION_TABLES_FORMAT_VERSION,
    COLLISION_TABLES_MAGIC,
)

FORMAT_NAME = "glasshead-collision-tables"
PREFIX_BYTES = 16
ALIGN = 8

#: Array name -> dtype, in payload order (declared once, in constants.py, for both readers).
ARRAY_DTYPES = COLLISION_TABLES_ARRAYS


class CollisionTablesError(ValueError):
    """Collision tables that cannot be read as this version of the format; says why."""


@dataclass
class CollisionTables:
    """Collision tables read from a file: ``header`` (dict) and ``arrays`` (name -> ndarray)."""

    header: dict[str, Any]
    arrays: dict[str, np.ndarray]

    def __getitem__(self, name: str) -> np.ndarray:
        return self.arrays[name]


def _pad(n: int) -> int:
    return (-n) % ALIGN


def encode_collision_tables(header: Mapping[str, Any],
                            arrays: Mapping[str, np.ndarray]) -> bytes:
    """Serialise ``header`` (dict without array entries) and ``arrays`` into the file's bytes."""
    missing = set(ARRAY_DTYPES) - set(arrays)
    if missing:
        raise ValueError(f"missing arrays: {sorted(missing)}")
    entries, chunks, offset = {}, [], 0
    for name, dtype in ARRAY_DTYPES.items():
        data = np.ascontiguousarray(arrays[name], dtype=np.dtype(dtype))
        raw = data.tobytes()
        entries[name] = {"dtype": dtype, "shape": list(data.shape), "offset": offset,
                         "nbytes": len(raw)}
        chunks.append(raw + b"\0" * _pad(len(raw)))
        offset += len(raw) + _pad(len(raw))
    payload = b"".join(chunks)
    full = dict(header, format=FORMAT_NAME, format_version=COLLISION_TABLES_FORMAT_VERSION,
                byte_order="little", arrays=entries, payload_bytes=len(payload),
                payload_crc32=zlib.crc32(payload))
    text = json.dumps(full, separators=(",", ":"), allow_nan=False).encode("utf-8")
    text += b" " * _pad(len(text))
    prefix = (COLLISION_TABLES_MAGIC + np.array([COLLISION_TABLES_FORMAT_VERSION, len(text)],
                                                dtype="<u4").tobytes())
    return prefix + text + payload


def decode_collision_header(data: bytes | bytearray | memoryview) -> dict[str, Any]:
    """The JSON header of a tables file, after checking the magic and the format version."""
    data = memoryview(data)
    if len(data) < PREFIX_BYTES or bytes(data[:8]) != COLLISION_TABLES_MAGIC:
        raise CollisionTablesError("not a Glasshead collision tables file (bad magic bytes)")
    version, length = (int(x) for x in np.frombuffer(bytes(data[8:16]), dtype="<u4"))
    if version != COLLISION_TABLES_FORMAT_VERSION:
        raise CollisionTablesError(
            f"collision tables format version {version} is not supported (this reader "
            f"understands version {COLLISION_TABLES_FORMAT_VERSION}); rebuild them with "
            "`glasshead build`")
    if PREFIX_BYTES + length > len(data):
        raise CollisionTablesError("collision tables file is truncated inside its header")
    try:
        header = json.loads(bytes(data[PREFIX_BYTES:PREFIX_BYTES + length]).decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise CollisionTablesError(f"collision tables header is not valid JSON ({exc})") from None
    if header.get("format") != FORMAT_NAME or header.get("format_version") != version:
        raise CollisionTablesError("collision tables header does not match its binary prefix")
    if header.get("byte_order") != "little":
        raise CollisionTablesError("collision tables must be little-endian")
    header["_payload_start"] = PREFIX_BYTES + length
    return header


def decode_collision_tables(data: bytes | bytearray | memoryview) -> CollisionTables:
    """Parse and check a whole tables file. data : bytes. Returns ``CollisionTables``."""
    data = bytes(data)
    header = decode_collision_header(data)
    start = header.pop("_payload_start")
    payload = data[start:]
    if len(payload) != header.get("payload_bytes"):
        raise CollisionTablesError(
            f"collision tables payload is {len(payload)} bytes, header says "
            f"{header.get('payload_bytes')} (truncated or padded file)")
    if zlib.crc32(payload) != header.get("payload_crc32"):
        raise CollisionTablesError("collision tables payload fails its CRC-32 check (corrupt)")
    arrays = {}
    entries = header.get("arrays", {})
    for name, dtype in ARRAY_DTYPES.items():
        entry = entries.get(name)
        if entry is None:
            raise CollisionTablesError(f"collision tables lack the array {name!r}")
        if entry.get("dtype") != dtype:
            raise CollisionTablesError(f"array {name!r} has dtype {entry.get('dtype')}, "
                                       f"expected {dtype}")
        shape = tuple(int(s) for s in entry["shape"])
        nbytes = int(np.prod(shape)) * np.dtype(dtype).itemsize
        offset = int(entry["offset"])
        if nbytes != entry["nbytes"] or offset % ALIGN or offset + nbytes > len(payload):
            raise CollisionTablesError(f"array {name!r} does not fit its declared shape/offset")
        arrays[name] = np.frombuffer(payload, dtype=dtype, count=int(np.prod(shape)),
                                     offset=offset).reshape(shape)
    _check_consistency(header, arrays)
    return CollisionTables(header=header, arrays=arrays)


def _check_consistency(header: dict[str, Any], arrays: dict[str, np.ndarray]) -> None:
    liner, vox = header["liner"], header["voxels"]
    nlat, nlon = int(liner["nlat"]), int(liner["nlon"])
    m = len(arrays["triangles"])
    expected = {
        "node_radius": (nlat + 1, nlon + 1), "cell_kind": (nlat, nlon), "cell_rmin": (nlat, nlon),
        "cell_rmax": (nlat, nlon), "cell_offsets": (nlat * nlon + 1,), "triangles": (m, 9),
        "planes": (m, 4), "voxels": tuple(vox["shape"]),
    }
    for name, shape in expected.items():
        if arrays[name].shape != shape:
            raise CollisionTablesError(f"array {name!r} has shape {arrays[name].shape}, "
                                       f"expected {shape}")
    offsets = arrays["cell_offsets"]
    if offsets[0] != 0 or offsets[-1] != len(arrays["cell_triangles"]) or np.any(
            np.diff(offsets.astype(np.int64)) < 0):
        raise CollisionTablesError("cell_offsets are not a valid index into cell_triangles")
    if len(arrays["cell_triangles"]) and arrays["cell_triangles"].max() >= m:
        raise CollisionTablesError("cell_triangles refers to a triangle that does not exist")
    if arrays["cell_kind"].max(initial=0) > 2 or arrays["voxels"].max(initial=0) > 2:
        raise CollisionTablesError("unknown cell kind or voxel class code")
