"""Versions for optimistic concurrency, and ids that are never reused.

Saved poses and EPG recordings gain ``version`` (1 for what is stored already), counted up by
every update and given to clients as the ETag. On SQLite the two tables are rebuilt with
AUTOINCREMENT, so the id of a deleted record is never given to a new one (without it SQLite
reuses the largest id after a delete); so is ``fit_jobs``. PostgreSQL's sequences never reuse
an id.

Revision ID: 0003
Revises: 0002
Create Date: 2026-11-25
"""

import sqlalchemy as sa
from alembic import op

revision = "0003"
down_revision = "0002"
branch_labels = None
depends_on = None

TABLES = ("saved_poses", "epg_recordings")


def upgrade() -> None:
    for table in TABLES:
        with op.batch_alter_table(table, recreate="auto",
                                  table_kwargs={"sqlite_autoincrement": True}) as batch:
            batch.add_column(sa.Column("version", sa.Integer(), nullable=False,
                                       server_default=sa.text("1")))
    if op.get_bind().dialect.name == "sqlite":
        # add_column alone does not copy the table; AUTOINCREMENT needs the table made anew
        for table in (*TABLES, "fit_jobs"):
            with op.batch_alter_table(table, recreate="always",
                                      table_kwargs={"sqlite_autoincrement": True}):
                pass


def downgrade() -> None:
    for table in TABLES:
        with op.batch_alter_table(table) as batch:
            batch.drop_column("version")
