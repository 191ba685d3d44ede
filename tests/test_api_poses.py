"""Saved poses over HTTP: create, read, list by name, replace, update, delete, and bad input."""

import pytest

from accounts_support import signed_in

API = "/api/v1"
TIP_UP = {"name": "tip up", "description": "alveolar closure",
          "params": {"tip_advance": 1.5, "tip_height": 4.0}}


@pytest.fixture
def client(start_app):
    """The app with an admin signed in (tests/test_api_roles.py has the other roles)."""
    return signed_in(start_app()[1], "admin")


def test_a_saved_pose_is_created_and_read_back(client):
    created = client.post(f"{API}/poses", json=TIP_UP)
    assert created.status_code == 201
    pose = created.json()
    assert pose["params"] == TIP_UP["params"] and pose["description"] == "alveolar closure"
    assert pose["created_at"].endswith("Z") or pose["created_at"].endswith("+00:00")
    again = client.get(f"{API}/poses/{pose['id']}").json()
    assert again == pose


def test_names_are_unique_and_a_clash_is_a_409_that_stores_nothing(client):
    client.post(f"{API}/poses", json=TIP_UP)
    clash = client.post(f"{API}/poses", json={**TIP_UP, "name": "  tip up  "})
    assert clash.status_code == 409 and "tip up" in clash.json()["detail"]
    other = client.post(f"{API}/poses", json={**TIP_UP, "name": "back up"}).json()
    rename = client.patch(f"{API}/poses/{other['id']}", json={"name": "tip up"})
    assert rename.status_code == 409
    assert client.get(f"{API}/poses/{other['id']}").json()["name"] == "back up"
    assert client.get(f"{API}/poses").json()["total"] == 2


def test_poses_list_in_name_order_and_can_be_found_by_name(client):
    for name in ("velar", "alveolar", "palatal"):
        client.post(f"{API}/poses", json={**TIP_UP, "name": name})
    listing = client.get(f"{API}/poses").json()
    assert [p["name"] for p in listing["poses"]] == ["alveolar", "palatal", "velar"]
    found = client.get(f"{API}/poses", params={"name": "palatal"}).json()
    assert found["total"] == 1 and found["poses"][0]["name"] == "palatal"
    assert client.get(f"{API}/poses", params={"name": "uvular"}).json()["total"] == 0


def test_put_replaces_and_patch_changes_only_the_given_fields(client):
    pose = client.post(f"{API}/poses", json=TIP_UP).json()
    replaced = client.put(f"{API}/poses/{pose['id']}",
                          json={"name": "tip down", "params": {"tip_height": -2.0}}).json()
    assert replaced["params"] == {"tip_height": -2.0} and replaced["description"] == ""
    patched = client.patch(f"{API}/poses/{pose['id']}", json={"description": "rest"}).json()
    assert (patched["name"], patched["params"], patched["description"]) == \
        ("tip down", {"tip_height": -2.0}, "rest")
    assert patched["updated_at"] >= pose["updated_at"]


def test_delete_removes_a_pose_and_unknown_ids_are_404(client):
    pose = client.post(f"{API}/poses", json=TIP_UP).json()
    assert client.delete(f"{API}/poses/{pose['id']}").status_code == 204
    assert client.get(f"{API}/poses/{pose['id']}").status_code == 404
    assert client.delete(f"{API}/poses/{pose['id']}").status_code == 404
    assert client.put(f"{API}/poses/999", json=TIP_UP).status_code == 404


@pytest.mark.parametrize("body, fragment", [
    ({**TIP_UP, "params": {"tip_height": "high"}}, "params.tip_height"),
    ({**TIP_UP, "params": {"9lives": 1.0}}, "'9lives' is not a parameter name"),
    ({**TIP_UP, "name": "   "}, "name"),
    ({**TIP_UP, "colour": "red"}, "colour"),
    ({"name": "no params"}, "params"),
])
def test_bad_poses_are_refused_with_422_naming_the_field(client, body, fragment):
    response = client.post(f"{API}/poses", json=body)
    assert response.status_code == 422
    assert fragment in response.json()["detail"]
    assert client.get(f"{API}/poses").json()["total"] == 0


def test_non_finite_parameter_values_are_refused(client):
    for value in (b"NaN", b"1e400", b"-Infinity"):
        response = client.post(f"{API}/poses",
                               content=b'{"name": "x", "params": {"jaw": ' + value + b"}}",
                               headers={"content-type": "application/json"})
        assert response.status_code == 422, value
        assert "params" in response.json()["detail"]
    assert client.get(f"{API}/poses").json()["total"] == 0


@pytest.mark.parametrize("field", ["params", "name", "description"])
def test_patching_a_field_to_null_is_refused(client, field):
    pose = client.post(f"{API}/poses", json=TIP_UP).json()
    response = client.patch(f"{API}/poses/{pose['id']}", json={field: None})
    assert response.status_code == 422 and field in response.json()["detail"]


def test_a_patched_description_past_its_length_is_refused_by_name(client):
    pose = client.post(f"{API}/poses", json=TIP_UP).json()
    response = client.patch(f"{API}/poses/{pose['id']}", json={"description": "x" * 2001})
    assert response.status_code == 422, response.text
    assert "description" in response.json()["detail"] and "2000" in response.json()["detail"]
