"""Tables for lessons and the people who practise them: classes, children, lessons,
assignments and practice records, and the adults a class is shared with (its staff).

Children are pseudonymous: a display name and an avatar id from a fixed list, nothing else (no
birth date, email address or real name is asked for or stored). A lesson's items are one JSON
list, because a lesson is always read and written whole and its items are ordered; a practice
record names its item by its position in that list. Every table is ``Versioned`` (an ETag per
record; ids never reused).
"""

from datetime import datetime

from sqlalchemy import JSON, CheckConstraint, ForeignKey, Integer, String, UniqueConstraint
from sqlalchemy.orm import Mapped, mapped_column, relationship

from glasshead.lessons.schema import DESCRIPTION_MAX_CHARS, LANGUAGE_MAX_CHARS, TITLE_MAX_CHARS
from glasshead.store.base import Base, Timestamped, UtcDateTime, Versioned, utc_now
from glasshead.store.practice_audio import PracticeAudio

#: The avatars a child may pick (icons in the web app, named so that no reading is needed).
AVATARS = ("cat", "dog", "fox", "owl", "frog", "bear", "fish", "bird", "rabbit", "turtle",
           "lion", "panda")
#: Join codes: six characters without the look-alikes 0/O, 1/I/L, 2/Z, 5/S, 8/B.
JOIN_CODE_ALPHABET = "34679ACDEFGHJKMNPQRTUVWXY"
JOIN_CODE_LENGTH = 6


class SchoolClass(Versioned, Timestamped, Base):
    """A class (or a clinician's caseload); children join it with its code."""

    __tablename__ = "classes"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(120))
    join_code: Mapped[str] = mapped_column(String(JOIN_CODE_LENGTH), unique=True)
    #: The teacher or clinician who made it; only they (and admins) see it and its children.
    owner_id: Mapped[int | None] = mapped_column(
        ForeignKey("users.id", ondelete="SET NULL"), index=True)


class ClassStaff(Base):
    """An adult a class is shared with: a clinician who follows a teacher's pupil, or a second
    teacher. They reach the class and its children as its owner does, but neither delete the
    class nor change who it is shared with (``api/ownership.py``)."""

    __tablename__ = "class_staff"
    __table_args__ = (UniqueConstraint("class_id", "user_id"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    class_id: Mapped[int] = mapped_column(ForeignKey("classes.id", ondelete="CASCADE"),
                                          index=True)
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"), index=True)
    added_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)


class Child(Versioned, Timestamped, Base):
    """A child in a class, known by a display name and an avatar only."""

    __tablename__ = "children"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    class_id: Mapped[int] = mapped_column(ForeignKey("classes.id", ondelete="CASCADE"),
                                          index=True)
    display_name: Mapped[str] = mapped_column(String(40))
    avatar: Mapped[str] = mapped_column(String(20))


class Lesson(Versioned, Timestamped, Base):
    """A lesson: a title, a language and its ordered items (``glasshead.lessons.schema``)."""

    __tablename__ = "lessons"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    title: Mapped[str] = mapped_column(String(TITLE_MAX_CHARS))
    language: Mapped[str] = mapped_column(String(LANGUAGE_MAX_CHARS))
    #: Written whole from a validated lesson, which has its format's defaults filled in.
    description: Mapped[str] = mapped_column(String(DESCRIPTION_MAX_CHARS))
    items: Mapped[list] = mapped_column(JSON)
    #: The author who made it; None for the starter lessons (and once the author is removed).
    owner_id: Mapped[int | None] = mapped_column(
        ForeignKey("users.id", ondelete="SET NULL"), index=True)


class Assignment(Versioned, Timestamped, Base):
    """A lesson given to a whole class or to one child (exactly one of the two)."""

    __tablename__ = "assignments"
    __table_args__ = (
        CheckConstraint("(class_id IS NULL) <> (child_id IS NULL)", name="one_assignee"),
        {"sqlite_autoincrement": True},
    )

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    lesson_id: Mapped[int] = mapped_column(ForeignKey("lessons.id", ondelete="CASCADE"),
                                           index=True)
    class_id: Mapped[int | None] = mapped_column(ForeignKey("classes.id", ondelete="CASCADE"),
                                                 index=True)
    child_id: Mapped[int | None] = mapped_column(ForeignKey("children.id", ondelete="CASCADE"),
                                                 index=True)


class PracticeRecord(Versioned, Timestamped, Base):
    """One go at one item of a lesson: when, how many replays, and a rating by whom."""

    __tablename__ = "practice_records"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    child_id: Mapped[int] = mapped_column(ForeignKey("children.id", ondelete="CASCADE"),
                                          index=True)
    lesson_id: Mapped[int] = mapped_column(ForeignKey("lessons.id", ondelete="CASCADE"),
                                           index=True)
    #: The item's position in the lesson's items, from 0.
    item_index: Mapped[int] = mapped_column(Integer)
    practised_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)
    replays: Mapped[int] = mapped_column(Integer, default=0)
    #: 1 (not yet) to 3 (got it), or None when nobody rated it.
    rating: Mapped[int | None] = mapped_column(Integer)
    #: "child" or "adult", or None with no rating.
    rated_by: Mapped[str | None] = mapped_column(String(10))
    #: What the learner's voice measured on this go ({f0, f1, f2, f3, f3_minus_f2, centroid,
    #: duration_s, verdict, target_vowel}), or None when nothing listened. Never the audio.
    measures: Mapped[dict | None] = mapped_column(JSON)
    #: The attempt's recording, when the child's clinician keeps them (store/practice_audio.py);
    #: loaded with the record, its WAV bytes only when read.
    audio: Mapped[PracticeAudio | None] = relationship(
        lazy="selectin", cascade="all, delete-orphan", passive_deletes=True)

    @property
    def has_audio(self) -> bool:
        return self.audio is not None
