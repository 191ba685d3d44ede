"""Build step: the EPG electrode layouts on the scene maxilla, written to ``epg-layout.json``.

The placement rule is in ``glasshead.epg.layout``. The file holds every grid (the Reading
62-electrode palate and the dense 96-electrode grid), so the browser and the API read one file.
The step is skipped when the file was built from the same maxilla by the same builder version.

The API reads the file through the asset store (``glasshead.asset_store``).
"""

import hashlib
import json
from pathlib import Path

import numpy as np

from glasshead.constants import EPG_LAYOUT_FILE, EPG_LAYOUT_FORMAT_VERSION
from glasshead.epg.layout import LayoutError, layout_document, validate_layout_document
from glasshead.pipeline.collision_tables import load_scene_maxilla
from glasshead.pipeline.outputs import current_output

LAYOUT_FILE = EPG_LAYOUT_FILE
#: Bumped whenever the placement changes for the same maxilla, so stale layouts rebuild.
BUILDER_VERSION = 1


class LayoutFileError(ValueError):
    """An electrode layout file that is missing, unreadable or of another format version."""


def _digest(vertices, faces):
    return hashlib.sha256(np.ascontiguousarray(vertices).tobytes()
                          + np.ascontiguousarray(faces).tobytes()).hexdigest()


def build_epg_layout(maxilla_vertices, maxilla_faces, out_dir, source=None):
    """Place every grid on the maxilla (vertices (n, 3) float mm, faces (m, 3) int, project
    frame) and write ``out_dir/epg-layout.json``. Returns the document."""
    document = layout_document(maxilla_vertices, maxilla_faces, source=source)
    document["builder"] = BUILDER_VERSION
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    (out / LAYOUT_FILE).write_text(json.dumps(document, indent=1) + "\n")
    return document


def build_step(assets_dir):
    """The `glasshead build` step: the layout of the scene maxilla, skipped when up to date.

    Returns {"step": "epg-layout", "file", "skipped", "electrodes": {grid: count}}.
    """
    v, f = load_scene_maxilla(assets_dir)
    out = Path(assets_dir) / LAYOUT_FILE
    digest = _digest(v, f)
    existing = current_output(out, digest, BUILDER_VERSION, EPG_LAYOUT_FORMAT_VERSION)
    if existing is not None:
        return _report(out, existing, skipped=True)
    document = build_epg_layout(v, f, assets_dir, source={"mesh": "maxilla (scene)"})
    return _report(out, document, skipped=False)


def _report(path, document, skipped):
    return {"step": "epg-layout", "file": str(path), "skipped": skipped,
            "electrodes": {name: len(grid["electrodes"])
                           for name, grid in document.get("grids", {}).items()}}


def read_layout(path):
    """Read and check a layout file; LayoutFileError naming the file if it is not one."""
    path = Path(path)
    try:
        return validate_layout_document(json.loads(path.read_text()))
    except FileNotFoundError:
        raise LayoutFileError(f"{path} is missing: run `glasshead build`") from None
    except (OSError, json.JSONDecodeError, LayoutError) as exc:
        raise LayoutFileError(f"{path}: not an electrode layout ({exc})") from None
