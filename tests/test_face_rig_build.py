"""The face rig build step and GET /api/v1/face/rig: what the rig holds, that it follows the built
meshes' vertex order, that the step skips itself when nothing changed, and the route's errors."""

import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.spatial import cKDTree

from face_rig_support import load_face
from glasshead.api.app import create_app
from glasshead.geometry.face import read_face_rig, validate_face_rig
from glasshead.geometry.face_rig import LIP_PARAMETER_NAMES, MESH_NAMES
from glasshead.pipeline.face_rig import build_face_rig, build_step
from glasshead.settings import get_settings

VECTORS = Path(__file__).parent / "vectors" / "face-rig.json"


@pytest.fixture(scope="module")
def face(built_assets):
    return load_face(built_assets)


def test_the_lip_parameters_use_the_tongue_rigs_table_format_in_group_lips(face, built_assets):
    tongue = json.loads((built_assets / "tongue-rig.json").read_text())["parameters"][0]
    for spec in face.rig["parameters"]:
        assert {"name", "unit", "min", "max", "neutral", "group"} <= set(spec)
        assert set(tongue) - {"moves"} <= set(spec) | {"moves"}
        assert spec["group"] == "lips" and spec["min"] <= spec["neutral"] <= spec["max"]
    assert tuple(p["name"] for p in face.rig["parameters"]) == LIP_PARAMETER_NAMES
    assert face.rig["jaw_parameter"] == "jaw_opening"


def test_the_rig_follows_the_built_meshes_vertex_for_vertex(face, manifest):
    counts = {m["name"]: m["vertices"] for m in manifest["meshes"] if m.get("scene", True)}
    for name in MESH_NAMES:
        spec = face.rig["meshes"][name]
        assert spec["vertex_count"] == counts[name] == len(face.meshes[name][0])
        digest = next(m["sha256"] for m in manifest["meshes"] if m["name"] == name)
        assert spec["source"] == f"build {digest}"
        probes = spec["probes"]
        np.testing.assert_allclose(face.meshes[name][0][probes["index"]], probes["position"],
                                   atol=1e-3)


def test_jaw_weights_run_from_the_upper_lip_to_the_lower_and_agree_on_shared_points(face):
    weights = {name: np.asarray(face.rig["meshes"][name]["jaw_weights"]) for name in MESH_NAMES}
    assert all(w.min() >= 0.0 and w.max() <= 1.0 for w in weights.values())
    for name, low, high in (("upper_lip", 0.0, 0.1), ("lower_lip", 0.8, 1.0)):
        middle = np.abs(face.meshes[name][0][:, 2]) < 5.0
        assert low <= np.median(weights[name][middle]) <= high, name
    # Wherever two meshes share a point they share its weight: skin and lips, skin and shell.
    for a, b in (("face_skin", "upper_lip"), ("face_skin", "lower_lip"),
                 ("upper_lip", "lower_lip"), ("face_skin", "head_shell")):
        distance, index = cKDTree(face.meshes[a][0]).query(face.meshes[b][0])
        shared = distance <= 1e-3
        assert shared.sum() >= 6, (a, b)
        np.testing.assert_allclose(weights[b][shared], weights[a][index[shared]], atol=1e-6)
    # The back of the head stays: most of the shell has weight 0.
    assert np.mean(weights["head_shell"] == 0.0) > 0.5


def test_the_build_step_skips_itself_when_nothing_changed(built_assets):
    before = (built_assets / "face-rig.json").stat().st_mtime_ns
    report = build_step(SimpleNamespace(data_dir=get_settings().data_dir, assets_dir=built_assets))
    assert report["skipped"] is True and report["step"] == "face-rig"
    assert (built_assets / "face-rig.json").stat().st_mtime_ns == before
    assert report["vertices"]["face_skin"] > 1500


def test_without_a_build_the_rig_is_made_from_the_sources_in_the_same_vertex_order(face, data_dir):
    rig = build_face_rig(data_dir, assets_dir=None)
    for name in MESH_NAMES:
        built, own = face.rig["meshes"][name], rig["meshes"][name]
        assert own["source"] == "sources" and own["vertex_count"] == built["vertex_count"]
        # Built meshes lie on the GLB lattice: within 0.0034 mm of the sources' points.
        np.testing.assert_allclose(own["probes"]["position"], built["probes"]["position"],
                                   atol=4e-3)
        np.testing.assert_allclose(own["jaw_weights"], built["jaw_weights"], atol=1e-3)


def test_a_damaged_rig_is_refused_with_the_reason(tmp_path):
    rig = json.loads(VECTORS.read_text())["fixtures"]["rig"]
    validate_face_rig(rig)
    for damage, message in ((lambda r: r.update(format_version=7), "format_version 7 is not 1"),
                            (lambda r: r["meshes"]["lower_lip"]["jaw_weights"].pop(),
                             "mesh lower_lip: needs vertex_count jaw_weights"),
                            (lambda r: r["teeth"]["upper"].pop("steps"), r"teeth.upper lacks"),
                            (lambda r: r["parameters"].reverse(), "face rig parameters are")):
        broken = json.loads(json.dumps(rig))
        damage(broken)
        path = tmp_path / "face-rig.json"
        path.write_text(json.dumps(broken))
        with pytest.raises(ValueError, match=message):
            read_face_rig(path)


@pytest.fixture
def client(tmp_path, monkeypatch):
    """An app whose assets directory holds the rig of the shared vectors."""
    rig = json.loads(VECTORS.read_text())["fixtures"]["rig"]
    (tmp_path / "face-rig.json").write_text(json.dumps(rig))
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(tmp_path))
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    yield TestClient(create_app())
    get_settings.cache_clear()


def test_the_rig_route_serves_the_definition(client):
    response = client.get("/api/v1/face/rig")
    assert response.status_code == 200
    body = response.json()
    assert [p["name"] for p in body["parameters"]] == list(LIP_PARAMETER_NAMES)
    assert body["parameters"][0]["unit"] == "ratio"
    assert len(body["meshes"]["upper_lip"]["jaw_weights"]) == \
        body["meshes"]["upper_lip"]["vertex_count"]
    assert {"upper", "lower"} <= set(body["teeth"])
    operations = client.get("/api/v1/openapi.json").json()["paths"]["/api/v1/face/rig"]
    assert operations["get"]["operationId"] == "getFaceRig"


def test_without_a_built_rig_the_route_answers_503_saying_what_to_run(client, tmp_path):
    (tmp_path / "face-rig.json").unlink()
    response = client.get("/api/v1/face/rig")
    assert response.status_code == 503
    assert "glasshead build" in response.json()["detail"]
