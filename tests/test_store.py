"""The database store: migrations, the schema they build, and what the tables keep."""

import io
from contextlib import redirect_stdout
from datetime import UTC, datetime

import numpy as np
import pytest
from alembic import command
from alembic.autogenerate import compare_metadata
from alembic.migration import MigrationContext
from alembic.script import ScriptDirectory
from sqlalchemy import inspect, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from glasshead.epg.formats import parse
from glasshead.settings import Settings, get_settings
from glasshead.store.base import Base
from glasshead.store.db import alembic_config, engine_for, get_engine, upgrade_to_head
from glasshead.store.models import EpgRecording, SavedPose
from glasshead.vectors.sources import emur_path


@pytest.fixture
def engine(tmp_path):
    engine = engine_for(f"sqlite:///{tmp_path / 'store.sqlite3'}")
    upgrade_to_head(engine)
    yield engine
    engine.dispose()


def test_the_default_database_is_a_sqlite_file_whose_directory_is_created(tmp_path, monkeypatch):
    path = tmp_path / "deep" / "er" / "glasshead.sqlite3"
    monkeypatch.setenv("GLASSHEAD_DATABASE_URL", f"sqlite:///{path}")
    get_settings.cache_clear()
    try:
        engine = get_engine()
        upgrade_to_head(engine)
        assert path.is_file()
        assert {"epg_recordings", "saved_poses"} <= set(inspect(engine).get_table_names())
        engine.dispose()
    finally:
        get_settings.cache_clear()


def test_the_shipped_settings_default_to_a_file_under_var():
    assert Settings.model_fields["database_url"].default.endswith("/var/glasshead.sqlite3")


def test_the_migrations_build_exactly_the_schema_of_the_models(engine):
    with engine.connect() as connection:
        differences = compare_metadata(MigrationContext.configure(connection), Base.metadata)
    assert differences == []


def test_upgrading_twice_changes_nothing_and_records_the_head_revision(engine):
    upgrade_to_head(engine)
    with engine.connect() as connection:
        current = MigrationContext.configure(connection).get_current_revision()
    assert current == ScriptDirectory.from_config(alembic_config()).get_current_head()
    assert current is not None and current >= "0005"


def test_the_migrations_render_as_postgresql(tmp_path):
    config = alembic_config("postgresql+psycopg://user:p%40ss@db/glasshead")
    buffer = io.StringIO()
    config.output_buffer = buffer
    with redirect_stdout(buffer):
        command.upgrade(config, "head", sql=True)
    sql = buffer.getvalue()
    assert "CREATE TABLE epg_recordings" in sql and "BYTEA" in sql
    assert "CONSTRAINT uq_saved_poses_name UNIQUE (name)" in sql


def test_a_real_recording_is_stored_as_compact_blobs_and_read_back_unchanged(engine):
    sequence = parse(emur_path().read_bytes(), "emur-json")[7]
    with Session(engine) as session:
        session.add(EpgRecording.from_sequence(sequence, "emur-json"))
        session.commit()
    with Session(engine) as session:
        record = session.scalars(select(EpgRecording)).one()
        assert len(record.contacts) == 8 * sequence.n_frames
        assert len(record.times) == 8 * sequence.n_frames
        back = record.to_sequence()
    np.testing.assert_array_equal(back.frames, sequence.frames)
    np.testing.assert_array_equal(back.t_s, sequence.t_s)  # stored as float64 bytes: exact
    assert (back.name, back.frame_rate_hz, back.meta) == (sequence.name, sequence.frame_rate_hz,
                                                          sequence.meta)
    assert record.first_t_s == sequence.t_s[0] and record.last_t_s == sequence.t_s[-1]


def test_pose_names_are_unique_and_times_come_back_in_utc(engine):
    with Session(engine) as session:
        before = datetime.now(UTC)
        session.add(SavedPose(name="tip up", params={"tip_height": 2.0}))
        session.commit()
        pose = session.scalars(select(SavedPose)).one()
        assert pose.created_at.tzinfo is UTC
        assert before <= pose.created_at <= datetime.now(UTC)
        session.add(SavedPose(name="tip up", params={}))
        with pytest.raises(IntegrityError):
            session.commit()


def test_naive_datetimes_are_refused_rather_than_stored_in_an_unknown_zone(engine):
    with Session(engine) as session:
        session.add(SavedPose(name="x", params={}, created_at=datetime(2024, 1, 1)))
        with pytest.raises(Exception, match="timezone-aware"):
            session.commit()
