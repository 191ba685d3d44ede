"""Owners: who made each class, lesson, saved pose and fit; whose each EPG recording is; and the
failed sign-in attempts that limit guessing.

``classes``, ``lessons``, ``saved_poses`` and ``fit_jobs`` gain ``owner_id`` (the user who made
the row; NULL when that user is removed, and NULL for every row made before this revision, which
only an admin may then change). ``epg_recordings`` gains ``child_id`` (the child it was recorded
from, deleted with the child; NULL for a reference recording) and ``uploaded_by`` (the user who
imported it). ``sign_in_attempts`` keeps failed sign-ins for a while (``glasshead.attempts``).

On SQLite the tables are not copied, as batch mode would do: dropping the old ``classes`` or
``lessons`` with foreign keys enforced would delete, by cascade, every child, assignment and
practice record that points at them. The column is added in place (``ALTER TABLE ... ADD
COLUMN``), and its foreign key is written into the table's definition as a table constraint,
the form ``create_table`` gives (SQLite's documented in-place schema change: ``writable_schema``
and a new ``schema_version``). That is safe because the new column holds only NULLs, which no
foreign key refuses. The downgrade copies the tables; run it with ``PRAGMA foreign_keys=OFF``.

Revision ID: 0008
Revises: 0007
Create Date: 2026-11-25
"""

import sqlalchemy as sa
from alembic import op

revision = "0008"
down_revision = "0007"
branch_labels = None
depends_on = None

#: (table, column, referred table, ON DELETE)
REFERENCES = (
    ("classes", "owner_id", "users", "SET NULL"),
    ("lessons", "owner_id", "users", "SET NULL"),
    ("saved_poses", "owner_id", "users", "SET NULL"),
    ("fit_jobs", "owner_id", "users", "SET NULL"),
    ("epg_recordings", "child_id", "children", "CASCADE"),
    ("epg_recordings", "uploaded_by", "users", "SET NULL"),
)


def upgrade() -> None:
    sqlite = op.get_context().dialect.name == "sqlite"
    for table, column, referred, ondelete in REFERENCES:
        name = f"fk_{table}_{column}_{referred}"
        if sqlite:
            op.execute(f"ALTER TABLE {table} ADD COLUMN {column} INTEGER")
            _sqlite_add_constraint(table, f"CONSTRAINT {name} FOREIGN KEY({column}) "
                                          f"REFERENCES {referred} (id) ON DELETE {ondelete}")
        else:
            op.add_column(table, sa.Column(column, sa.Integer(), nullable=True))
            op.create_foreign_key(name, table, referred, [column], ["id"], ondelete=ondelete)
        op.create_index(f"ix_{table}_{column}", table, [column], unique=False)
    op.create_table(
        "sign_in_attempts",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("key", sa.String(length=300), nullable=False),
        sa.Column("failed_at", sa.DateTime(timezone=True), nullable=False),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_sign_in_attempts")),
    )
    op.create_index(op.f("ix_sign_in_attempts_key"), "sign_in_attempts", ["key"], unique=False)


def _sqlite_add_constraint(table: str, constraint: str) -> None:
    """Append ``constraint`` to ``table``'s CREATE TABLE text, in place (sqlite.org/lang_altertable,
    "making other kinds of table schema changes"); valid only for a constraint that the rows
    already meet."""
    bind = op.get_bind()
    sql = bind.execute(sa.text("SELECT sql FROM sqlite_master WHERE type = 'table' AND "
                               "name = :name"), {"name": table}).scalar_one().rstrip()
    if not sql.endswith(")"):
        raise RuntimeError(f"unexpected definition of table {table}: {sql!r}")
    version = bind.execute(sa.text("PRAGMA schema_version")).scalar_one()
    bind.execute(sa.text("PRAGMA writable_schema = ON"))
    bind.execute(sa.text("UPDATE sqlite_master SET sql = :sql WHERE type = 'table' AND "
                         "name = :name"),
                 {"sql": f"{sql[:-1].rstrip()}, \n\t{constraint}\n)", "name": table})
    bind.execute(sa.text(f"PRAGMA schema_version = {int(version) + 1}"))
    bind.execute(sa.text("PRAGMA writable_schema = OFF"))


def downgrade() -> None:
    op.drop_index(op.f("ix_sign_in_attempts_key"), table_name="sign_in_attempts")
    op.drop_table("sign_in_attempts")
    for table, column, referred, _ in reversed(REFERENCES):
        op.drop_index(f"ix_{table}_{column}", table_name=table)
        with op.batch_alter_table(table) as batch:
            batch.drop_constraint(f"fk_{table}_{column}_{referred}", type_="foreignkey")
            batch.drop_column(column)
