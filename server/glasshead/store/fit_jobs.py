"""The ``fit_jobs`` table: an author's observation, the fit's state and progress, and its result.

A fit runs in a worker process (``glasshead.jobs.fit_job``), never in a request; this row is all
the request and the worker share, and the rows in state ``queued`` are the queue every server
takes jobs from (``glasshead.jobs.fit_queue``). A server with a free worker moves a row from
``queued`` to ``running``; its worker moves it on to ``done`` (``params`` and ``report`` set) or
``failed`` (``message`` set), and writes ``progress`` a few times a second while it runs. A
finished fit is a target: ``params`` holds a value for every articulation parameter (tongue,
jaw, lips, velum), as a saved pose does.

The observation is kept as one little-endian float64 blob (``observation_shape`` gives its
shape): a contour (n, 2), a surface's vertices (k, 3), a wanted EPG pattern and its weights
(2, 8, 8) or flesh points (k, 4); a combined fit's parts one after another, ``observation_shape``
then ``[[kind, shape], ...]`` in that order. A
surface of a few hundred thousand vertices is a few megabytes this way, several times less than
as JSON numbers, and the worker reads it back exactly.
"""

from datetime import datetime

import numpy as np
from sqlalchemy import JSON, ForeignKey, Integer, LargeBinary, String, Text
from sqlalchemy.orm import Mapped, mapped_column

from glasshead.store.base import Base, Timestamped, UtcDateTime

#: The states of a fit, in the order it passes through them (``failed`` may follow any).
FIT_STATES = ("queued", "running", "done", "failed")
#: The kinds of observation a fit takes.
FIT_KINDS = ("contour", "surface", "epg", "ema", "combined")
#: Layout of ``FitJob.observation``.
OBSERVATION_DTYPE = np.dtype("<f8")


class FitJob(Timestamped, Base):
    """One fit of the tongue to an uploaded observation, and the target it made."""

    __tablename__ = "fit_jobs"
    #: A deleted fit's id is never given to a new one (a stale link must not open another's).
    __table_args__ = {"sqlite_autoincrement": True}

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    #: contour, surface, epg, ema or combined (``FIT_KINDS``).
    kind: Mapped[str] = mapped_column(String(20))
    #: The optimiser: bobyqa, praxis or sbplx.
    method: Mapped[str] = mapped_column(String(20))
    #: queued, running, done or failed (``FIT_STATES``).
    state: Mapped[str] = mapped_column(String(20), index=True, default="queued")
    #: Why a fit failed (None otherwise).
    message: Mapped[str | None] = mapped_column(Text)
    #: ``{evaluations, best_error, fraction}`` while running; the last values once finished.
    progress: Mapped[dict] = mapped_column(JSON, default=dict)
    observation: Mapped[bytes] = mapped_column(LargeBinary)
    observation_shape: Mapped[list] = mapped_column(JSON)
    #: What the upload said beside the numbers: file name, format, frames, options of the fit.
    source: Mapped[dict] = mapped_column(JSON, default=dict)
    #: The fitted target: every rig parameter by name (None until done).
    params: Mapped[dict | None] = mapped_column(JSON)
    #: rms_mm, evaluations, seconds, volume_change_pct, at_limit, method and per-kind figures.
    report: Mapped[dict | None] = mapped_column(JSON)
    started_at: Mapped[datetime | None] = mapped_column(UtcDateTime())
    finished_at: Mapped[datetime | None] = mapped_column(UtcDateTime())
    #: The user who uploaded the observation (None once removed, and for older fits).
    owner_id: Mapped[int | None] = mapped_column(
        ForeignKey("users.id", ondelete="SET NULL"), index=True)

    def set_observation(self, points: np.ndarray | dict[str, np.ndarray]) -> None:
        if isinstance(points, dict):
            parts = {k: np.ascontiguousarray(v, dtype=OBSERVATION_DTYPE) for k, v in points.items()}
            self.observation = b"".join(part.tobytes() for part in parts.values())
            self.observation_shape = [[k, list(part.shape)] for k, part in parts.items()]
            return
        points = np.ascontiguousarray(points, dtype=OBSERVATION_DTYPE)
        self.observation = points.tobytes()
        self.observation_shape = list(points.shape)

    def get_observation(self) -> np.ndarray | dict[str, np.ndarray]:
        flat = np.frombuffer(self.observation, dtype=OBSERVATION_DTYPE).astype(np.float64)
        shape = self.observation_shape
        if not shape or not isinstance(shape[0], list):
            return flat.reshape(shape)
        parts, start = {}, 0
        for kind, part_shape in shape:
            size = int(np.prod(part_shape))
            parts[str(kind)] = flat[start:start + size].reshape(part_shape)
            start += size
        return parts
