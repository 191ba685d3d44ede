"""Children's bearer tokens (stored as SHA-256), from signing in with a class's join code.

Revision ID: 0007
Revises: 0006
Create Date: 2026-11-25
"""

import sqlalchemy as sa
from alembic import op

revision = "0007"
down_revision = "0006"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "child_tokens",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("token_sha256", sa.String(length=64), nullable=False),
        sa.Column("child_id", sa.Integer(), nullable=False),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("expires_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("revoked_at", sa.DateTime(timezone=True), nullable=True),
        sa.ForeignKeyConstraint(["child_id"], ["children.id"], ondelete="CASCADE",
                                name=op.f("fk_child_tokens_child_id_children")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_child_tokens")),
        sa.UniqueConstraint("token_sha256", name=op.f("uq_child_tokens_token_sha256")),
    )
    op.create_index(op.f("ix_child_tokens_child_id"), "child_tokens", ["child_id"], unique=False)


def downgrade() -> None:
    op.drop_index(op.f("ix_child_tokens_child_id"), table_name="child_tokens")
    op.drop_table("child_tokens")
