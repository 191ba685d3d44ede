"""The asset store: every built file loaded once at start-up, reloaded when its content changes,
and a missing or corrupt file answered with one 503 shape on every route that needs it."""

import json
import os

import pytest

from assets_support import copy_built_assets
from glasshead.asset_store import ASSETS, AssetStore, AssetUnavailableError
from glasshead.constants import REBUILD_COMMAND

#: An utterance with its flesh points, which pose the lip meshes.
FLESH_POINTS = {"phones": [{"symbol": "P", "start_s": 0.0, "end_s": 0.1}],
                "audio": {"kind": "none"}, "flesh_points": True}
#: Every route that reads a built asset, with a request that is valid when the asset is there.
ROUTES = {
    "manifest": [("get", "/api/v1/anatomy", None)],
    "tongue_rig": [("get", "/api/v1/tongue/rig", None),
                   ("post", "/api/v1/tongue/surface", {"params": {"tip_height": 2.0}}),
                   ("post", "/api/v1/epg/contacts", {"params": {"tip_height": 2.0}})],
    "collision_tables": [("get", "/api/v1/collision/tables", None),
                         ("post", "/api/v1/collision/correct", {"vertices": [[0.0, 0.0, 0.0]]}),
                         ("post", "/api/v1/epg/contacts", {"params": {"tip_height": 2.0}})],
    "epg_layout": [("get", "/api/v1/epg/layout", None),
                   ("post", "/api/v1/epg/contacts", {"params": {"tip_height": 2.0}})],
    "face_rig": [("get", "/api/v1/face/rig", None)],
    "velum_rig": [("get", "/api/v1/velum/rig", None),
                  ("post", "/api/v1/tongue/surface", {"params": {"velum_opening": 0.5}})],
    "landmarks": [("get", "/api/v1/anatomy/landmarks", None)],
    "velum_mesh": [("post", "/api/v1/collision/correct",
                    {"vertices": [[0.0, 0.0, 0.0]], "velum_opening": 0.5}),
                   ("post", "/api/v1/tract/acoustics", {"params": {"velum_opening": 0.5}})],
    "pharynx_mesh": [("post", "/api/v1/collision/correct",
                      {"vertices": [[0.0, 0.0, 0.0]], "velum_opening": 0.5})],
    "upper_lip_mesh": [("post", "/api/v1/utterances", FLESH_POINTS)],
    "lower_lip_mesh": [("post", "/api/v1/utterances", FLESH_POINTS)],
    "phoneme_targets": [("get", "/api/v1/phonemes", None), ("get", "/api/v1/phonemes/T", None)],
    "vtl_observations": [("get", "/api/v1/observations", None),
                         ("get", "/api/v1/observations/a", None)],
    "fit_report": [("get", "/api/v1/observations", None), ("get", "/api/v1/observations/a", None)],
    "tract_section": [("post", "/api/v1/tract/acoustics", {"params": {"jaw_opening": 2.0}})],
}


@pytest.fixture
def assets(tmp_path, built_assets):
    """A private copy of the built assets, free to damage."""
    copy = tmp_path / "assets"
    copy_built_assets(built_assets, copy)
    return copy


def _call(client, method, path, body):
    return client.post(path, json=body) if method == "post" else client.get(path)


def _file(name):
    return next(spec.file for spec in ASSETS if spec.name == name)


def test_every_route_serves_from_the_one_store_loaded_at_start_up(assets, start_app):
    app, client = start_app(assets)
    loads_after_start = dict(app.state.assets.loads)
    assert loads_after_start == dict.fromkeys(loads_after_start, 1)
    for calls in ROUTES.values():
        for method, path, body in calls:
            response = _call(client, method, path, body)
            assert response.status_code == 200, (path, response.text)
    assert app.state.assets.loads == loads_after_start


def test_health_lists_every_asset_with_its_content_hash(assets, start_app):
    _, client = start_app(assets)
    body = client.get("/api/v1/health").json()
    assert body["status"] == "ok" and body["assets_built"] is True
    assert set(body["assets"]) == {spec.name for spec in ASSETS}
    for state in body["assets"].values():
        assert state["status"] == "ok" and len(state["sha256"]) == 64


def test_a_file_rewritten_with_other_content_is_reloaded_even_with_the_same_size_and_time(
        assets):
    store = AssetStore(assets, recheck_s=0.0)
    path = assets / _file("face_rig")
    rig = json.loads(path.read_text())
    first = store.get("face_rig")
    assert first["parameters"][0]["description"] == rig["parameters"][0]["description"]
    stat = path.stat()
    text = path.read_text()
    old = rig["parameters"][0]["description"]
    new = old[::-1]  # same length: same size
    path.write_text(text.replace(json.dumps(old), json.dumps(new), 1))
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert path.stat().st_size == stat.st_size
    assert store.get("face_rig")["parameters"][0]["description"] == new
    assert store.loads["face_rig"] == 2


def test_a_file_touched_without_a_change_is_not_parsed_again(assets):
    store = AssetStore(assets, recheck_s=0.0)
    rig = store.get("tongue_rig")
    (assets / _file("tongue_rig")).touch()
    assert store.get("tongue_rig") is rig
    assert store.loads["tongue_rig"] == 1


def test_derived_values_are_made_once_per_version_of_their_asset(assets):
    store = AssetStore(assets, recheck_s=0.0)
    made = []
    for _ in range(3):
        store.derived("epg_layout", "count", lambda layout: made.append(1) or len(layout))
    assert len(made) == 1
    path = assets / _file("epg_layout")
    path.write_text(path.read_text() + "\n")
    store.derived("epg_layout", "count", lambda layout: made.append(1) or len(layout))
    assert len(made) == 2


@pytest.mark.parametrize("name", [spec.name for spec in ASSETS])
@pytest.mark.parametrize("damage", ["missing", "truncated", "garbage"])
def test_a_missing_or_corrupt_asset_answers_503_naming_it_and_the_command(assets, start_app,
                                                                          name, damage):
    path = assets / _file(name)
    if damage == "missing":
        path.unlink()
    elif damage == "truncated":
        path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    else:
        path.write_bytes(b"\x00\xffnot an asset")
    problem = "missing" if damage == "missing" else "corrupt"
    _, client = start_app(assets)  # the server starts
    health = client.get("/api/v1/health").json()
    assert health["status"] == "degraded" and health["assets_built"] is False
    assert health["assets"][name]["status"] == problem
    assert _file(name) in health["assets"][name]["detail"]
    others = [n for n in health["assets"] if n != name]
    assert all(health["assets"][n]["status"] == "ok" for n in others)
    for method, path_, body in ROUTES[name]:
        response = _call(client, method, path_, body)
        assert response.status_code == 503, (path_, response.text)
        assert response.headers["content-type"].startswith("application/json")
        error = response.json()
        assert error["asset"] == name and error["file"] == _file(name)
        assert error["problem"] == problem and error["command"] == REBUILD_COMMAND
        assert _file(name) in error["detail"] and REBUILD_COMMAND in error["detail"]


def test_a_repaired_asset_is_served_again_without_a_restart(assets, start_app):
    path = assets / _file("tongue_rig")
    good = path.read_bytes()
    path.write_text("{}")
    app, client = start_app(assets)
    app.state.assets.recheck_s = 0.0
    assert client.get("/api/v1/tongue/rig").status_code == 503
    path.write_bytes(good)
    assert client.get("/api/v1/tongue/rig").status_code == 200


def test_no_request_fits_or_builds_anything(assets, monkeypatch, start_app):
    """Without a tongue rig the routes answer 503 at once; they never fit the rest shape."""
    import glasshead.pipeline.build as build
    import glasshead.pipeline.tongue_rig as tongue_rig

    def refuse(*args, **kwargs):
        raise AssertionError("a request ran the pipeline")

    monkeypatch.setattr(tongue_rig, "fit_definition", refuse)
    monkeypatch.setattr(tongue_rig, "build_tongue_rig", refuse)
    monkeypatch.setattr(build, "run", refuse)
    (assets / _file("tongue_rig")).unlink()
    _, client = start_app(assets)
    for method, path, body in ROUTES["tongue_rig"]:
        assert _call(client, method, path, body).status_code == 503


def test_the_store_refuses_an_unknown_asset_name_and_reports_unavailable_ones(tmp_path):
    store = AssetStore(tmp_path)
    with pytest.raises(KeyError, match="no asset named"):
        store.get("nothing")
    with pytest.raises(AssetUnavailableError, match="glasshead build"):
        store.get("manifest")
    assert store.status()["ok"] is False


@pytest.mark.parametrize("bad", [True, None, "1.5", [1.0]])
def test_observations_with_a_coordinate_that_is_not_a_number_are_corrupt(assets, bad):
    path = assets / _file("vtl_observations")
    document = json.loads(path.read_text())
    document["shapes"][3]["tongue_surface_vertices"][17][1] = bad
    path.write_text(json.dumps(document))
    store = AssetStore(assets)
    with pytest.raises(AssetUnavailableError, match="corrupt"):
        store.get("vtl_observations")
    document["shapes"][3]["tongue_surface_vertices"][17][1] = 2
    path.write_text(json.dumps(document))
    assert AssetStore(assets).get("vtl_observations")["shapes"][3]["name"]
