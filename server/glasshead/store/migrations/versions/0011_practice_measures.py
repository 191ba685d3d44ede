"""A practice record's measures: what the learner's voice measured on the attempt (F0, F1 to
F3, the fricative's centroid, F3 - F2, the duration, the verdict), never the audio.

Revision ID: 0011
Revises: 0010
Create Date: 2026-11-28
"""

import sqlalchemy as sa
from alembic import op

revision = "0011"
down_revision = "0010"
branch_labels = None
depends_on = None


def upgrade() -> None:
    with op.batch_alter_table("practice_records") as batch:
        batch.add_column(sa.Column("measures", sa.JSON(), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("practice_records") as batch:
        batch.drop_column("measures")
