"""Where the generators get their inputs: the reference data and the built assets.

Every function fails with ``MissingSourceError`` saying what is missing and what to do, never
with a bare traceback from deep inside a reader. ``built_assets()`` runs ``glasshead build`` once
per process (instant when the assets are up to date), so the generators read fresh assets.
"""

import json
from functools import lru_cache
from pathlib import Path

from glasshead.constants import BADIN_TO_PROJECT_AXES, FACE_RIG_FILE, TONGUE_RIG_FILE
from glasshead.geometry.frame import badin_to_project, fix_winding
from glasshead.geometry.meshio import read_obj
from glasshead.settings import get_settings

BADIN = Path("anatomy") / "artisynth-badin"
EMUR_FILE = Path("epg") / "emur-engassim.json"


class MissingSourceError(RuntimeError):
    """Reference data or a built asset that a vector file needs is missing or unreadable."""


def data_dir() -> Path:
    """The reference data directory (GLASSHEAD_DATA_DIR, by default ../shared/data)."""
    path = Path(get_settings().data_dir)
    if not path.is_dir():
        raise MissingSourceError(f"reference data not found: expected the directory {path} "
                                 "(set GLASSHEAD_DATA_DIR to the shared data directory)")
    return path


def data_file(relative) -> Path:
    path = data_dir() / relative
    if not path.is_file():
        raise MissingSourceError(f"reference data file missing: {path} (set GLASSHEAD_DATA_DIR "
                                 "to a complete copy of the shared data)")
    return path


def emur_path() -> Path:
    """The emuR engassim EPG recordings (JSON) in the reference data."""
    return data_file(EMUR_FILE)


def badin_mesh(name):
    """(vertices (n, 3) float64, faces (m, 3) int64) of a Badin mesh, in the project frame."""
    v, f = read_obj(data_file(BADIN / f"{name}.obj"))
    return badin_to_project(v), fix_winding(f, BADIN_TO_PROJECT_AXES)


@lru_cache(maxsize=1)
def built_assets() -> Path:
    """The assets directory after ``glasshead build`` (run here, once, if anything is stale)."""
    from glasshead.pipeline.build import run
    from glasshead.pipeline.sources import DataDirError

    settings = get_settings()
    try:
        run(data_dir(), settings.assets_dir, log=lambda message: print(f"    build: {message}"))
    except DataDirError as exc:
        raise MissingSourceError(str(exc)) from None
    return Path(settings.assets_dir)


def built_json(name):
    """A JSON asset that ``glasshead build`` writes, parsed."""
    path = built_assets() / name
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise MissingSourceError(f"built asset {path} is missing or unreadable ({exc}); run "
                            "`glasshead build --force`") from None


def tongue_rig_definition() -> dict:
    """The built tongue rig definition, checked."""
    from glasshead.geometry.tongue_rig import validate_definition

    definition = built_json(TONGUE_RIG_FILE)
    validate_definition(definition)
    return definition


def face_rig_definition() -> dict:
    """The built face rig definition, checked, without its inputs hash (a build detail)."""
    from glasshead.geometry.face import validate_face_rig

    rig = validate_face_rig(built_json(FACE_RIG_FILE))
    return {k: v for k, v in rig.items() if k != "inputs_sha256"}


def scene_meshes(names):
    """Rest vertices of built scene meshes: dict name -> (n, 3) float64 (the GLBs' float32)."""
    from glasshead.pipeline.face_rig_sources import read_scene_meshes

    assets = built_assets()
    try:
        meshes = read_scene_meshes(assets)
    except ValueError as exc:
        raise MissingSourceError(f"{exc}; run `glasshead build --force`") from None
    if not meshes:
        raise MissingSourceError(f"no build manifest in {assets}; run `glasshead build`")
    return {name: meshes[name][0][0] for name in names}
