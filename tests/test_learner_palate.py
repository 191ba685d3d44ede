"""A learner's own palate (pipeline.learner_palate): the CBCT subject's maxilla (another person's
palate, ``artisynth-dynjaw``) uploaded as a scan is registered onto the head and rebuilt into
exact collision tables and an electrode layout on which /t/ and /k/ still close their rows; bad
scans get a clear answer and leave the previous palate in place."""

import itertools
import json
import struct

import numpy as np
import pytest
import trimesh

from collision_support import ExactRays, check_exact_correction
from glasshead.constants import COLLISION_TABLES_FILE, COLLISION_TOL, EPG_LAYOUT_FILE
from glasshead.epg.contacts import probes_from_layout
from glasshead.epg.synthetic import synthetic_frame
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.pipeline.learner_palate import (
    MAX_TRIANGLES,
    PALATE_MESH,
    REPORT_FILE,
    ScanError,
    build_learner_palate,
    read_scan,
)

#: The residual on the palate and teeth the issue allows, mm RMS (measured: 1.07 for the STL in
#: metres upside down; 1.24 for the OBJ as stored).
RESIDUAL_RMS_MM = 1.5
#: Random tongue poses checked against the rebuilt tables.
POSES, SEED = 200, 2032


@pytest.fixture(scope="module")
def dynjaw(data_dir):
    path = data_dir / "anatomy" / "artisynth-dynjaw"
    return {"maxilla": (path / "maxilla.obj").read_bytes(), "jaw": (path / "jaw.obj").read_bytes()}


@pytest.fixture(scope="module")
def palate(dynjaw, built_assets, tmp_path_factory):
    """The CBCT maxilla as a scanner might send it: an STL in metres, upside down."""
    mesh = trimesh.load(trimesh.util.wrap_as_stream(dynjaw["maxilla"]), file_type="obj",
                        force="mesh", process=False)
    turned = mesh.vertices @ np.diag([1.0, -1.0, -1.0]) / 1000.0
    scan = trimesh.Trimesh(turned, mesh.faces, process=False).export(file_type="stl")
    out = tmp_path_factory.mktemp("palate") / "child-1"
    steps = []
    report = build_learner_palate(scan, "stl", built_assets, out,
                                  progress=lambda step, share: steps.append((step, share)))
    return {"dir": out, "report": report, "steps": steps}


def test_another_persons_palate_in_metres_upside_down_registers_within_a_millimetre_and_a_half(
        palate):
    assert palate["report"]["scan"]["units"].startswith("m ")
    residual = palate["report"]["registration"]["mouth_facing_residual"]
    assert residual["rms_mm"] <= RESIDUAL_RMS_MM, residual
    shares = [share for _, share in palate["steps"]]
    assert shares == sorted(shares) and shares[0] == 0.0 and shares[-1] == 1.0
    saved = json.loads((palate["dir"] / REPORT_FILE).read_text())
    assert saved["registration"]["mouth_facing_residual"] == residual


def test_the_rebuilt_tables_stay_exact(palate, built_assets):
    from glasshead.asset_store import AssetStore

    tables = decode_collision_tables((palate["dir"] / COLLISION_TABLES_FILE).read_bytes())
    placed = trimesh.load(palate["dir"] / PALATE_MESH, force="mesh", process=False)
    rays = ExactRays(placed.vertices, placed.faces, tables.header["origin"])
    rig = AssetStore(built_assets).get("tongue_rig")
    worst, corrected = check_exact_correction(tables, rays, rig, POSES, SEED)
    assert worst <= COLLISION_TOL.depth
    assert corrected > POSES


def test_the_electrodes_keep_their_rows_and_t_and_k_still_close_theirs(palate, built_store):
    layout = json.loads((palate["dir"] / EPG_LAYOUT_FILE).read_text())
    reading = layout["grids"]["reading62"]
    # Rows run front to back along the midline, as on the head's own palate.
    front_to_back = [row["midline_point"][0] for row in reading["rows_detail"]]
    assert len(reading["electrodes"]) == 62
    assert all(a > b for a, b in itertools.pairwise(front_to_back)), front_to_back
    tables = decode_collision_tables((palate["dir"] / COLLISION_TABLES_FILE).read_bytes())
    probes = probes_from_layout(reading)
    rig = built_store.get("tongue_rig")
    targets = {t["ipa"]: t["params"] for t in built_store.get("phoneme_targets")["targets"]}
    # /t/ closes the front row (its six electrodes), /k/ one of the two back rows across its
    # middle six.
    t = synthetic_frame(rig, rig.values_clipped(targets["t"]), tables, probes).grid
    assert t[0, 1:7].all(), t
    k = synthetic_frame(rig, rig.values_clipped(targets["k"]), tables, probes).grid
    assert k[6:, 1:7].all(axis=1).any(), k
    # Control: the rest tongue, on this other person's palate, touches next to nothing.
    rest = synthetic_frame(rig, rig.values_clipped({}), tables, probes).grid
    assert rest.sum() <= 2 < min(t.sum(), k.sum()), rest


def test_a_lower_jaw_is_refused_and_the_previous_palate_stays(dynjaw, built_assets, palate,
                                                              tmp_path):
    out = tmp_path / "kept"
    out.mkdir()
    (out / "marker").write_text("the previous palate")
    with pytest.raises(ScanError, match="does not fit this head's palate") as refused:
        build_learner_palate(dynjaw["jaw"], "obj", built_assets, out)
    # With a picture to look at: both cuts, and the figure.
    picture = refused.value.picture
    assert 'class="head"' in picture and 'class="scan"' in picture and "mm RMS" in picture
    assert picture.count("<polyline") >= 2
    assert (out / "marker").read_text() == "the previous palate"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kept"], "nothing half-built is kept"


@pytest.mark.parametrize(("data", "kind", "message"), [
    (b"these are notes, not a mesh", "obj", "holds no triangles|not a readable"),
    (b"\0" * 80 + struct.pack("<I", 5_000_000), "stl", f"at most {MAX_TRIANGLES:,}"),
    (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "dwg", "must be STL, PLY, OBJ"),
    (b"v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n", "obj", "flat"),
])
def test_bad_scans_are_refused_with_the_reason(data, kind, message):
    with pytest.raises(ScanError, match=message):
        read_scan(data, kind)
