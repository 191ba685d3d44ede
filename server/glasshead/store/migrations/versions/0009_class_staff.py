"""Class staff: the adults a class is shared with besides its owner (a clinician who follows a
teacher's pupil, a second teacher), each once; removed with the class or with the user.

Revision ID: 0009
Revises: 0008
Create Date: 2026-11-25
"""

import sqlalchemy as sa
from alembic import op

revision = "0009"
down_revision = "0008"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "class_staff",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("class_id", sa.Integer(), nullable=False),
        sa.Column("user_id", sa.Integer(), nullable=False),
        sa.Column("added_at", sa.DateTime(timezone=True), nullable=False),
        sa.ForeignKeyConstraint(["class_id"], ["classes.id"], ondelete="CASCADE",
                                name=op.f("fk_class_staff_class_id_classes")),
        sa.ForeignKeyConstraint(["user_id"], ["users.id"], ondelete="CASCADE",
                                name=op.f("fk_class_staff_user_id_users")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_class_staff")),
        sa.UniqueConstraint("class_id", "user_id", name=op.f("uq_class_staff_class_id")),
    )
    op.create_index(op.f("ix_class_staff_class_id"), "class_staff", ["class_id"], unique=False)
    op.create_index(op.f("ix_class_staff_user_id"), "class_staff", ["user_id"], unique=False)


def downgrade() -> None:
    op.drop_index(op.f("ix_class_staff_user_id"), table_name="class_staff")
    op.drop_index(op.f("ix_class_staff_class_id"), table_name="class_staff")
    op.drop_table("class_staff")
