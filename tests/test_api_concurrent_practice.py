"""A class practising at once: hundreds of practice records written concurrently by the children
of a class (each with their own child token) through two uvicorn workers, on a SQLite file and on
a real PostgreSQL server, are all there afterwards, each once, with what was written; and a
teacher's rating of each, sent concurrently, lands on every one.
"""

from concurrent.futures import ThreadPoolExecutor

import httpx
import pytest

from server_process import API, ServerProcess

WORKERS = 2
CHILDREN = 10
#: Practice records written in all, from 8 threads (bounded: about 7 s on two busy cores).
RECORDS = 200


def database_url(setting: str, tmp_path, postgres_server_factory) -> str:
    if setting == "sqlite":
        return f"sqlite:///{tmp_path / 'practice.sqlite3'}"
    server = postgres_server_factory()
    return server.url(server.create_database())


def a_class_with_children(client: httpx.Client) -> tuple[int, list[dict]]:
    """As the admin: a class of CHILDREN children with the first starter lesson assigned;
    returns the lesson's id and each child with their token's Authorization header."""
    made = client.post(f"{API}/classes", json={"name": "Practice at once"})
    assert made.status_code == 201, made.text
    code = made.json()["join_code"]
    lesson_id = client.get(f"{API}/lessons").json()["lessons"][0]["id"]
    assigned = client.post(f"{API}/assignments",
                           json={"lesson_id": lesson_id, "class_id": made.json()["id"]})
    assert assigned.status_code == 201, assigned.text
    children = []
    for n in range(CHILDREN):
        child = client.post(f"{API}/children", json={"class_id": made.json()["id"],
                                                      "display_name": f"Child {n}",
                                                      "avatar": "owl"})
        assert child.status_code == 201, child.text
        session = client.post(f"{API}/auth/child-sessions",
                              json={"join_code": code, "child_id": child.json()["id"]},
                              headers={"Authorization": ""})
        assert session.status_code == 201, session.text
        children.append({"id": child.json()["id"],
                         "headers": {"Authorization": f"Bearer {session.json()['token']}"}})
    return lesson_id, children


def read_back(admin: httpx.Client) -> dict[int, dict]:
    """Every practice record, page by page, by id; the pages' total is RECORDS."""
    kept = []
    for offset in range(0, RECORDS + 100, 100):
        page = admin.get(f"{API}/practice", params={"offset": offset, "limit": 100})
        assert page.status_code == 200, page.text
        assert page.json()["total"] == RECORDS
        kept += page.json()["records"]
    return {record["id"]: record for record in kept}


@pytest.mark.parametrize("setting", ["sqlite", "postgresql"])
def test_hundreds_of_concurrent_practice_records_are_all_kept_once(setting, tmp_path, request):
    url = database_url(setting, tmp_path,
                       lambda: request.getfixturevalue("postgres_server"))
    server = ServerProcess(tmp_path, url, workers=WORKERS).start()
    try:
        with httpx.Client(base_url=server.base, timeout=30, headers=server.headers) as admin:
            lesson_id, children = a_class_with_children(admin)

            def practise(k: int) -> tuple[int, int]:
                child = children[k % CHILDREN]
                body = {"child_id": child["id"], "lesson_id": lesson_id, "item_index": 0,
                        "replays": k}
                with httpx.Client(base_url=server.base, timeout=30,
                                  headers=child["headers"]) as client:
                    response = client.post(f"{API}/practice", json=body)
                assert response.status_code == 201, (k, response.status_code, response.text)
                return k, response.json()["id"]

            with ThreadPoolExecutor(8) as pool:
                written = dict(pool.map(practise, range(RECORDS)))
            assert len(set(written.values())) == RECORDS, "every write got its own id"

            by_id = read_back(admin)
            assert len(by_id) == RECORDS
            for k, record_id in written.items():
                assert by_id[record_id]["replays"] == k
                assert by_id[record_id]["child_id"] == children[k % CHILDREN]["id"]

            def rate(record_id: int) -> int:
                return admin.patch(f"{API}/practice/{record_id}",
                                   json={"rating": 2, "rated_by": "adult"}).status_code

            with ThreadPoolExecutor(8) as pool:
                assert set(pool.map(rate, written.values())) == {200}
            assert all(record["rating"] == 2 for record in read_back(admin).values())
    finally:
        server.stop()
