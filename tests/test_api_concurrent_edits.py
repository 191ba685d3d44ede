"""No silent lost updates: ETags, If-Match and ids that are never reused (poses, recordings)."""

import sqlite3
from concurrent.futures import ThreadPoolExecutor

import pytest
import sqlalchemy as sa

from accounts_support import signed_in
from glasshead.store.db import alembic_config, engine_for, upgrade_to_head

API = "/api/v1"
POSE = {"name": "t closure", "description": "", "params": {"tip_height": 2.0}}
ONE_FRAME = {"format": "emur-json", "content": {"frames": [{"t_ms": 0, "rows": ["00000000"] * 8}]}}


@pytest.fixture
def client(start_app):
    return signed_in(start_app()[1], "admin")


def _pose(client, **changes):
    response = client.post(f"{API}/poses", json={**POSE, **changes})
    assert response.status_code == 201, response.text
    return response


def test_every_read_and_write_of_a_pose_carries_an_etag_that_changes_with_each_update(client):
    created = _pose(client)
    pose_id = created.json()["id"]
    tags = [created.headers["etag"], client.get(f"{API}/poses/{pose_id}").headers["etag"]]
    assert tags[0] == tags[1]
    patched = client.patch(f"{API}/poses/{pose_id}", json={"description": "v2"},
                           headers={"If-Match": tags[1]})
    assert patched.status_code == 200, patched.text
    assert patched.headers["etag"] != tags[1]
    assert client.get(f"{API}/poses/{pose_id}").headers["etag"] == patched.headers["etag"]


@pytest.mark.parametrize("method", ["PUT", "PATCH", "DELETE"])
def test_a_stale_write_gets_412_naming_the_current_etag_and_changes_nothing(client, method):
    pose_id = _pose(client).json()["id"]
    stale = client.get(f"{API}/poses/{pose_id}").headers["etag"]
    newer = client.patch(f"{API}/poses/{pose_id}", json={"description": "the newer edit"})
    assert newer.status_code == 200
    body = None if method == "DELETE" else {**POSE, "description": "the stale edit"}
    response = client.request(method, f"{API}/poses/{pose_id}", json=body,
                              headers={"If-Match": stale})
    assert response.status_code == 412, response.text
    assert response.headers["etag"] == newer.headers["etag"]
    assert "changed since it was read" in response.json()["detail"]
    kept = client.get(f"{API}/poses/{pose_id}")
    assert kept.status_code == 200 and kept.json()["description"] == "the newer edit"


def test_if_match_star_and_a_list_holding_the_current_etag_let_the_write_through(client):
    pose_id = _pose(client).json()["id"]
    current = client.get(f"{API}/poses/{pose_id}").headers["etag"]
    assert client.patch(f"{API}/poses/{pose_id}", json={"description": "a"},
                        headers={"If-Match": "*"}).status_code == 200
    current = client.get(f"{API}/poses/{pose_id}").headers["etag"]
    assert client.patch(f"{API}/poses/{pose_id}", json={"description": "b"},
                        headers={"If-Match": f'"pose-0-v1", {current}'}).status_code == 200


def test_a_write_without_if_match_is_allowed_and_overwrites(client):
    pose_id = _pose(client).json()["id"]
    response = client.put(f"{API}/poses/{pose_id}", json={**POSE, "description": "blind"})
    assert response.status_code == 200
    assert client.get(f"{API}/poses/{pose_id}").json()["description"] == "blind"


def test_of_twenty_concurrent_patches_from_the_same_version_exactly_one_wins(client):
    pose_id = _pose(client).json()["id"]
    tag = client.get(f"{API}/poses/{pose_id}").headers["etag"]

    def patch(k):
        return client.patch(f"{API}/poses/{pose_id}", json={"description": f"edit {k}"},
                            headers={"If-Match": tag}).status_code

    with ThreadPoolExecutor(max_workers=20) as pool:
        statuses = list(pool.map(patch, range(20)))
    assert sorted(statuses) == [200] + [412] * 19, statuses
    winner = statuses.index(200)
    assert client.get(f"{API}/poses/{pose_id}").json()["description"] == f"edit {winner}"


def test_a_deleted_poses_id_is_never_given_to_the_next_pose(client):
    first = _pose(client, name="first").json()["id"]
    second = _pose(client, name="second").json()["id"]
    assert client.delete(f"{API}/poses/{second}").status_code == 204
    third = _pose(client, name="third").json()["id"]
    assert third > second > first
    assert client.get(f"{API}/poses/{second}").status_code == 404


def test_a_deleted_recordings_id_is_never_reused_and_a_stale_delete_is_refused(client):
    made = client.post(f"{API}/epg/recordings", json=ONE_FRAME)
    assert made.status_code == 201
    recording = made.json()["recordings"][0]["id"]
    tag = client.get(f"{API}/epg/recordings/{recording}").headers["etag"]
    assert client.delete(f"{API}/epg/recordings/{recording}",
                         headers={"If-Match": '"recording-1-v9"'}).status_code == 412
    assert client.delete(f"{API}/epg/recordings/{recording}",
                         headers={"If-Match": tag}).status_code == 204
    again = client.post(f"{API}/epg/recordings", json=ONE_FRAME).json()["recordings"][0]["id"]
    assert again > recording


def test_upgrading_a_database_with_poses_keeps_them_at_version_1_and_stops_id_reuse(tmp_path):
    from alembic import command

    path = tmp_path / "old.sqlite3"
    engine = engine_for(f"sqlite:///{path}")
    config = alembic_config(f"sqlite:///{path}")
    with engine.begin() as connection:
        config.attributes["connection"] = connection
        command.upgrade(config, "0002")
        connection.execute(sa.text(
            "INSERT INTO saved_poses (id, name, description, params, created_at, updated_at) "
            "VALUES (7, 'old', '', '{}', '2026-01-01 00:00:00', '2026-01-01 00:00:00')"))
    upgrade_to_head(engine)
    engine.dispose()
    with sqlite3.connect(path) as db:
        assert db.execute("SELECT id, name, version FROM saved_poses").fetchall() == [
            (7, "old", 1)]
        for table in ("saved_poses", "epg_recordings", "fit_jobs"):
            sql = db.execute("SELECT sql FROM sqlite_master WHERE name = ?", (table,)).fetchone()
            assert "AUTOINCREMENT" in sql[0], sql
