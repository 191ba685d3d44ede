"""The `glasshead` command writes what is made from code: the lesson format's JSON Schema and
the list of shared vector files (the vectors themselves: tests/test_vectors_command.py)."""

import json

from glasshead.cli import main
from glasshead.lessons.schema import json_schema
from glasshead.vectors import VECTOR_FILES


def test_lesson_schema_writes_the_published_schema(tmp_path, capsys):
    out = tmp_path / "lesson.schema.json"
    assert main(["lesson-schema", str(out)]) == 0
    assert json.loads(out.read_text()) == json_schema()
    assert capsys.readouterr().out.strip() == f"wrote {out}"


def test_vectors_lists_every_vector_file(capsys):
    assert main(["vectors", "--list"]) == 0
    assert capsys.readouterr().out.split() == list(VECTOR_FILES)


def test_migrate_brings_a_new_database_to_the_newest_migration(tmp_path, monkeypatch, capsys):
    from sqlalchemy import inspect

    from glasshead.settings import get_settings
    from glasshead.store.db import engine_for

    database = tmp_path / "new.sqlite3"
    url = f"sqlite:///{database}"
    monkeypatch.setenv("GLASSHEAD_DATABASE_URL", url)
    get_settings.cache_clear()
    try:
        assert main(["migrate"]) == 0
    finally:
        get_settings.cache_clear()
    assert "lessons" in inspect(engine_for(url)).get_table_names()
    assert capsys.readouterr().out.strip().endswith("is up to date")


def test_palate_names_a_scan_that_is_not_a_mesh_and_writes_nothing(tmp_path, capsys):
    scan = tmp_path / "jaw.stl"
    scan.write_bytes(b"solid nothing\nendsolid nothing\n")
    assert main(["palate", str(scan), "--out", str(tmp_path / "child")]) == 2
    assert f"{scan}: the file" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["jaw.stl"]
    assert main(["palate", str(tmp_path / "missing.ply"), "--out", str(tmp_path / "c")]) == 2
