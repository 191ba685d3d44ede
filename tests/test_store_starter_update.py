"""Revision 0013: the starter lessons nobody changed get the views that show their sounds; an
edited one, one an author owns and every other lesson stay as they were."""

import json

from alembic import command
from sqlalchemy import text

from glasshead.lessons.starter import starter_lessons
from glasshead.store.db import alembic_config, engine_for, upgrade_to_head

#: Items as the starter lessons had them before 0013: see-through skin, no cutaway, every label.
OLD_ITEMS = [{"target": {"kind": "phoneme", "text": "s"}, "presentation": "static",
              "views": {"skin_transparency": 0.8, "labels": True, "epg": True}}]


def items_of(connection, lesson_id):
    items = connection.execute(text("SELECT items FROM lessons WHERE id = :id"),
                               {"id": lesson_id}).scalar_one()
    return json.loads(items) if isinstance(items, str) else items


def test_revision_0013_updates_only_the_starter_lessons_nobody_changed(tmp_path):
    url = f"sqlite:///{tmp_path / 'starter.sqlite3'}"
    engine = engine_for(url)
    config = alembic_config(url)
    with engine.begin() as connection:
        config.attributes["connection"] = connection
        command.upgrade(config, "0012")
    old = json.dumps(OLD_ITEMS)
    with engine.begin() as connection:
        titles = dict(connection.execute(text("SELECT title, id FROM lessons")).all())
        # As 0005 left them on a server made before: version 1, no owner, the old items.
        connection.execute(text("UPDATE lessons SET items = :items"), {"items": old})
        # One edited since (version 2), one taken over by an author, and an author's own.
        connection.execute(text("UPDATE lessons SET version = 2 WHERE title = '/t/ and /k/'"))
        connection.execute(text("INSERT INTO users (username, display_name, role, password_hash,"
                                " version, created_at, updated_at) VALUES ('ann', 'Ann', "
                                "'author', 'x', 1, CURRENT_TIMESTAMP, CURRENT_TIMESTAMP)"))
        connection.execute(text("UPDATE lessons SET owner_id = 1 WHERE title = '/r/ and /l/'"))
        connection.execute(text(
            "INSERT INTO lessons (title, language, description, items, version, created_at, "
            "updated_at) VALUES ('The vowels', 'en-US', 'mine', :items, 1, CURRENT_TIMESTAMP, "
            "CURRENT_TIMESTAMP)"), {"items": old})
        own = connection.execute(text("SELECT max(id) FROM lessons")).scalar_one()
        connection.execute(text("UPDATE lessons SET title = 'My vowels' WHERE id = :id"),
                           {"id": own})
    upgrade_to_head(engine)
    new = {lesson.title: [item.model_dump(mode="json") for item in lesson.items]
           for lesson in starter_lessons()}
    with engine.begin() as connection:
        versions = dict(connection.execute(text("SELECT id, version FROM lessons")).all())
        for title in ("/s/ and /ʃ/", "Nasals and their oral pairs", "The vowels"):
            assert items_of(connection, titles[title]) == new[title], title
            assert versions[titles[title]] == 2, "an ETag taken before no longer matches"
        for title in ("/t/ and /k/", "/r/ and /l/"):
            assert items_of(connection, titles[title]) == OLD_ITEMS, title
        assert items_of(connection, own) == OLD_ITEMS
        assert versions[own] == 1
    first = new["/s/ and /ʃ/"][0]["views"]
    assert (first["cutaway"], first["camera"], first["labels"]) == (
        True, "profile", ["tongue_tip", "alveolar", "postalveolar"])
    engine.dispose()
