"""GET /anatomy: the meshes that `glasshead build` wrote, from its manifest."""

import json

from fastapi import APIRouter, HTTPException
from pydantic import BaseModel

from glasshead.settings import get_settings

router = APIRouter(tags=["anatomy"])


class MeshEntry(BaseModel):
    name: str
    url: str
    triangles: int
    vertices: int
    lod: str
    frame: str
    scene: bool
    role: str
    sha256: str


class Anatomy(BaseModel):
    format_version: int
    frame: dict
    meshes: list[MeshEntry]


def read_manifest() -> dict:
    """The build manifest; 503 with a hint when the assets have not been built."""
    path = get_settings().assets_dir / "manifest.json"
    if not path.is_file():
        raise HTTPException(status_code=503,
                            detail=f"anatomy not built: {path} is missing; run `glasshead build`")
    return json.loads(path.read_text())


@router.get("/anatomy", operation_id="getAnatomy", response_model=Anatomy)
def anatomy() -> Anatomy:
    manifest = read_manifest()
    meshes = [
        MeshEntry(
            name=m["name"],
            url=f"/assets/build/{m['file']}?v={m['sha256'][:16]}",
            triangles=m["triangles"],
            vertices=m["vertices"],
            lod=str(m.get("lod", "full")),
            frame=m.get("frame", "project-mm"),
            scene=bool(m.get("scene", True)),
            role=m.get("role", "other"),
            sha256=m["sha256"],
        )
        for m in manifest["meshes"]
    ]
    return Anatomy(format_version=manifest["format_version"], frame=manifest["frame"], meshes=meshes)
