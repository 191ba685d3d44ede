"""Tables of the Glasshead store.

Each resource is one mapped class with typed ``Mapped[]`` columns. Later resources (users,
classes, lessons, practice records) join this module or a sibling module imported here, with a
migration of their own; a practice record will point at ``epg_recordings.id`` and
``saved_poses.id`` with ordinary foreign keys.

EPG frames are stored as two compact blobs per recording rather than one row per frame: a
recording is always read and written whole (playback, export, comparison), frames are never
queried one at a time, and 8 bytes of contacts plus 8 bytes of time per frame is a small fraction
of what a row per frame costs (a 2-minute take at 200 Hz is 24,000 frames: 384 kB as blobs). The
blob layouts are fixed and little-endian, so SQLite and PostgreSQL hold identical bytes.
"""

import numpy as np
from sqlalchemy import JSON, Float, ForeignKey, Integer, LargeBinary, String, Text
from sqlalchemy.orm import Mapped, mapped_column

from glasshead.epg.sequence import EpgSequence, frames_to_raw, raw_to_frames
from glasshead.store.base import Base, Timestamped, Versioned

#: Layout of ``EpgRecording.contacts``: 8 bytes per frame in emuR's compressed EPG layout
#: (byte 0 = R8 ... byte 7 = R1; bit c = electrode column c + 1).
CONTACT_BYTES_PER_FRAME = 8
#: Layout of ``EpgRecording.times``: one little-endian float64 per frame, seconds.
TIME_DTYPE = np.dtype("<f8")


class EpgRecording(Versioned, Timestamped, Base):
    """A real EPG recording: frames with their own times and frame rate, and where it came from."""

    __tablename__ = "epg_recordings"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    #: The format it was imported from: emur-json, csv or ssff.
    source_format: Mapped[str] = mapped_column(String(20))
    #: Frames per second the recording was made at (None for a single frame of unknown rate).
    frame_rate_hz: Mapped[float | None] = mapped_column(Float)
    n_frames: Mapped[int] = mapped_column(Integer)
    #: Times of the first and last frame, seconds.
    first_t_s: Mapped[float] = mapped_column(Float)
    last_t_s: Mapped[float] = mapped_column(Float)
    contacts: Mapped[bytes] = mapped_column(LargeBinary)
    times: Mapped[bytes] = mapped_column(LargeBinary)
    #: Label, utterance, word, segment start_s/end_s and other fields the source file carried.
    meta: Mapped[dict] = mapped_column(JSON, default=dict)
    #: The child it was recorded from (deleted with them); None for a reference recording.
    child_id: Mapped[int | None] = mapped_column(
        ForeignKey("children.id", ondelete="CASCADE"), index=True)
    #: The user who imported it (None once that user is removed, and for older recordings).
    uploaded_by: Mapped[int | None] = mapped_column(
        ForeignKey("users.id", ondelete="SET NULL"), index=True)

    @classmethod
    def from_sequence(cls, sequence: EpgSequence, source_format: str) -> "EpgRecording":
        return cls(
            name=sequence.name,
            source_format=source_format,
            frame_rate_hz=sequence.frame_rate_hz,
            n_frames=sequence.n_frames,
            first_t_s=float(sequence.t_s[0]),
            last_t_s=float(sequence.t_s[-1]),
            contacts=frames_to_raw(sequence.frames).tobytes(),
            times=sequence.t_s.astype(TIME_DTYPE).tobytes(),
            meta=dict(sequence.meta),
        )

    def to_sequence(self) -> EpgSequence:
        raw = np.frombuffer(self.contacts, dtype=np.uint8).reshape(-1, CONTACT_BYTES_PER_FRAME)
        t_s = np.frombuffer(self.times, dtype=TIME_DTYPE).astype(np.float64)
        return EpgSequence(raw_to_frames(raw), t_s, self.name, self.frame_rate_hz,
                           dict(self.meta or {}))


class SavedPose(Versioned, Timestamped, Base):
    """A target: a named set of articulation parameters saved from the workbench.

    ``params`` maps parameter names (as in the tongue rig definition) to values in the rig's
    units. Phoneme targets carry the same shape of data, so views that show a saved pose can
    show a phoneme target instead.
    """

    __tablename__ = "saved_poses"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(120), unique=True)
    description: Mapped[str] = mapped_column(Text, default="")
    params: Mapped[dict] = mapped_column(JSON)
    #: The user who saved it (None once removed, and for poses saved before owners).
    owner_id: Mapped[int | None] = mapped_column(
        ForeignKey("users.id", ondelete="SET NULL"), index=True)


# Tables kept in sibling modules, imported here so that every table is on Base.metadata.
from glasshead.store.fit_jobs import FitJob  # noqa: E402, F401
from glasshead.store.idempotency_keys import IdempotencyKey  # noqa: E402, F401
from glasshead.store.lessons import (  # noqa: E402, F401
    Assignment,
    Child,
    Lesson,
    PracticeRecord,
    SchoolClass,
)
from glasshead.store.practice_audio import AudioRecordingSwitch, PracticeAudio  # noqa: E402, F401
from glasshead.store.users import (  # noqa: E402, F401
    AuthToken,
    ChildToken,
    SignInAttempt,
    User,
)
from glasshead.store.utterance_cache import CachedUtterance  # noqa: E402, F401
