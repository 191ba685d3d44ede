"""Past one machine: the API as two uvicorn worker processes on a real PostgreSQL server (started
by the test, tests/postgres_support.py) keeps the promises it keeps on SQLite: of 20 concurrent
PATCHes from one version exactly one wins, and a SIGKILL during concurrent writes loses no
acknowledged write and leaves tables and indexes that pg_amcheck finds sound.
"""

from concurrent.futures import ThreadPoolExecutor

import httpx
import pytest
import sqlalchemy as sa
from alembic.migration import MigrationContext

from glasshead.store.db import engine_for
from server_process import (
    API,
    WRITES,
    ServerProcess,
    check_acknowledged_writes_are_there,
    kill_during_writes,
    write_concurrently,
)

WORKERS = 2
POSE = {"name": "t closure", "description": "", "params": {"tip_height": 2.0}}


@pytest.fixture
def postgres_url(postgres_server) -> str:
    """A fresh, empty database on the module's PostgreSQL server."""
    return postgres_server.url(postgres_server.create_database())


def assert_migrated_once(url: str) -> None:
    """Two workers started at once on a new database: one migrated, the other found it done."""
    engine = engine_for(url)
    with engine.connect() as connection:
        heads = connection.execute(sa.text("SELECT version_num FROM alembic_version")).all()
        assert len(heads) == 1
        assert MigrationContext.configure(connection).get_current_revision() == heads[0][0]
    engine.dispose()


def test_of_twenty_concurrent_patches_across_two_new_workers_exactly_one_wins(tmp_path,
                                                                              postgres_url):
    server = ServerProcess(tmp_path, postgres_url, workers=WORKERS).start()
    try:
        with httpx.Client(base_url=server.base, timeout=30, headers=server.headers) as client:
            created = client.post(f"{API}/poses", json=POSE)
            assert created.status_code == 201, created.text
            pose_id, tag = created.json()["id"], created.headers["etag"]

            def patch(k):
                return client.patch(f"{API}/poses/{pose_id}", json={"description": f"edit {k}"},
                                    headers={"If-Match": tag}).status_code

            with ThreadPoolExecutor(max_workers=20) as pool:
                statuses = list(pool.map(patch, range(20)))
            assert sorted(statuses) == [200] + [412] * 19, statuses
            winner = statuses.index(200)
            kept = client.get(f"{API}/poses/{pose_id}").json()
            assert kept["description"] == f"edit {winner}"
    finally:
        server.stop()
    assert_migrated_once(postgres_url)


def test_every_acknowledged_write_survives_a_sigkill_of_both_workers(tmp_path, postgres_url,
                                                                      postgres_server):
    server = ServerProcess(tmp_path, postgres_url, workers=WORKERS)
    server.start()
    try:
        acknowledged = kill_during_writes(server)
        server.start()
        check_acknowledged_writes_are_there(server.base, acknowledged, server.headers)
        assert len(write_concurrently(server.base, 4, first=WRITES, headers=server.headers)) == 4
    finally:
        server.stop()
    database = postgres_url.split("/")[3].split("?")[0]
    counts = postgres_server.psql(database, "SELECT (SELECT count(*) FROM saved_poses) || ' ' || "
                                            "(SELECT count(*) FROM epg_recordings)").split()
    kinds = [kind for kind, _ in acknowledged.values()]
    assert int(counts[0]) >= kinds.count("pose") + 2
    assert int(counts[1]) >= kinds.count("recording") + 2
    postgres_server.amcheck(database)  # raises, naming the problem, when it finds corruption
