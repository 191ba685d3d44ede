"""POST /utterances: text, phonemes or timed phones -> timed phones, tracks, cues and audio.

``POST /utterances/textgrid`` takes a Praat TextGrid upload as the file form of ``phones``;
``GET /utterances/{id}/audio.wav`` serves an utterance's audio. The work is in
``glasshead.speech.utterance`` (docs/speech.md); results are cached by a hash of the request and
of the phoneme targets, and a cached answer is the stored JSON as it was written. An answer
not in the cache is made in a compute worker (``jobs.compute``): espeak-ng and VocalTractLab are
native code, and a fault in them costs that one request (502, naming what it spoke), never the
server. The worker keeps what it made in the cache it is sent (``settings.utterance_cache``: a
directory on this machine, or the database, where every server on it finds it).
"""

import hashlib
import re
from typing import Annotated, Literal

from fastapi import APIRouter, File, Form, HTTPException, Request, Response, UploadFile
from fastapi.concurrency import run_in_threadpool
from fastapi.responses import FileResponse
from pydantic import BaseModel, ConfigDict, Field, model_validator

from glasshead.api.deps import AssetsDep, CacheDep, ComputeDep, open_cache
from glasshead.asset_store import AssetStore
from glasshead.flesh_point_assets import FLESH_POINT_ASSETS, flesh_point_rig
from glasshead.geometry.flesh_points import FLESH_POINT_NAMES
from glasshead.jobs.compute import ComputePool
from glasshead.speech import audio, tract_voice, utterance
from glasshead.speech.espeak import EspeakUnavailableError
from glasshead.speech.pronounce import MAX_TEXT_CHARS
from glasshead.speech.textgrid import TextGridError, read_textgrid
from glasshead.tract_assets import TRACT_ASSETS, tract_shape

router = APIRouter(tags=["utterances"])

#: Largest TextGrid accepted, bytes.
MAX_TEXTGRID_BYTES = 1024 * 1024
#: The documented example: "sip" after 50 ms of silence, in Praat's short text format.
TEXTGRID_EXAMPLE = ('File type = "ooTextFile"\nObject class = "TextGrid"\n\n0\n0.5\n<exists>\n1\n'
                    '"IntervalTier"\n"phones"\n0\n0.5\n4\n0\n0.05\n""\n0.05\n0.22\n"s"\n'
                    '0.22\n0.34\n"ɪ"\n0.34\n0.5\n"p"\n')
AudioKind = Literal["natural", "lowpass", "vocoded", "none", "articulatory", "tract"]
FleshPoint = Literal[FLESH_POINT_NAMES]
Rate = Field(1.0, ge=0.5, le=2.0, description="speaking rate: 1 is espeak-ng's 175 words a "
                                              "minute; timed phones are divided by it")


class AudioOptions(BaseModel):
    kind: AudioKind = Field("natural", description="natural (espeak-ng), lowpass (hearing "
                            "loss), vocoded (cochlear implant), none, articulatory "
                            "(VocalTractLab's JD3 speaker), or tract (the head's own tract "
                            "through VocalTractLab's tube synthesis)")
    cutoff_hz: float = Field(audio.DEFAULT_CUTOFF_HZ, ge=audio.CUTOFF_RANGE_HZ[0],
                             le=audio.CUTOFF_RANGE_HZ[1], description="lowpass: the cut-off")
    channels: int = Field(audio.DEFAULT_CHANNELS, ge=audio.CHANNEL_RANGE[0],
                          le=audio.CHANNEL_RANGE[1], description="vocoded: the channels")


class PhoneIn(BaseModel):
    symbol: str = Field(description="ARPAbet or IPA; sil (or empty) for silence")
    start_s: float
    end_s: float


class UtteranceRequest(BaseModel):
    """Exactly one of ``text``, ``phonemes`` and ``phones``."""

    model_config = ConfigDict(json_schema_extra={"examples": [
        {"text": "Ted and Kim bring a pink map."},
        {"phonemes": "ʃ ɪ p", "rate": 0.75, "audio": {"kind": "lowpass", "cutoff_hz": 1000.0}},
        {"phones": [{"symbol": "sil", "start_s": 0.0, "end_s": 0.05},
                    {"symbol": "s", "start_s": 0.05, "end_s": 0.22},
                    {"symbol": "ɪ", "start_s": 0.22, "end_s": 0.34},
                    {"symbol": "p", "start_s": 0.34, "end_s": 0.5}],
         "audio": {"kind": "none"}}]})
    text: str | None = Field(None, min_length=1, max_length=MAX_TEXT_CHARS,
                             description="English text")
    phonemes: list[str] | str | None = Field(
        None, description="IPA or ARPAbet symbols: a list, or one string separated by spaces")
    phones: list[PhoneIn] | None = Field(None, description="phones with their own timings")
    rate: float = Rate
    audio: AudioOptions = Field(default_factory=AudioOptions)
    dominance: bool = Field(False, description="also send each phone's dominance curves, per "
                                               "group of parameters (the player plots them)")
    flesh_points: bool = Field(False, description="also send the tracks of the points where "
                               "articulography puts its sensors (tongue, incisors, lips)")

    @model_validator(mode="after")
    def one_input(self):
        given = [n for n in ("text", "phonemes", "phones") if getattr(self, n) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of text, phonemes and phones"
                             + (f" (got {', '.join(given)})" if given else ""))
        if self.text is not None and not self.text.strip():
            raise ValueError("text is empty")
        return self


class PhoneOut(BaseModel):
    symbol: str = Field(description="ARPAbet without stress digit, or sil")
    ipa: str | None
    stress: int | None
    word: str | None
    start_s: float
    end_s: float


class WordOut(BaseModel):
    text: str
    source: str | None = Field(description="cmudict or espeak-ng")
    start_s: float
    end_s: float


class Utterance(BaseModel):
    id: str = Field(description="content hash of the request and the phoneme targets")
    phones: list[PhoneOut]
    words: list[WordOut]
    duration_s: float
    rate: float
    rate_hz: float = Field(description="frames per second of the tracks and cues")
    n_frames: int
    tracks: dict[str, list[float]] = Field(description="every articulation parameter, "
                                                       "frame i at t = i / rate_hz")
    cues: dict[str, list[float]] = Field(description="voicing, nasal_airflow, frication; 0..1")
    audio: dict
    audio_url: str | None
    voice: str | None = Field(description="what made the audio, e.g. espeak-ng en-us, "
                                          "VocalTractLab JD3; null without audio")
    warnings: list[str] = Field(description="e.g. the words that could not be pronounced")
    dominance: dict | None = Field(None, description="with dominance: true, {groups: {group: "
                                   "[[float] * n_frames per phone]}, parameters: {parameter: "
                                   "group}}")
    flesh_points: dict[FleshPoint, list[list[float]]] | None = Field(
        None, description="with flesh_points: true, {point: [[x, y, z] * n_frames]}, mm in the "
        "project frame (x anterior, y up, z left): the tongue's tip (10 mm behind the apex), "
        "blade, dorsum and back (25, 40 and 55 mm) on its upper mid-sagittal outline before the "
        "collision correction, the lower incisor's edge moved by the jaw, the lips' vermilion "
        "midpoints posed by the face rig, and the upper incisor's edge (fixed)")


def content_key(store: AssetStore, request: dict) -> str:
    """What the answer to ``request`` is made from, as the cache key takes it: the phoneme
    targets' hash, or with ``flesh_points`` or the ``tract`` voice a hash of it and of every
    asset the points or the tract read."""
    targets = store.entry("phoneme_targets").sha256
    names = list(FLESH_POINT_ASSETS) if request.get("flesh_points") else []
    if request["audio"]["kind"] == "tract":
        names += [n for n in FLESH_POINT_ASSETS + TRACT_ASSETS if n not in names]
    if not names:
        return targets
    hashes = [targets] + [store.entry(name).sha256 for name in names]
    return hashlib.sha256("\0".join(hashes).encode()).hexdigest()


def speak(store: AssetStore, payload: dict) -> bytes:
    """In a compute worker: the utterance's JSON (``utterance.make``), made and kept in the
    cache the payload names (``cache_dir`` or ``database_url``, as ``open_cache`` takes)."""
    request = payload["request"]
    entry = store.entry("phoneme_targets")

    def flesh(tracks):  # prepared only when the answer is not cached
        return flesh_point_rig(store).tracks(tracks)

    def tract(tracks, rate_hz, phones):
        return tract_voice.speak(tract_shape(store), tracks, rate_hz, phones)

    try:
        return utterance.make(request, entry.value, content_key(store, request),
                              open_cache(payload),
                              flesh_points=flesh if request.get("flesh_points") else None,
                              tract_voice=tract)
    except utterance.UtteranceInputError as exc:
        raise HTTPException(status_code=422, detail=str(exc)) from None
    except EspeakUnavailableError as exc:
        raise HTTPException(status_code=503, detail=str(exc)) from None


def _speaking(request: dict) -> str:
    """What a worker speaking ``request`` was doing, for an error that names the input."""
    if request.get("text") is not None:
        text = request["text"]
        return f"speaking the text {text[:80] + ('…' if len(text) > 80 else '')!r}"
    if request.get("phonemes") is not None:
        phonemes = request["phonemes"]
        shown = phonemes if isinstance(phonemes, str) else " ".join(phonemes)
        return f"speaking the phonemes {shown[:80]!r}"
    return f"speaking {len(request['phones'])} timed phones"


async def _respond(request: dict, assets: AssetStore, cache: utterance.UtteranceCache,
                   compute: ComputePool) -> Response:
    hit = await run_in_threadpool(utterance.cached_answer, request,
                                  content_key(assets, request), cache)
    if hit is not None:
        return Response(content=hit, media_type="application/json")
    return await compute.respond(speak, {"request": request, **cache.location},
                                 doing=_speaking(request))


@router.post("/utterances", operation_id="createUtterance", response_model=Utterance)
async def create_utterance(body: UtteranceRequest, assets: AssetsDep, cache: CacheDep,
                           compute: ComputeDep) -> Response:
    """Speak text, phonemes (IPA or ARPAbet) or timed phones: the phones with their times, the
    coarticulated tracks and cues, and the audio's URL; with ``flesh_points``, also the tracks
    of the EMA sensor points on the rig."""
    return await _respond(body.model_dump(mode="json"), assets, cache, compute)


@router.post("/utterances/textgrid", operation_id="createUtteranceFromTextGrid",
             response_model=Utterance,
             openapi_extra={"requestBody": {"content": {"multipart/form-data": {"example": {
                 "file": TEXTGRID_EXAMPLE, "rate": 1.0, "audio_kind": "none"}}}}})
async def create_utterance_from_textgrid(
    assets: AssetsDep,
    cache: CacheDep,
    compute: ComputeDep,
    file: Annotated[UploadFile, File(description="a Praat TextGrid; its first interval tier")],
    rate: Annotated[float, Form(ge=0.5, le=2.0)] = 1.0,
    audio_kind: Annotated[AudioKind, Form()] = "none",
    cutoff_hz: Annotated[float, Form(ge=audio.CUTOFF_RANGE_HZ[0],
                                     le=audio.CUTOFF_RANGE_HZ[1])] = audio.DEFAULT_CUTOFF_HZ,
    channels: Annotated[int, Form(ge=audio.CHANNEL_RANGE[0],
                                  le=audio.CHANNEL_RANGE[1])] = audio.DEFAULT_CHANNELS,
) -> Response:
    """The phones of a TextGrid's first interval tier (empty labels are silence), spoken as
    ``POST /utterances`` speaks ``phones``."""
    data = await file.read(MAX_TEXTGRID_BYTES + 1)
    if len(data) > MAX_TEXTGRID_BYTES:
        raise HTTPException(status_code=413, detail=f"a TextGrid may be at most "
                                                    f"{MAX_TEXTGRID_BYTES} bytes")
    try:
        phones = read_textgrid(data)
    except TextGridError as exc:
        raise HTTPException(status_code=422, detail=f"file: {exc}") from None
    body = UtteranceRequest(phones=phones, rate=rate,
                            audio={"kind": audio_kind, "cutoff_hz": cutoff_hz,
                                   "channels": channels})
    return await _respond(body.model_dump(mode="json"), assets, cache, compute)


@router.get("/utterances/{utterance_id}/audio.wav", operation_id="getUtteranceAudio",
            response_class=FileResponse)
def get_utterance_audio(utterance_id: str, cache: CacheDep, request: Request) -> Response:
    """The WAV of an utterance made before (16-bit mono), by this server or any other that
    shares its cache; a ``Range`` of bytes is answered 206."""
    if isinstance(cache, utterance.DirectoryCache):
        path = cache.audio_path(utterance_id)
        if path is not None:
            return FileResponse(path, media_type="audio/wav")
        data = None
    else:
        data = cache.audio(utterance_id) if utterance.is_id(utterance_id) else None
    if data is None:
        raise HTTPException(status_code=404, detail=f"no audio for utterance {utterance_id!r}; "
                                                    "POST /api/v1/utterances makes it")
    return byte_range_response(data, "audio/wav", request.headers.get("range"))


def byte_range_response(data: bytes, media_type: str, range_header: str | None) -> Response:
    """``data`` whole (200), or the one range ``bytes=first-last``, ``first-`` or ``-suffix``
    asks for (206 with Content-Range; 416 when it starts past the end), as a media element
    seeking in the audio asks. Several ranges, or a header not understood, get it whole."""
    headers = {"Accept-Ranges": "bytes"}
    size = len(data)
    match = re.fullmatch(r"\s*bytes\s*=\s*(\d*)\s*-\s*(\d*)\s*", range_header or "")
    if match is None or match.groups() == ("", ""):
        return Response(data, media_type=media_type, headers=headers)
    first, last = match.groups()
    if first and last and int(last) < int(first):  # not a valid range: ignored
        return Response(data, media_type=media_type, headers=headers)
    if first == "":  # the last ``suffix`` bytes
        start, end = max(0, size - int(last)), size - 1
    else:
        start, end = int(first), min(int(last), size - 1) if last else size - 1
    if start >= size or start > end:
        raise HTTPException(status_code=416,
                            headers={**headers, "Content-Range": f"bytes */{size}"},
                            detail=f"the range {range_header!r} starts past the audio's "
                                   f"{size} bytes")
    return Response(data[start:end + 1], status_code=206, media_type=media_type,
                    headers={**headers, "Content-Range": f"bytes {start}-{end}/{size}"})
