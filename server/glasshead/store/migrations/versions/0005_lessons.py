"""Lessons, classes, children, assignments and practice records; the starter lessons.

Every table is versioned (ETags) and never reuses an id (AUTOINCREMENT on SQLite). The starter
lessons (``glasshead.lessons.starter``) are inserted here, once, into the new table: a restart
finds the database at head and inserts nothing, and a lesson a user deletes stays deleted.

Revision ID: 0005
Revises: 0004
Create Date: 2026-11-25
"""

import json
from datetime import UTC, datetime

import sqlalchemy as sa
from alembic import context, op

revision = "0005"
down_revision = "0004"
branch_labels = None
depends_on = None


def _common() -> list[sa.Column]:
    return [sa.Column("version", sa.Integer(), nullable=False, server_default=sa.text("1")),
            sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
            sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False)]


def upgrade() -> None:
    auto = {"sqlite_autoincrement": True}
    op.create_table(
        "classes",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("name", sa.String(length=120), nullable=False),
        sa.Column("join_code", sa.String(length=6), nullable=False),
        *_common(),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_classes")),
        sa.UniqueConstraint("join_code", name=op.f("uq_classes_join_code")),
        **auto,
    )
    op.create_table(
        "children",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("class_id", sa.Integer(), nullable=False),
        sa.Column("display_name", sa.String(length=40), nullable=False),
        sa.Column("avatar", sa.String(length=20), nullable=False),
        *_common(),
        sa.ForeignKeyConstraint(["class_id"], ["classes.id"], ondelete="CASCADE",
                                name=op.f("fk_children_class_id_classes")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_children")),
        **auto,
    )
    op.create_table(
        "lessons",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("title", sa.String(length=200), nullable=False),
        sa.Column("language", sa.String(length=35), nullable=False),
        sa.Column("description", sa.String(length=2000), nullable=False),
        sa.Column("items", sa.JSON(), nullable=False),
        *_common(),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_lessons")),
        **auto,
    )
    op.create_table(
        "assignments",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("lesson_id", sa.Integer(), nullable=False),
        sa.Column("class_id", sa.Integer(), nullable=True),
        sa.Column("child_id", sa.Integer(), nullable=True),
        *_common(),
        sa.CheckConstraint("(class_id IS NULL) <> (child_id IS NULL)",
                           name=op.f("ck_assignments_one_assignee")),
        sa.ForeignKeyConstraint(["lesson_id"], ["lessons.id"], ondelete="CASCADE",
                                name=op.f("fk_assignments_lesson_id_lessons")),
        sa.ForeignKeyConstraint(["class_id"], ["classes.id"], ondelete="CASCADE",
                                name=op.f("fk_assignments_class_id_classes")),
        sa.ForeignKeyConstraint(["child_id"], ["children.id"], ondelete="CASCADE",
                                name=op.f("fk_assignments_child_id_children")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_assignments")),
        **auto,
    )
    op.create_table(
        "practice_records",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("child_id", sa.Integer(), nullable=False),
        sa.Column("lesson_id", sa.Integer(), nullable=False),
        sa.Column("item_index", sa.Integer(), nullable=False),
        sa.Column("practised_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("replays", sa.Integer(), nullable=False),
        sa.Column("rating", sa.Integer(), nullable=True),
        sa.Column("rated_by", sa.String(length=10), nullable=True),
        *_common(),
        sa.ForeignKeyConstraint(["child_id"], ["children.id"], ondelete="CASCADE",
                                name=op.f("fk_practice_records_child_id_children")),
        sa.ForeignKeyConstraint(["lesson_id"], ["lessons.id"], ondelete="CASCADE",
                                name=op.f("fk_practice_records_lesson_id_lessons")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_practice_records")),
        **auto,
    )
    for table, column in (("children", "class_id"), ("assignments", "lesson_id"),
                          ("assignments", "class_id"), ("assignments", "child_id"),
                          ("practice_records", "child_id"), ("practice_records", "lesson_id")):
        op.create_index(op.f(f"ix_{table}_{column}"), table, [column], unique=False)
    _insert_starter_lessons()


def _insert_starter_lessons() -> None:
    """Online, the items as JSON values; in ``alembic upgrade --sql`` (offline) as JSON text,
    which renders as a literal (a JSON value does not) that both backends' JSON columns take."""
    from glasshead.lessons.starter import starter_lessons

    offline = context.is_offline_mode()
    lessons = sa.table("lessons", sa.column("title", sa.String), sa.column("language", sa.String),
                       sa.column("description", sa.String),
                       sa.column("items", sa.Text if offline else sa.JSON),
                       sa.column("version", sa.Integer),
                       sa.column("created_at", sa.DateTime(timezone=True)),
                       sa.column("updated_at", sa.DateTime(timezone=True)))
    now = datetime.now(UTC)
    op.bulk_insert(lessons, [
        {"title": lesson.title, "language": lesson.language, "description": lesson.description,
         "items": _json(lesson.items, offline),
         "version": 1, "created_at": now, "updated_at": now}
        for lesson in starter_lessons()])


def _json(items, offline: bool):
    values = [item.model_dump(mode="json") for item in items]
    return json.dumps(values, ensure_ascii=False) if offline else values


def downgrade() -> None:
    for table in ("practice_records", "assignments", "lessons", "children", "classes"):
        op.drop_table(table)
