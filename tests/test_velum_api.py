"""GET /velum/rig, and velum_opening (and the lip parameters) on every route that takes
articulation parameters: accepted in range, refused out of range with 422 naming the range."""

import json

import pytest

from accounts_support import signed_in
from assets_support import copy_built_assets
from glasshead.constants import VELUM_RIG_FILE

API = "/api/v1"
OUT_OF_RANGE = "params.velum_opening: 1.5 is outside [0, 1]"


@pytest.fixture
def client(built_assets, start_app):
    return signed_in(start_app(built_assets)[1], "author")


def _pose(params, name="nasal"):
    return {"name": name, "params": params}


def test_the_velum_rig_is_served_as_built(client, built_assets):
    response = client.get(f"{API}/velum/rig")
    assert response.status_code == 200
    body = response.json()
    built = json.loads((built_assets / VELUM_RIG_FILE).read_text())
    assert body["parameters"] == built["parameters"]
    assert body["poses"]["positions"]["rest"] == built["poses"]["positions"]["rest"]
    assert body["port"]["rows"] == built["port"]["rows"]


def test_routes_that_take_parameters_accept_velum_opening_and_lip_parameters(client):
    params = {"velum_opening": 1.0, "lip_opening": 0.0, "tip_height": 2.0}
    surface = client.post(f"{API}/tongue/surface", json={"params": params})
    assert surface.status_code == 200 and "velum_opening" not in surface.json()["params"]
    plain = client.post(f"{API}/tongue/surface", json={"params": {"tip_height": 2.0}})
    assert surface.json()["vertices"] == plain.json()["vertices"]  # the tongue ignores them
    contacts = client.post(f"{API}/epg/contacts", json={"params": params})
    assert contacts.status_code == 200
    created = client.post(f"{API}/poses", json=_pose(params))
    assert created.status_code == 201 and created.json()["params"] == params
    pose_id = created.json()["id"]
    assert client.put(f"{API}/poses/{pose_id}",
                      json=_pose({"velum_opening": 0.0})).status_code == 200
    assert client.patch(f"{API}/poses/{pose_id}",
                        json={"params": {"velum_opening": 0.5}}).status_code == 200


def test_an_out_of_range_velum_opening_gets_a_422_naming_it_and_its_range_on_every_route(client):
    bad = {"velum_opening": 1.5}
    pose_id = client.post(f"{API}/poses", json=_pose({"velum_opening": 0.2})).json()["id"]
    responses = {
        "tongue surface": client.post(f"{API}/tongue/surface", json={"params": bad}),
        "epg contacts": client.post(f"{API}/epg/contacts", json={"params": bad}),
        "create pose": client.post(f"{API}/poses", json=_pose(bad, "other")),
        "replace pose": client.put(f"{API}/poses/{pose_id}", json=_pose(bad)),
        "update pose": client.patch(f"{API}/poses/{pose_id}", json={"params": bad}),
    }
    for route, response in responses.items():
        assert response.status_code == 422, route
        assert response.json()["detail"] == OUT_OF_RANGE, route
    assert client.get(f"{API}/poses/{pose_id}").json()["params"] == {"velum_opening": 0.2}
    low = client.post(f"{API}/epg/contacts", json={"params": {"velum_opening": -0.1}})
    assert low.json()["detail"] == "params.velum_opening: -0.1 is outside [0, 1]"


def test_out_of_range_lip_and_tongue_values_in_a_pose_are_refused_naming_the_range(client):
    lip = client.post(f"{API}/poses", json=_pose({"lip_protrusion": 9.0}))
    assert lip.status_code == 422
    assert lip.json()["detail"] == "params.lip_protrusion: 9 is outside [0, 8] mm"
    tongue = client.post(f"{API}/poses", json=_pose({"tip_height": 400.0}))
    assert tongue.status_code == 422 and tongue.json()["detail"].startswith(
        "params.tip_height: 400 is outside")
    kept = client.post(f"{API}/poses", json=_pose({"tip_advance": 1.5}))
    assert kept.status_code == 201  # a name no rig has is kept, as before


def test_without_a_built_velum_rig_the_velum_routes_say_what_to_run(built_assets, tmp_path,
                                                                    start_app):
    assets = tmp_path / "assets"
    copy_built_assets(built_assets, assets, VELUM_RIG_FILE, "*.glb")
    _, client = start_app(assets)
    for response in (client.get(f"{API}/velum/rig"),
                     client.post(f"{API}/tongue/surface", json={"params": {"velum_opening": 0.5}})):
        assert response.status_code == 503
        body = response.json()
        assert body["asset"] == "velum_rig" and body["file"] == VELUM_RIG_FILE
        assert body["problem"] == "missing" and body["command"] == "glasshead build"
    # A request without a velum parameter does not need the velum rig.
    assert client.post(f"{API}/tongue/surface", json={"params": {}}).status_code == 200
