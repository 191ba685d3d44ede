"""GET /collision/tables: the liner and voxel tables. POST /collision/correct: the Python reference.

The tables are one binary file built by `glasshead build` (format in
``glasshead.geometry.collision_format``). GET /collision/tables answers with its JSON header and
the URL of the binary; the browser fetches the binary, checks it and corrects the tongue itself
every frame. POST /collision/correct runs the Python twin of that correction on given vertices.
"""

import hashlib
from functools import lru_cache
from pathlib import Path
from typing import Annotated

from fastapi import APIRouter, HTTPException
from pydantic import BaseModel, Field

from glasshead.constants import COLLISION_MAX_VERTICES, COLLISION_TABLES_FORMAT_VERSION
from glasshead.geometry.collision import correct_vertices
from glasshead.geometry.collision_format import CollisionTablesError, decode_collision_tables
from glasshead.pipeline.collision_tables import TABLES_FILE
from glasshead.settings import get_settings

router = APIRouter(tags=["collision"])

Coordinate = Annotated[float, Field(strict=True, allow_inf_nan=False)]
Vertex = Annotated[list[Coordinate], Field(min_length=3, max_length=3)]


class CorrectRequest(BaseModel):
    vertices: Annotated[list[Vertex], Field(max_length=COLLISION_MAX_VERTICES,
                                            description="Tongue vertices [x, y, z], mm, "
                                                        "project frame.")]


class CollisionCounts(BaseModel):
    screened: int
    tested: int
    corrected: int


class CorrectResponse(BaseModel):
    vertices: list[list[float]] = Field(description="The vertices after correction.")
    flags: list[int] = Field(description="Per vertex: 0 screened by the voxel table, 1 tested "
                                         "against the liner and outside, 2 corrected.")
    counts: CollisionCounts
    format_version: int


class TablesInfo(BaseModel):
    format_version: int
    url: str = Field(description="The binary tables file (JSON header inside).")
    bytes: int
    header: dict


def _tables_path() -> Path:
    path = get_settings().assets_dir / TABLES_FILE
    if not path.is_file():
        raise HTTPException(status_code=503, detail=f"collision tables not built: {path} is "
                                                    "missing; run `glasshead build`")
    return path


@lru_cache(maxsize=2)
def _load(path: str, mtime_ns: int, size: int):
    data = Path(path).read_bytes()
    return decode_collision_tables(data), hashlib.sha256(data).hexdigest(), len(data)


def load_tables():
    """(tables, sha256, bytes) of the current file, parsed once per version of it; 503 when the
    file is missing or unreadable."""
    path = _tables_path()
    stat = path.stat()
    try:
        return _load(str(path), stat.st_mtime_ns, stat.st_size)
    except CollisionTablesError as exc:
        raise HTTPException(status_code=503, detail=f"collision tables unusable: {exc}") from None


@router.get("/collision/tables", operation_id="getCollisionTables", response_model=TablesInfo)
def collision_tables() -> TablesInfo:
    tables, digest, size = load_tables()
    return TablesInfo(format_version=COLLISION_TABLES_FORMAT_VERSION,
                      url=f"/assets/build/{TABLES_FILE}?v={digest[:16]}", bytes=size,
                      header=tables.header)


@router.post("/collision/correct", operation_id="correctCollision",
             response_model=CorrectResponse)
def collision_correct(request: CorrectRequest) -> CorrectResponse:
    tables, _, _ = load_tables()
    if not request.vertices:
        counts = CollisionCounts(screened=0, tested=0, corrected=0)
        return CorrectResponse(vertices=[], flags=[], counts=counts,
                               format_version=COLLISION_TABLES_FORMAT_VERSION)
    corrected, flags, counts = correct_vertices(request.vertices, tables)
    return CorrectResponse(vertices=corrected.tolist(), flags=flags.tolist(),
                           counts=CollisionCounts(**counts),
                           format_version=COLLISION_TABLES_FORMAT_VERSION)
