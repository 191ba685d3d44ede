"""The asset store: everything `glasshead build` writes, loaded once and handed to the routes.

Each built file (manifest, tongue rig, face rig, collision tables, EPG layout; later steps add
theirs to ``ASSETS``) is read, checked and parsed once, at start-up, into one ``AssetStore``.
Routes receive the store as a FastAPI dependency (``glasshead.api.deps.AssetsDep``) and never
read files, fit or build anything themselves.

A file is loaded again when its content hash changes. Looking at a file costs one ``stat`` per
request; its bytes are hashed again when the ``stat`` changes, or at most every ``recheck_s``
seconds otherwise (so a file rewritten with the same size and time is still picked up).

A missing or corrupt file never stops the store: the asset is marked ``missing`` or ``corrupt``
with the reason, ``status()`` reports it (GET /health), and ``get`` raises
``AssetUnavailableError``, which the API turns into a 503 naming the asset and the command that
rebuilds it.
"""

import hashlib
import itertools
import json
import logging
import threading
import time
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from glasshead.constants import (
    COLLISION_TABLES_FILE,
    EPG_LAYOUT_FILE,
    FACE_RIG_FILE,
    FIT_REPORT_FILE,
    FIT_REPORT_FORMAT_VERSION,
    LANDMARKS_FILE,
    LOWER_LIP_GLB,
    MANIFEST_FILE,
    MANIFEST_FORMAT_VERSION,
    PHARYNX_GLB,
    PHONEME_TARGETS_FILE,
    PHONEME_TARGETS_FORMAT_VERSION,
    REBUILD_COMMAND,
    TONGUE_RIG_FILE,
    TRACT_SECTION_FILE,
    TRACT_SECTION_FORMAT_VERSION,
    UPPER_LIP_GLB,
    VELUM_REST_GLB,
    VELUM_RIG_FILE,
    VTL_OBSERVATIONS_FILE,
)
from glasshead.epg.layout import validate_layout_document
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.geometry.face import validate_face_rig
from glasshead.geometry.landmarks import validate_landmarks
from glasshead.geometry.tongue_rig import validate_definition
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.geometry.velum import VelumRig, prepare_velum

log = logging.getLogger("glasshead.assets")

#: Seconds between content checks of a file whose ``stat`` has not changed.
RECHECK_S = 1.0


def _json(data: bytes) -> Any:
    return json.loads(data.decode("utf-8"))


def read_manifest(data: bytes) -> dict:
    """The build manifest: format version, frame and one entry per mesh."""
    manifest = _json(data)
    if not isinstance(manifest, dict):
        raise ValueError("the manifest must be a JSON object")
    version = manifest.get("format_version")
    if version != MANIFEST_FORMAT_VERSION:
        raise ValueError(f"manifest format_version {version!r} is not {MANIFEST_FORMAT_VERSION}")
    meshes = manifest.get("meshes")
    if not isinstance(meshes, list) or not meshes:
        raise ValueError("the manifest lists no meshes")
    for k, mesh in enumerate(meshes):
        missing = [key for key in ("name", "file", "sha256", "triangles", "vertices")
                   if not isinstance(mesh, dict) or key not in mesh]
        if missing:
            raise ValueError(f"manifest mesh {k} lacks {', '.join(missing)}")
    return manifest


def read_tongue_rig(data: bytes) -> TongueRig:
    """The tongue rig, ready to evaluate; its definition is ``.definition``."""
    definition = _json(data)
    validate_definition(definition)
    return TongueRig(definition)


def read_face_rig(data: bytes) -> dict:
    return validate_face_rig(_json(data))


def read_epg_layout(data: bytes) -> dict:
    return validate_layout_document(_json(data))


def read_velum_rig(data: bytes) -> VelumRig:
    """The velum rig, ready to pose; its definition is ``.definition``."""
    return prepare_velum(_json(data))


def read_landmarks(data: bytes) -> dict:
    """The teaching landmarks (parts and places of articulation), checked."""
    return validate_landmarks(_json(data))


#: What every phoneme target holds (glasshead.pipeline.phoneme_targets).
PHONEME_TARGET_KEYS = ("arpabet", "ipa", "kind", "examples", "features", "params", "contexts",
                       "source", "volume_change_pct", "epg")


def _versioned(data: bytes, what: str, format_version: int) -> dict:
    """A JSON object in the given format version (ValueError naming ``what`` otherwise)."""
    document = _json(data)
    if not isinstance(document, dict):
        raise ValueError(f"the {what} must be a JSON object")
    version = document.get("format_version")
    if version != format_version:
        raise ValueError(f"{what} format_version {version!r} is not {format_version}")
    return document


def read_phoneme_targets(data: bytes) -> dict:
    """The phoneme targets: format version, one target per phoneme with its parameters and
    synthetic EPG (8 rows of 0/1, R1 first)."""
    document = _versioned(data, "phoneme targets", PHONEME_TARGETS_FORMAT_VERSION)
    targets = document.get("targets")
    if not isinstance(targets, list) or not targets:
        raise ValueError("the phoneme targets list no targets")
    for k, target in enumerate(targets):
        missing = [key for key in PHONEME_TARGET_KEYS
                   if not isinstance(target, dict) or key not in target]
        if missing:
            raise ValueError(f"phoneme target {k} lacks {', '.join(missing)}")
        rows = target["epg"].get("rows") if isinstance(target["epg"], dict) else None
        if not isinstance(rows, list) or len(rows) != 8 or any(
                not isinstance(r, str) or len(r) != 8 or set(r) - {"0", "1"} for r in rows):
            raise ValueError(f"phoneme target {target['arpabet']}: epg.rows must be 8 strings "
                             "of 8 '0'/'1'")
        if not isinstance(target["params"], dict) or not all(
                isinstance(v, (int, float)) and not isinstance(v, bool)
                for v in target["params"].values()):
            raise ValueError(f"phoneme target {target['arpabet']}: params must map names to "
                             "numbers")
    return document


def _points_of(value, width: int) -> bool:
    # Types are compared exactly (what json.loads makes): bool, a subclass of int, is refused.
    # Mapping ``type`` over the flattened coordinates keeps a start-up that reads 40,000 points
    # at a few milliseconds.
    return isinstance(value, list) \
        and all(type(p) is list and len(p) == width for p in value) \
        and set(map(type, itertools.chain.from_iterable(value))) <= {int, float}


def read_tract_section(data: bytes) -> dict:
    """The tract's still section and stations (glasshead.pipeline.tract_section), checked."""
    document = _versioned(data, "tract section", TRACT_SECTION_FORMAT_VERSION)
    stations = document.get("stations")
    if not isinstance(stations, list) or len(stations) < 2 or any(
            not isinstance(p, list) or len(p) != 2 for p in stations):
        raise ValueError("the tract section needs at least two [x, y] stations")
    for key in ("still", "mandible", "incisor_x", "uvula_y", "nose"):
        if key not in document:
            raise ValueError(f"the tract section lacks {key}")
    return document


def read_vtl_observations(data: bytes) -> dict:
    """VocalTractLab's JD3 shapes (glasshead.pipeline.vtl_observations): each with its name,
    class, tongue outline (n, 2) and tongue surface vertices (n, 3), mm, project frame."""
    document = _json(data)
    if not isinstance(document, dict) or not isinstance(document.get("shapes"), list) \
            or not document["shapes"]:
        raise ValueError("the observations must be a JSON object listing shapes")
    for k, shape in enumerate(document["shapes"]):
        missing = [key for key in ("name", "class", "tongue_outline", "tongue_surface_vertices")
                   if not isinstance(shape, dict) or key not in shape]
        if missing:
            raise ValueError(f"observed shape {k} lacks {', '.join(missing)}")
        if not _points_of(shape["tongue_outline"], 2) \
                or not _points_of(shape["tongue_surface_vertices"], 3):
            raise ValueError(f"observed shape {shape['name']}: the tongue outline must be (n, 2) "
                             "and its surface vertices (n, 3) numbers")
    return document


#: What every shape of the fit report holds (glasshead.pipeline.fit_report); a fitted one also
#: FIT_KEYS.
FIT_REPORT_KEYS = ("name", "label", "source", "rms_mm")
FIT_KEYS = ("max_error_mm", "evaluations", "seconds", "method", "volume_change_pct",
            "at_limit", "start_params", "params", "origin", "outline", "errors", "plot")


def read_fit_report(data: bytes) -> dict:
    """The fit report: format version, and per shape its label, its 2D fit's error and cost,
    the start and fitted parameters, the rays' origin, the compared outline and the errors."""
    document = _json(data)
    if not isinstance(document, dict):
        raise ValueError("the fit report must be a JSON object")
    version = document.get("format_version")
    if version != FIT_REPORT_FORMAT_VERSION:
        raise ValueError(f"fit report format_version {version!r} is not "
                         f"{FIT_REPORT_FORMAT_VERSION}")
    shapes = document.get("shapes")
    if not isinstance(shapes, list) or not shapes:
        raise ValueError("the fit report lists no shapes")
    for k, shape in enumerate(shapes):
        keys = FIT_REPORT_KEYS + (FIT_KEYS if isinstance(shape, dict)
                                  and shape.get("rms_mm") is not None else ())
        missing = [key for key in keys if not isinstance(shape, dict) or key not in shape]
        if missing:
            raise ValueError(f"fit report shape {k} lacks {', '.join(missing)}")
        if shape["rms_mm"] is not None and (
                not _points_of(shape["outline"], 2) or not _points_of([shape["origin"]], 3)
                or len(shape["errors"]) != len(shape["outline"])):
            raise ValueError(f"fit report shape {shape['name']}: the outline must be (m, 2), the "
                             "origin (3,) and the errors one per outline point")
    return document


def read_glb_mesh(data: bytes) -> tuple:
    """(vertices (n, 3) float64, faces (m, 3) int64) of a one-mesh GLB, in its vertex order."""
    import io

    import numpy as np
    import trimesh

    mesh = trimesh.load(io.BytesIO(data), file_type="glb", force="mesh", process=False)
    if not isinstance(mesh, trimesh.Trimesh):
        raise ValueError("the GLB holds no triangle mesh")
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if vertices.ndim != 2 or vertices.shape[1] != 3 or not len(faces):
        raise ValueError("the GLB holds no triangle mesh")
    return vertices, faces


@dataclass(frozen=True)
class AssetSpec:
    """One built file: the name routes ask for, its file under the assets directory, and the
    reader that checks and parses its bytes (raising on anything it does not accept)."""

    name: str
    file: str
    read: Callable[[bytes], Any]


#: Every asset the API serves, in build order.
ASSETS: tuple[AssetSpec, ...] = (
    AssetSpec("manifest", MANIFEST_FILE, read_manifest),
    AssetSpec("tongue_rig", TONGUE_RIG_FILE, read_tongue_rig),
    AssetSpec("collision_tables", COLLISION_TABLES_FILE, decode_collision_tables),
    AssetSpec("epg_layout", EPG_LAYOUT_FILE, read_epg_layout),
    AssetSpec("face_rig", FACE_RIG_FILE, read_face_rig),
    AssetSpec("velum_rig", VELUM_RIG_FILE, read_velum_rig),
    AssetSpec("landmarks", LANDMARKS_FILE, read_landmarks),
    # The tongue's collision with the velum and the pharyngeal wall (geometry.tract_collision).
    AssetSpec("velum_mesh", VELUM_REST_GLB, read_glb_mesh),
    AssetSpec("pharynx_mesh", PHARYNX_GLB, read_glb_mesh),
    # The lips at rest, for the flesh points of an utterance (geometry.flesh_points).
    AssetSpec("upper_lip_mesh", UPPER_LIP_GLB, read_glb_mesh),
    AssetSpec("lower_lip_mesh", LOWER_LIP_GLB, read_glb_mesh),
    AssetSpec("phoneme_targets", PHONEME_TARGETS_FILE, read_phoneme_targets),
    AssetSpec("vtl_observations", VTL_OBSERVATIONS_FILE, read_vtl_observations),
    AssetSpec("fit_report", FIT_REPORT_FILE, read_fit_report),
    AssetSpec("tract_section", TRACT_SECTION_FILE, read_tract_section),
)


class AssetUnavailableError(Exception):
    """An asset that is missing or corrupt; the API answers 503 with ``to_json()``."""

    def __init__(self, name: str, file: str, problem: str, reason: str):
        self.name, self.file, self.problem, self.reason = name, file, problem, reason
        super().__init__(f"asset {name} ({file}) is {problem}: {reason}; "
                         f"run `{REBUILD_COMMAND}` to rebuild it")

    def to_json(self) -> dict:
        return {"detail": str(self), "asset": self.name, "file": self.file,
                "problem": self.problem, "command": REBUILD_COMMAND}


@dataclass
class Asset:
    """One loaded version of a file: the parsed value, its content hash and size, and values
    derived from it (dropped with it when the file changes)."""

    name: str
    value: Any
    sha256: str
    size: int
    derived: dict = field(default_factory=dict)


@dataclass
class _Slot:
    spec: AssetSpec
    loaded: Asset | None = None
    error: AssetUnavailableError | None = None
    failed_sha256: str | None = None
    stat_key: tuple | None = None
    checked_at: float = float("-inf")


class AssetStore:
    """The built assets under ``assets_dir``, each loaded once per content version."""

    def __init__(self, assets_dir, specs: tuple[AssetSpec, ...] = ASSETS,
                 recheck_s: float = RECHECK_S, clock: Callable[[], float] = time.monotonic):
        self.assets_dir = Path(assets_dir)
        self.recheck_s = recheck_s
        self._clock = clock
        self._slots = {spec.name: _Slot(spec) for spec in specs}
        self._lock = threading.Lock()
        #: How many times each asset was parsed (tests read it to see that nothing reloads).
        self.loads: dict[str, int] = dict.fromkeys(self._slots, 0)

    @property
    def names(self) -> list[str]:
        return list(self._slots)

    def load_all(self) -> dict:
        """Load every asset now (at start-up); never raises. Returns ``status()``."""
        with self._lock:
            for slot in self._slots.values():
                self._refresh(slot, force=True)
        report = self.status()
        for name, state in report["assets"].items():
            if state["status"] != "ok":
                log.warning("asset %s: %s", name, state["detail"])
        return report

    def entry(self, name: str) -> Asset:
        """The current version of an asset; AssetUnavailableError when it is missing or corrupt."""
        slot = self._slots.get(name)
        if slot is None:
            raise KeyError(f"no asset named {name!r}; known: {', '.join(self._slots)}")
        with self._lock:
            self._refresh(slot)
            if slot.loaded is None:
                raise slot.error or AssetUnavailableError(name, slot.spec.file, "missing",
                                                          "not loaded")
            return slot.loaded

    def get(self, name: str) -> Any:
        """The parsed value of an asset (see ``ASSETS``)."""
        return self.entry(name).value

    def derived(self, name: str, key: Hashable, make: Callable[[Any], Any]) -> Any:
        """``make(value)`` of an asset, computed once per version of it and per ``key``."""
        asset = self.entry(name)
        with self._lock:
            if key not in asset.derived:
                asset.derived[key] = make(asset.value)
            return asset.derived[key]

    def status(self) -> dict:
        """{"ok": all loaded, "assets": {name: {file, status, sha256 | detail}}}: ``status`` is
        ``ok``, ``missing`` or ``corrupt``."""
        assets = {}
        with self._lock:
            for name, slot in self._slots.items():
                self._refresh(slot)
                if slot.loaded is not None:
                    assets[name] = {"file": slot.spec.file, "status": "ok",
                                    "sha256": slot.loaded.sha256, "bytes": slot.loaded.size}
                else:
                    error = slot.error
                    assets[name] = {"file": slot.spec.file,
                                    "status": error.problem if error else "missing",
                                    "detail": str(error) if error else "not loaded"}
        return {"ok": all(a["status"] == "ok" for a in assets.values()), "assets": assets}

    def _refresh(self, slot: _Slot, force: bool = False) -> None:
        spec = slot.spec
        path = self.assets_dir / spec.file
        try:
            stat = path.stat()
        except FileNotFoundError:
            slot.loaded, slot.stat_key, slot.failed_sha256 = None, None, None
            slot.error = AssetUnavailableError(spec.name, spec.file, "missing",
                                          f"{path} does not exist")
            return
        except OSError as exc:
            self._fail(slot, None, f"cannot read {path}: {exc}")
            return
        key = (stat.st_mtime_ns, stat.st_size, stat.st_ino)
        now = self._clock()
        if not force and key == slot.stat_key and now - slot.checked_at < self.recheck_s:
            return
        slot.stat_key, slot.checked_at = key, now
        try:
            data = path.read_bytes()
        except OSError as exc:
            self._fail(slot, None, f"cannot read {path}: {exc}")
            return
        digest = hashlib.sha256(data).hexdigest()
        if slot.loaded is not None and slot.loaded.sha256 == digest:
            return
        if slot.loaded is None and slot.failed_sha256 == digest:
            return
        try:
            value = spec.read(data)
        except Exception as exc:  # any reader failure means the file cannot be served
            self._fail(slot, digest, f"{path} is not a valid {spec.name} file "
                                     f"({type(exc).__name__}: {exc})")
            return
        slot.loaded = Asset(spec.name, value, digest, len(data))
        slot.error, slot.failed_sha256 = None, None
        self.loads[spec.name] += 1

    @staticmethod
    def _fail(slot: _Slot, digest: str | None, reason: str) -> None:
        slot.loaded, slot.failed_sha256 = None, digest
        slot.error = AssetUnavailableError(slot.spec.name, slot.spec.file, "corrupt", reason)
