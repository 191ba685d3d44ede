"""The starter lessons show what they teach: each item on the cutaway in profile, close on the
mouth, with the labels its contrast is about (``glasshead.lessons.starter``).

A starter lesson nobody has changed since 0005 inserted it (no owner, still at version 1) gets
the new items and description, and version 2, so that an ETag taken before no longer matches.
A starter lesson someone edited, and every other lesson, is left as it is. Downgrading leaves
the lessons as they are: the new fields are optional in the lesson format.

Revision ID: 0013
Revises: 0012
Create Date: 2026-11-29
"""

import json
from datetime import UTC, datetime

import sqlalchemy as sa
from alembic import context, op

revision = "0013"
down_revision = "0012"
branch_labels = None
depends_on = None


def upgrade() -> None:
    from glasshead.lessons.starter import starter_lessons

    offline = context.is_offline_mode()
    lessons = sa.table("lessons", sa.column("id", sa.Integer), sa.column("title", sa.String),
                       sa.column("description", sa.String),
                       sa.column("items", sa.Text if offline else sa.JSON),
                       sa.column("owner_id", sa.Integer), sa.column("version", sa.Integer),
                       sa.column("updated_at", sa.DateTime(timezone=True)))
    now = datetime.now(UTC)
    for lesson in starter_lessons():
        items = [item.model_dump(mode="json") for item in lesson.items]
        op.execute(
            lessons.update()
            .where(lessons.c.title == lesson.title, lessons.c.owner_id.is_(None),
                   lessons.c.version == 1)
            .values(description=lesson.description,
                    items=json.dumps(items, ensure_ascii=False) if offline else items,
                    version=2, updated_at=now))


def downgrade() -> None:
    pass
