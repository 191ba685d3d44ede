"""What the build steps share about their own output files."""

import json
from pathlib import Path


def write_json(path, document):
    """Write JSON atomically (temporary file, then rename)."""
    path = Path(path)
    temporary = path.with_name(path.name + ".tmp")
    temporary.write_text(json.dumps(document, indent=1))
    temporary.replace(path)


def read_json(path):
    """The JSON object at ``path``, or {} when it is missing, unreadable or not an object."""
    try:
        document = json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError):
        return {}
    return document if isinstance(document, dict) else {}


def current_output(path, digest, builder, format_version):
    """The JSON document at ``path`` when it was built from inputs with sha256 ``digest`` by this
    ``builder`` version in this ``format_version``, so the step can skip itself; else None (also
    when the file is missing or unreadable)."""
    existing = read_json(path)
    source = existing.get("source")
    if isinstance(source, dict) and source.get("sha256") == digest \
            and existing.get("builder") == builder \
            and existing.get("format_version") == format_version:
        return existing
    return None


def load_built_meshes(assets_dir, names, scene_only=False):
    """The built GLBs of the meshes ``names``, as the manifest in ``assets_dir`` lists them:
    {name: (vertices (n, 3) float64, faces (m, 3) int64, sha256)}, in the GLBs' vertex order (the
    order the web app sees). Only ``scene: true`` entries count when ``scene_only``.
    FileNotFoundError without a manifest; ValueError naming a mesh it lacks or whose file is
    missing."""
    import numpy as np
    import trimesh

    from glasshead.constants import MANIFEST_FILE

    path = Path(assets_dir) / MANIFEST_FILE
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing: build the anatomy first")
    entries = {m["name"]: m for m in json.loads(path.read_text()).get("meshes", [])
               if not scene_only or m.get("scene", True)}
    meshes = {}
    for name in names:
        if name not in entries:
            kind = "scene mesh" if scene_only else "mesh"
            raise ValueError(f"{path} lists no {kind} {name!r}: build the anatomy first")
        file = Path(assets_dir) / entries[name]["file"]
        if not file.is_file():
            raise ValueError(f"{file} (mesh {name!r} of {path}) is missing")
        mesh = trimesh.load(file, force="mesh", process=False)  # process=False keeps the order
        if not isinstance(mesh, trimesh.Trimesh):
            raise ValueError(f"{file} (mesh {name!r} of {path}) holds no triangle mesh")
        meshes[name] = (np.asarray(mesh.vertices, dtype=np.float64),
                        np.asarray(mesh.faces, dtype=np.int64), entries[name].get("sha256"))
    return meshes
