"""Recording of a child's attempts: the clinician's switch, and the attempts' audio.

Nothing a child says leaves their device unless a clinician (or an admin) has switched
recording on for that child: ``PUT /children/{id}/audio-recording``. Each change is kept with
who made it and when, and ``GET`` answers the switch with its history, to the child's adults
and to the child's own device (which asks before it sends anything). While the switch is on,
``PUT /practice/{id}/audio`` stores the attempt's recording beside its practice record: a WAV
file, 16-bit PCM mono, 8 to 48 kHz, at most ``MAX_AUDIO_SECONDS``. While it is off the upload
is a 409 and nothing is stored. The audio is part of the child's export and deletion
(``child_records.py``); deleting the practice record deletes it.
"""

import io
import wave
from datetime import datetime
from typing import Annotated

from fastapi import APIRouter, Depends, HTTPException, Request, Response, status
from fastapi.concurrency import run_in_threadpool
from pydantic import BaseModel, ConfigDict
from sqlalchemy.orm import Session

from glasshead.api.auth import Person, allow, require_role
from glasshead.api.error_responses import Responses
from glasshead.api.lookups import RecordId
from glasshead.api.ownership import child_of, practice_for
from glasshead.store.lessons import Child
from glasshead.store.practice_audio import (
    AudioRecordingSwitch,
    PracticeAudio,
    recording_on,
    switch_history,
)
from glasshead.store.session import SessionDep
from glasshead.store.users import User

router = APIRouter(tags=["practice audio"])

#: The longest attempt kept, seconds.
MAX_AUDIO_SECONDS = 30
#: The sample rates taken, Hz (telephone to studio).
MIN_SAMPLE_RATE, MAX_SAMPLE_RATE = 8_000, 48_000
#: The largest body: the longest attempt at the highest rate (2.75 MiB), with room for a WAV's
#: extra chunks.
MAX_AUDIO_BYTES = 3 * 1024 * 1024
#: The media types a WAV file goes by.
WAV_TYPES = ("audio/wav", "audio/x-wav", "audio/wave", "audio/vnd.wave")

#: Who reads the switch and the audio: the child's adults, and the child.
Reader = Annotated[Person, Depends(allow("teacher", "clinician", "admin", "child"))]
#: Who sets the switch: a clinician of the child's class, or an admin.
Setter = Annotated[User, Depends(require_role("clinician", "admin"))]
#: Who deletes a recording: the child's adults.
Keeper = Annotated[Person, Depends(allow("teacher", "clinician", "admin"))]


class SwitchChange(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    enabled: bool
    set_by: int | None
    set_by_name: str
    set_at: datetime


class AudioRecordingState(BaseModel):
    """Whether an attempt's recording may leave the child's device, and who said so when."""

    child_id: int
    enabled: bool
    set_by: int | None
    set_by_name: str | None
    set_at: datetime | None
    history: list[SwitchChange]


class AudioRecordingIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [{"enabled": True}]})
    enabled: bool


class PracticeAudioOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    practice_id: int
    child_id: int
    sample_rate: int
    duration_s: float
    bytes: int
    created_at: datetime


def _state(session: Session, child: Child) -> AudioRecordingState:
    history = switch_history(session, child.id)
    last = history[0] if history else None
    return AudioRecordingState(
        child_id=child.id, enabled=bool(last and last.enabled),
        set_by=last.set_by if last else None, set_by_name=last.set_by_name if last else None,
        set_at=last.set_at if last else None,
        history=[SwitchChange.model_validate(change) for change in history])


@router.get("/children/{child_id}/audio-recording", operation_id="getAudioRecording",
            response_model=AudioRecordingState)
def get_audio_recording(child_id: RecordId, session: SessionDep,
                        person: Reader) -> AudioRecordingState:
    """Whether the child's attempts are recorded and kept, who set it when, and every change
    before. The child's device reads it before it sends any audio."""
    return _state(session, child_of(session, person, child_id))


@router.put("/children/{child_id}/audio-recording", operation_id="setAudioRecording",
            response_model=AudioRecordingState)
def set_audio_recording(child_id: RecordId, body: AudioRecordingIn, session: SessionDep,
                        user: Setter) -> AudioRecordingState:
    """Switch the recording of the child's attempts on or off (a clinician of the child's
    class, or an admin). Every change is kept with who made it and when; switching off keeps
    the recordings already made until they or the child's data are deleted."""
    child = child_of(session, Person(user=user), child_id)
    session.add(AudioRecordingSwitch(child_id=child.id, enabled=body.enabled, set_by=user.id,
                                     set_by_name=user.display_name))
    session.commit()
    return _state(session, child)


UPLOAD_RESPONSES: Responses = {
    409: {"description": "recording is off for the child: nothing is stored"},
    415: {"description": "the body is not sent as a WAV file (Content-Type audio/wav)"},
}


@router.put("/practice/{record_id}/audio", operation_id="putPracticeAudio",
            status_code=status.HTTP_201_CREATED, response_model=PracticeAudioOut,
            responses=UPLOAD_RESPONSES,
            openapi_extra={"requestBody": {"required": True, "content": {
                "audio/wav": {"schema": {"type": "string", "format": "binary"},
                              # The bytes themselves cannot be shown: what they are.
                              "example": "RIFF<size>WAVEfmt <PCM, 1 channel, 16000 Hz, 16-bit>"
                                         "data<samples>"}}}})
async def put_practice_audio(record_id: RecordId, request: Request, session: SessionDep,
                             person: Reader) -> PracticeAudioOut:
    """Keep the recording of an attempt with its practice record, while the child's recording
    is switched on: the raw bytes of a WAV file (16-bit PCM, mono, 8 to 48 kHz, at most 30 s).
    A second upload replaces the first."""
    content_type = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if content_type not in WAV_TYPES:
        raise HTTPException(status_code=415, detail="send the recording as a WAV file, "
                                                    "Content-Type: audio/wav")
    body = await request.body()
    # The database and the WAV's check off the event loop, as the sync routes run.
    return await run_in_threadpool(_keep_audio, session, person, record_id, body)


def _keep_audio(session: Session, person: Person, record_id: int,
                body: bytes) -> PracticeAudioOut:
    record = practice_for(session, person, record_id)
    if not recording_on(session, record.child_id):
        raise HTTPException(status_code=409, detail=f"recording is off for child "
                                                    f"{record.child_id}: a clinician switches "
                                                    f"it on (PUT /children/{record.child_id}"
                                                    "/audio-recording); nothing was stored")
    sample_rate, duration_s = check_wav(body)
    if record.audio is None:
        record.audio = PracticeAudio(child_id=record.child_id, sample_rate=sample_rate,
                                     duration_s=duration_s, wav=body)
    else:
        record.audio.sample_rate, record.audio.duration_s = sample_rate, duration_s
        record.audio.wav = body
    session.commit()
    audio = record.audio
    return PracticeAudioOut(practice_id=record.id, child_id=record.child_id,
                            sample_rate=audio.sample_rate, duration_s=audio.duration_s,
                            bytes=len(body), created_at=audio.created_at)


def check_wav(content: bytes) -> tuple[int, float]:
    """The sample rate and duration of a 16-bit PCM mono WAV file; a 422 naming the problem
    when it is not one, or is longer than MAX_AUDIO_SECONDS."""
    try:
        with wave.open(io.BytesIO(content), "rb") as reader:
            channels, width, rate, frames = (reader.getnchannels(), reader.getsampwidth(),
                                             reader.getframerate(), reader.getnframes())
    except (wave.Error, EOFError, ValueError) as error:
        raise HTTPException(status_code=422, detail=f"body: not a PCM WAV file ({error})") from None
    problems = [p for p, bad in (
        (f"{channels} channels, not 1 (mono)", channels != 1),
        (f"{8 * width}-bit samples, not 16-bit", width != 2),
        (f"{rate} Hz, not {MIN_SAMPLE_RATE} to {MAX_SAMPLE_RATE} Hz",
         not MIN_SAMPLE_RATE <= rate <= MAX_SAMPLE_RATE),
        ("no samples", frames == 0),
    ) if bad]
    if problems:
        raise HTTPException(status_code=422, detail="body: the WAV file has " +
                                                    ", ".join(problems))
    duration_s = frames / rate
    if duration_s > MAX_AUDIO_SECONDS:
        raise HTTPException(status_code=422, detail=f"body: the recording lasts "
                                                    f"{duration_s:.1f} s, more than "
                                                    f"{MAX_AUDIO_SECONDS} s")
    if len(content) < 44 + 2 * frames:
        raise HTTPException(status_code=422, detail="body: the WAV file is cut short: it "
                                                    f"declares {frames} samples")
    return rate, duration_s


def _audio_of(session: Session, person: Person, record_id: int) -> PracticeAudio:
    audio = practice_for(session, person, record_id).audio
    if audio is None:
        raise HTTPException(status_code=404, detail=f"practice record {record_id} has no "
                                                    "recording")
    return audio


@router.get("/practice/{record_id}/audio", operation_id="getPracticeAudio",
            response_class=Response, responses={200: {"content": {"audio/wav": {}}}})
def get_practice_audio(record_id: RecordId, session: SessionDep, person: Reader) -> Response:
    """The attempt's recording as it was kept (audio/wav); a 404 when it has none."""
    audio = _audio_of(session, person, record_id)
    return Response(audio.wav, media_type="audio/wav", headers={
        "Content-Disposition": f'attachment; filename="practice-{record_id}.wav"',
        "Cache-Control": "private, no-store"})


@router.delete("/practice/{record_id}/audio", operation_id="deletePracticeAudio",
               status_code=status.HTTP_204_NO_CONTENT)
def delete_practice_audio(record_id: RecordId, session: SessionDep, person: Keeper) -> Response:
    """Delete the attempt's recording; the practice record and its measures stay."""
    session.delete(_audio_of(session, person, record_id))
    session.commit()
    return Response(status_code=status.HTTP_204_NO_CONTENT)
