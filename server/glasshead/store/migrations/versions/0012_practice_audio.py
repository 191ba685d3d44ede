"""Audio of practice attempts, kept only while a clinician's switch for the child is on, and
the history of that switch (store/practice_audio.py).

Revision ID: 0012
Revises: 0011
Create Date: 2026-11-28
"""

import sqlalchemy as sa
from alembic import op

revision = "0012"
down_revision = "0011"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "audio_recording_switches",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("child_id", sa.Integer(), nullable=False),
        sa.Column("enabled", sa.Boolean(), nullable=False),
        sa.Column("set_by", sa.Integer(), nullable=True),
        sa.Column("set_by_name", sa.String(length=120), nullable=False),
        sa.Column("set_at", sa.DateTime(timezone=True), nullable=False),
        sa.ForeignKeyConstraint(["child_id"], ["children.id"], ondelete="CASCADE",
                                name=op.f("fk_audio_recording_switches_child_id_children")),
        sa.ForeignKeyConstraint(["set_by"], ["users.id"], ondelete="SET NULL",
                                name=op.f("fk_audio_recording_switches_set_by_users")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_audio_recording_switches")),
    )
    op.create_index(op.f("ix_audio_recording_switches_child_id"), "audio_recording_switches",
                    ["child_id"], unique=False)
    op.create_table(
        "practice_audio",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("practice_id", sa.Integer(), nullable=False),
        sa.Column("child_id", sa.Integer(), nullable=False),
        sa.Column("sample_rate", sa.Integer(), nullable=False),
        sa.Column("duration_s", sa.Float(), nullable=False),
        sa.Column("wav", sa.LargeBinary(), nullable=False),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.ForeignKeyConstraint(["child_id"], ["children.id"], ondelete="CASCADE",
                                name=op.f("fk_practice_audio_child_id_children")),
        sa.ForeignKeyConstraint(["practice_id"], ["practice_records.id"], ondelete="CASCADE",
                                name=op.f("fk_practice_audio_practice_id_practice_records")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_practice_audio")),
        sa.UniqueConstraint("practice_id", name=op.f("uq_practice_audio_practice_id")),
    )
    op.create_index(op.f("ix_practice_audio_child_id"), "practice_audio", ["child_id"],
                    unique=False)


def downgrade() -> None:
    op.drop_index(op.f("ix_practice_audio_child_id"), table_name="practice_audio")
    op.drop_table("practice_audio")
    op.drop_index(op.f("ix_audio_recording_switches_child_id"),
                  table_name="audio_recording_switches")
    op.drop_table("audio_recording_switches")
