"""The utterance cache in the database: a made utterance's response and WAV by its id, so that
servers on several machines serve each other's utterances (store/utterance_cache.py).

Revision ID: 0010
Revises: 0009
Create Date: 2026-11-28
"""

import sqlalchemy as sa
from alembic import op

revision = "0010"
down_revision = "0009"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "utterance_cache",
        sa.Column("id", sa.String(length=24), nullable=False),
        sa.Column("answer", sa.LargeBinary(), nullable=False),
        sa.Column("wav", sa.LargeBinary(), nullable=True),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_utterance_cache")),
    )
    op.create_index(op.f("ix_utterance_cache_created_at"), "utterance_cache", ["created_at"],
                    unique=False)


def downgrade() -> None:
    op.drop_index(op.f("ix_utterance_cache_created_at"), table_name="utterance_cache")
    op.drop_table("utterance_cache")
