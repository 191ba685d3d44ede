"""GET /anatomy: the meshes that `glasshead build` wrote, from its manifest."""

from fastapi import APIRouter
from pydantic import BaseModel

from glasshead.api.deps import AssetsDep

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


@router.get("/anatomy", operation_id="getAnatomy", response_model=Anatomy)
def anatomy(assets: AssetsDep) -> Anatomy:
    manifest = assets.get("manifest")
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
    return Anatomy(format_version=manifest["format_version"], frame=manifest["frame"],
                   meshes=meshes)
