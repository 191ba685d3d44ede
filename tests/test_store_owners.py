"""Schema revision 0008 on a database that has rows: owners and a recording's child are added
without losing a class, child or lesson (on SQLite the tables are not copied: dropping ``classes``
would delete its children by cascade), and the new foreign keys act as declared. On SQLite and on
a real PostgreSQL server."""

import pytest
from alembic import command
from sqlalchemy import inspect, text
from sqlalchemy.exc import IntegrityError

from glasshead.store.db import alembic_config, engine_for, upgrade_to_head
from postgres_support import throwaway_postgres

NOW = "CURRENT_TIMESTAMP"
ROWS_AT_0007 = (
    f"INSERT INTO users (username, display_name, role, password_hash, version, created_at, "
    f"updated_at) VALUES ('ann', 'Ann', 'teacher', 'x', 1, {NOW}, {NOW})",
    f"INSERT INTO classes (name, join_code, version, created_at, updated_at) "
    f"VALUES ('Owls', '7KQ4MX', 1, {NOW}, {NOW})",
    f"INSERT INTO children (class_id, display_name, avatar, version, created_at, updated_at) "
    f"VALUES (1, 'Ada', 'owl', 1, {NOW}, {NOW})",
    f"INSERT INTO assignments (lesson_id, class_id, version, created_at, updated_at) "
    f"VALUES (1, 1, 1, {NOW}, {NOW})",
)


@pytest.fixture(params=["sqlite", "postgresql"])
def url(request, tmp_path):
    if request.param == "sqlite":
        yield f"sqlite:///{tmp_path / 'owners.sqlite3'}"
        return
    with throwaway_postgres() as server:
        yield server.url(server.create_database())


def count(connection, table: str) -> int:
    return connection.execute(text(f"SELECT count(*) FROM {table}")).scalar_one()


def test_revision_0008_keeps_every_row_and_its_foreign_keys_act_as_declared(url):
    engine = engine_for(url)
    config = alembic_config(url)
    with engine.begin() as connection:
        config.attributes["connection"] = connection
        command.upgrade(config, "0007")
    with engine.begin() as connection:
        for statement in ROWS_AT_0007:
            connection.execute(text(statement))
        lessons = count(connection, "lessons")
    upgrade_to_head(engine)
    with engine.begin() as connection:
        assert [count(connection, t) for t in ("classes", "children", "assignments", "lessons")] \
            == [1, 1, 1, lessons]
        assert connection.execute(text("SELECT owner_id FROM classes")).scalar_one() is None
        connection.execute(text("UPDATE classes SET owner_id = 1"))
        connection.execute(text("UPDATE lessons SET owner_id = 1 WHERE id = 1"))
        connection.execute(text(
            "INSERT INTO epg_recordings (name, source_format, n_frames, first_t_s, last_t_s, "
            f"contacts, times, meta, version, created_at, updated_at, child_id, uploaded_by) "
            f"VALUES ('r', 'csv', 0, 0, 0, :blob, :blob, '{{}}', 1, {NOW}, {NOW}, 1, 1)"),
            {"blob": b""})
    with engine.begin() as connection:
        connection.execute(text("DELETE FROM users"))  # owners and uploaders: SET NULL
        assert connection.execute(text("SELECT owner_id FROM classes")).scalar_one() is None
        assert connection.execute(text("SELECT uploaded_by FROM epg_recordings")).scalar_one() \
            is None
        assert count(connection, "lessons") == lessons
        connection.execute(text("DELETE FROM children"))  # a child's recordings: CASCADE
        assert count(connection, "epg_recordings") == 0
    with pytest.raises(IntegrityError), engine.begin() as connection:
        connection.execute(text("UPDATE classes SET owner_id = 99"))
    foreign_keys = {fk["name"]: fk for fk in inspect(engine).get_foreign_keys("classes")}
    assert foreign_keys["fk_classes_owner_id_users"]["options"]["ondelete"] == "SET NULL"
    if url.startswith("sqlite"):
        with engine.connect() as connection:
            assert connection.execute(text("PRAGMA integrity_check")).scalar_one() == "ok"
    engine.dispose()
