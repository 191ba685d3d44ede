"""A killed server loses no acknowledged write: a real uvicorn server on a SQLite file is killed
with SIGKILL during concurrent writes (poses and recording imports), started again on the same
file, and every write it had answered 201 reads back; SQLite's integrity check says ok.

The default SQLite database is in WAL mode with a busy timeout (store/db.py), so that concurrent
writers wait instead of failing and a kill leaves a log the next start recovers.
"""

import sqlite3

from glasshead.store.db import SQLITE_BUSY_TIMEOUT_MS, engine_for
from server_process import (
    WRITES,
    ServerProcess,
    check_acknowledged_writes_are_there,
    kill_during_writes,
    write_concurrently,
)


def test_a_sqlite_file_database_is_in_wal_mode_with_a_busy_timeout(tmp_path):
    engine = engine_for(f"sqlite:///{tmp_path / 'wal.sqlite3'}")
    with engine.connect() as connection:
        driver = connection.connection.dbapi_connection
        assert driver.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
        assert driver.execute("PRAGMA busy_timeout").fetchone()[0] == SQLITE_BUSY_TIMEOUT_MS
        assert driver.execute("PRAGMA foreign_keys").fetchone()[0] == 1
    engine.dispose()


def test_every_acknowledged_write_survives_a_sigkill_and_the_database_checks_ok(tmp_path):
    """Two workers on one new file: they also migrate it once (a lock file beside it)."""
    database = tmp_path / "crash.sqlite3"
    server = ServerProcess(tmp_path, f"sqlite:///{database}", workers=2).start()
    try:
        acknowledged = kill_during_writes(server)
        server.start()  # the same database file, recovered from its WAL
        check_acknowledged_writes_are_there(server.base, acknowledged, server.headers)
        after = write_concurrently(server.base, 4, first=WRITES, headers=server.headers)
        assert len(after) == 4  # and it takes writes again
    finally:
        server.stop()
    with sqlite3.connect(database) as db:
        assert db.execute("PRAGMA integrity_check").fetchall() == [("ok",)]
        assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
        poses = db.execute("SELECT count(*) FROM saved_poses").fetchone()[0]
        recordings = db.execute("SELECT count(*) FROM epg_recordings").fetchone()[0]
    kinds = [kind for kind, _ in acknowledged.values()]
    assert poses >= kinds.count("pose") + 2 and recordings >= kinds.count("recording") + 2
