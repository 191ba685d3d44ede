"""Audio of practice attempts, kept only for a child whose clinician switched recording on.

By default nothing a child says leaves their device: a practice record keeps what the voice
measured, never the sound. A clinician (or an admin) may switch recording on for one child;
each change of that switch is a row of ``audio_recording_switches`` (who, when, on or off), so
that an audit shows who decided what. While it is on, each attempt's recording may be stored
beside its practice record in ``practice_audio`` (one WAV per record, 16-bit PCM mono). Both
tables go with the child: their export lists them and their deletion removes them
(``api/routes/child_records.py``); deleting a practice record deletes its audio.
"""

from datetime import datetime

from sqlalchemy import Boolean, Float, ForeignKey, Integer, LargeBinary, String, select
from sqlalchemy.orm import Mapped, Session, mapped_column

from glasshead.store.base import Base, UtcDateTime, utc_now
from glasshead.store.users import MAX_DISPLAY_NAME_LENGTH


class AudioRecordingSwitch(Base):
    """One change of a child's recording switch: on or off, by whom, when."""

    __tablename__ = "audio_recording_switches"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    child_id: Mapped[int] = mapped_column(ForeignKey("children.id", ondelete="CASCADE"),
                                          index=True)
    enabled: Mapped[bool] = mapped_column(Boolean)
    #: The clinician or admin who set it (None once that user is removed; the name stays).
    set_by: Mapped[int | None] = mapped_column(ForeignKey("users.id", ondelete="SET NULL"))
    set_by_name: Mapped[str] = mapped_column(String(MAX_DISPLAY_NAME_LENGTH))
    set_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)


def switch_history(session: Session, child_id: int, *, newest_first: bool = True
                   ) -> list[AudioRecordingSwitch]:
    """Every change of a child's recording switch, newest first (oldest first for an export)."""
    order = AudioRecordingSwitch.id.desc() if newest_first else AudioRecordingSwitch.id
    return list(session.scalars(select(AudioRecordingSwitch)
                                .where(AudioRecordingSwitch.child_id == child_id)
                                .order_by(order)))


def recording_on(session: Session, child_id: int) -> bool:
    """Whether the child's switch is on now: its last change switched it on."""
    return bool(session.scalar(select(AudioRecordingSwitch.enabled)
                               .where(AudioRecordingSwitch.child_id == child_id)
                               .order_by(AudioRecordingSwitch.id.desc()).limit(1)))


class PracticeAudio(Base):
    """The recording of one practice attempt (a WAV file), stored with the child's data."""

    __tablename__ = "practice_audio"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    practice_id: Mapped[int] = mapped_column(
        ForeignKey("practice_records.id", ondelete="CASCADE"), unique=True)
    child_id: Mapped[int] = mapped_column(ForeignKey("children.id", ondelete="CASCADE"),
                                          index=True)
    sample_rate: Mapped[int] = mapped_column(Integer)
    duration_s: Mapped[float] = mapped_column(Float)
    #: The WAV file as uploaded (checked to be 16-bit PCM mono); loaded only when asked for.
    wav: Mapped[bytes] = mapped_column(LargeBinary, deferred=True)
    created_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)
