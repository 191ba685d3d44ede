"""An utterance: text, phonemes or timed phones -> timed phones, audio and coarticulated tracks.

The three inputs meet in one list of timed phones:

- text: ``pronounce`` (CMUdict, espeak-ng), then one espeak-ng synthesis times the phones; the
  natural voice (``neural_voice``, for the natural, low-pass and vocoded audio) says the text
  and the phones are moved onto its clock by aligning the two syntheses (``align``); with it
  missing or failing, espeak-ng's audio stands;
- phonemes (IPA or ARPAbet): the same synthesis of exactly those phones;
- phones with ``start_s``/``end_s`` (a forced alignment, a TextGrid): taken as given, divided by
  the rate; the espeak-ng voice, when asked for, is synthesised and stretched phone by phone onto
  those times (``audio.retime``: each phone keeps its pitch and spectrum).

The tracks and cues come from ``speech.coarticulation.coarticulate`` on the phones and the built
phoneme targets. The result is cached under an id that is a hash of the request's content, the
targets' content hash, the coarticulation constants and ``FORMAT_VERSION``: the same request on
the same targets and constants is read back, not made again. The cache is given to ``make`` as
an object with ``answer``, ``audio`` and ``put``: a ``DirectoryCache`` (``<id>.json`` and
``<id>.wav`` in ``speech_cache_dir``, on this machine's disk) or the database's
(``store.utterance_cache.DatabaseCache``, shared by every server on the database).
"""

import hashlib
import io
import json
import os
import re
import wave
from pathlib import Path
from typing import Protocol

from glasshead.phonemes import UnknownPhonemeError, lookup
from glasshead.speech import align, audio, espeak, neural_voice, vtl_voice
from glasshead.speech.espeak_phones import PAUSE, VOWELS
from glasshead.speech.pronounce import pronounce
from glasshead.speech.tract_voice import VOICE as TRACT_VOICE

#: Bump when the response changes for the same request.
FORMAT_VERSION = 5
#: The tracks' frame rate, Hz.
RATE_HZ = 100.0
#: The audio kinds made from the natural voice (the neural one for text; espeak-ng otherwise).
NEURAL_KINDS = ("natural", "lowpass", "vocoded")
#: Phone times are compared with this tolerance, s (a TextGrid's boundaries are written rounded).
TIME_TOLERANCE_S = 1e-6
_PAUSE_SYMBOLS = {"sil", "sp", "spn", "_", ""}


class UtteranceInputError(ValueError):
    """The request cannot be spoken; the message names the problem (answered with 422)."""


def request_id(request: dict, targets_sha256: str) -> str:
    """The cache key: a hash of the request's content (keys sorted), the targets' hash, the
    coarticulation constants in use and the format version; 24 hex digits."""
    from glasshead.speech.dominance import load_constants

    canonical = json.dumps(request, sort_keys=True, separators=(",", ":"), ensure_ascii=False)
    constants = json.dumps(load_constants(), sort_keys=True)
    digest = hashlib.sha256(
        f"{FORMAT_VERSION}\0{targets_sha256}\0{constants}\0{canonical}".encode())
    return digest.hexdigest()[:24]


def is_id(text: str) -> bool:
    """Whether ``text`` has the form of an utterance id (24 hex digits)."""
    return re.fullmatch(r"[0-9a-f]{24}", text) is not None


class UtteranceCache(Protocol):
    """Where made utterances are kept, by id: the response's JSON bytes and its WAV."""

    #: What a compute worker is sent to open the same cache (``cache_dir`` or ``database_url``).
    location: dict

    def answer(self, utterance_id: str, *, with_audio: bool = False) -> bytes | None: ...

    def audio(self, utterance_id: str) -> bytes | None: ...

    def put(self, utterance_id: str, answer: bytes, wav: bytes | None) -> None: ...


class DirectoryCache:
    """The cache as files in ``directory``: ``<id>.json`` and ``<id>.wav``, each written to a
    temporary name and renamed, the WAV first, so that a reader never sees half a file."""

    def __init__(self, directory):
        self.directory = Path(directory)

    @property
    def location(self) -> dict:
        return {"cache_dir": str(self.directory)}

    def answer(self, utterance_id: str, *, with_audio: bool = False) -> bytes | None:
        """The cached response's JSON bytes, or None (with ``with_audio``: also None when its
        WAV is missing)."""
        if not is_id(utterance_id):
            return None
        try:
            data = (self.directory / f"{utterance_id}.json").read_bytes()
        except FileNotFoundError:
            return None
        return None if with_audio and self.audio_path(utterance_id) is None else data

    def audio_path(self, utterance_id: str) -> Path | None:
        """The cached WAV of an utterance, or None (unknown id, or an utterance without
        audio)."""
        if not is_id(utterance_id):
            return None
        path = self.directory / f"{utterance_id}.wav"
        return path if path.is_file() else None

    def audio(self, utterance_id: str) -> bytes | None:
        path = self.audio_path(utterance_id)
        try:
            return None if path is None else path.read_bytes()
        except FileNotFoundError:
            return None

    def put(self, utterance_id: str, answer: bytes, wav: bytes | None) -> None:
        self.directory.mkdir(parents=True, exist_ok=True)
        if wav is not None:
            _write_atomic(self.directory / f"{utterance_id}.wav", wav)
        _write_atomic(self.directory / f"{utterance_id}.json", answer)


def _write_atomic(path: Path, data: bytes) -> None:
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    temporary.write_bytes(data)
    os.replace(temporary, path)


def wav_bytes(samples, sample_rate: int) -> bytes:
    """A mono 16-bit PCM WAV file of (n,) samples (int16, or float in -1..1), as
    ``audio.write_wav`` writes it."""
    import numpy as np

    buffer = io.BytesIO()
    with wave.open(buffer, "wb") as out:
        out.setnchannels(1)
        out.setsampwidth(2)
        out.setframerate(int(sample_rate))
        out.writeframes(audio.to_int16(np.asarray(samples)).astype("<i2").tobytes())
    return buffer.getvalue()


def parse_phonemes(phonemes: list[str] | str) -> list[tuple[str, int | None]]:
    """Symbols (a list, or one string separated by spaces) in IPA or ARPAbet as (ARPAbet, stress);
    an ARPAbet stress digit or an IPA stress mark (ˈ ˌ) is kept; "sil" is a pause."""
    symbols = phonemes.split() if isinstance(phonemes, str) else list(phonemes)
    if not symbols:
        raise UtteranceInputError("phonemes: at least one phoneme is needed")
    return [_parse_symbol(s, f"phonemes[{k}]") for k, s in enumerate(symbols)]


def _parse_symbol(symbol, where: str) -> tuple[str, int | None]:
    text = str(symbol).strip()
    if text.lower() in _PAUSE_SYMBOLS:
        return PAUSE, None
    stress = None
    if text[:1] in "ˈˌ":
        stress, text = (1 if text[0] == "ˈ" else 2), text[1:]
    text = text.replace("ː", "")
    if text[-1:] in "012" and len(text) > 1:
        stress = int(text[-1])
    try:
        phoneme = lookup(text)
    except UnknownPhonemeError as exc:
        raise UtteranceInputError(f"{where}: {exc}") from None
    return phoneme.arpabet, (stress if phoneme.arpabet in VOWELS else None)


def parse_phones(phones: list[dict], rate: float) -> list[dict]:
    """Timed phones checked (known symbols; each starts before it ends, at or after 0 and after
    the one before it ends) and their times divided by ``rate``; a gap before or between phones
    becomes a silence, so that the phones cover the utterance from 0."""
    if not phones:
        raise UtteranceInputError("phones: at least one phone is needed")
    out, previous_end = [], 0.0
    for k, phone in enumerate(phones):
        symbol, stress = _parse_symbol(phone["symbol"], f"phones[{k}].symbol")
        start, end = float(phone["start_s"]), float(phone["end_s"])
        if start < -TIME_TOLERANCE_S:
            raise UtteranceInputError(f"phones[{k}] ({phone['symbol']}) starts before 0 s")
        if end <= start:
            raise UtteranceInputError(f"phones[{k}] ({phone['symbol']}) runs backwards: it ends "
                                      f"at {end} s, not after its start at {start} s")
        if start < previous_end - TIME_TOLERANCE_S:
            raise UtteranceInputError(f"phones[{k}] ({phone['symbol']}) starts at {start} s, "
                                      f"overlapping the phone before, which ends at "
                                      f"{previous_end} s")
        if start > previous_end + TIME_TOLERANCE_S:  # a gap is silence
            out.append({"symbol": PAUSE, "stress": None, "start_s": previous_end / rate,
                        "end_s": start / rate, "word": None})
        previous_end = end
        out.append({"symbol": symbol, "stress": phone.get("stress", stress),
                    "start_s": max(start, 0.0) / rate, "end_s": end / rate, "word": None})
    return out


def _coarticulate(phones: list[dict], targets: dict) -> dict:
    from glasshead.speech.coarticulation import coarticulate

    return coarticulate(phones, targets, rate_hz=RATE_HZ)


#: Decimals of the flesh points sent, mm (a micrometre).
FLESH_POINT_DECIMALS = 3
#: Decimals of the dominance curves sent (far below what a plot shows; keeps the answer small).
DOMINANCE_DECIMALS = 5


def _dominance(phones: list[dict], targets: dict) -> dict:
    """The dominance curves for ``"dominance": true``: ``{"groups": {group: [[float] * n_frames
    per phone]}, "parameters": {parameter: group}}``. Dominance is the same for every parameter
    of a group (``speech.dominance.GROUPS``), so it is sent once per group."""
    import numpy as np

    from glasshead.speech.coarticulation import coarticulate_arrays
    from glasshead.speech.dominance import GROUPS

    arrays = coarticulate_arrays(phones, targets, rate_hz=RATE_HZ,
                                 constants={"return_dominance": True})
    used = sorted(set(arrays["groups"].tolist()))
    curves = np.round(arrays["dominance"], DOMINANCE_DECIMALS)
    return {"groups": {GROUPS[g]: curves[g].tolist() for g in used},
            "parameters": {n: GROUPS[g] for n, g in zip(arrays["names"],
                                                          arrays["groups"].tolist(),
                                                          strict=True)}}


def _spoken(words, rate: float, word_names: list[str | None]) -> tuple[list[dict], object]:
    """One espeak-ng synthesis of ``words``; the phones with stress and word attached."""
    synthesis = espeak.get_engine().synthesize(words, rate)
    flat = [(phone, w) for w, word in enumerate(words) for phone in word]
    phones = []
    for phone in synthesis.phones:
        stress, w = (flat[phone["index"]][0][1], flat[phone["index"]][1]) if phone[
            "index"] is not None else (None, None)
        word = word_names[w] if w is not None else None
        phones.append({"symbol": phone["symbol"], "stress": stress, "word": word,
                       "word_index": w if word is not None else None,
                       "start_s": phone["start_s"], "end_s": phone["end_s"]})
    return phones, synthesis


def _neural(text: str, rate: float, phones: list[dict], synthesis, warnings: list[str]):
    """The natural voice saying ``text``, with ``phones`` (timed on espeak-ng's ``synthesis``)
    moved onto its clock (``align.map_times``); None, with a warning, when it is not installed
    or fails (espeak-ng's audio then stands)."""
    if not neural_voice.available():
        warnings.append("the natural voice is not installed: espeak-ng speaks")
        return None
    try:
        speech = neural_voice.synthesize(text, rate)
    except Exception as exc:  # a model that cannot say it: espeak-ng speaks instead
        warnings.append(f"the natural voice could not say it ({type(exc).__name__}): "
                        "espeak-ng speaks")
        return None
    if len(speech.samples) == 0:
        warnings.append("the natural voice said nothing: espeak-ng speaks")
        return None
    import numpy as np

    bounds = [phones[0]["start_s"]] + [p["end_s"] for p in phones]
    moved = align.map_times(bounds, (synthesis.samples, synthesis.sample_rate),
                            (speech.samples, speech.sample_rate))
    # The phones end with the audio (the voice's own closing silence joins the last phone).
    length = len(speech.samples) / speech.sample_rate
    moved[-1] = max(moved[-1], length)
    if moved[-1] > length:
        speech.samples = np.concatenate([speech.samples, np.zeros(
            int(np.ceil((moved[-1] - length) * speech.sample_rate)))])
        moved[-1] = len(speech.samples) / speech.sample_rate
    # To 0.1 ms: a boundary on a frame's time is then that time's own number (140 frames of
    # 10 ms make 1.4000000000000001 s, which a player's 140 / 100 would put before it).
    moved = np.round(moved, 4)
    for phone, start, end in zip(phones, moved[:-1], moved[1:], strict=True):
        phone["start_s"], phone["end_s"] = float(start), float(end)
    return speech


def cached_answer(request: dict, targets_sha256: str, cache: UtteranceCache) -> bytes | None:
    """The cached response's JSON bytes for a validated request, or None when it (or the audio
    it names) is not cached."""
    return cache.answer(request_id(request, targets_sha256),
                        with_audio=request["audio"]["kind"] != "none")


def make(request: dict, targets: dict, targets_sha256: str, cache: UtteranceCache,
         flesh_points=None, tract_voice=None) -> bytes:
    """The response's JSON bytes for a validated request (``text`` | ``phonemes`` | ``phones``,
    ``rate``, ``audio``, ``dominance``, ``flesh_points``), from ``cache`` or made and kept there.
    ``flesh_points``: what a request with ``"flesh_points": true`` needs, a function of the
    tracks ({name: [float] * n_frames}) giving {point: (n_frames, 3) mm}
    (``geometry.flesh_points.FleshPointRig.tracks``); ``targets_sha256`` must then also stand for
    what that function reads. ``tract_voice``: what audio of kind ``tract`` needs, a function of
    the tracks, their rate and the timed phones giving (samples, sample rate)
    (``speech.tract_voice.speak`` on the head's tract shape); ``targets_sha256`` must then stand
    for what it reads too. UtteranceInputError for input that cannot be spoken;
    espeak.EspeakUnavailableError when espeak-ng is needed and missing."""
    hit = cached_answer(request, targets_sha256, cache)
    if hit is not None:
        return hit
    utterance_id = request_id(request, targets_sha256)
    rate, options = request["rate"], request["audio"]
    kind = options["kind"]
    warnings, word_names = [], []
    synthesis = None
    voice_name = f"espeak-ng {espeak.VOICE}"
    if request.get("text") is not None:
        engine = espeak.get_engine()
        said = pronounce(request["text"], engine)
        warnings = [f"could not pronounce {w!r}: neither CMUdict nor espeak-ng knows it; "
                    "the rest is spoken" for w in said.unpronounceable]
        if not said.words:
            raise UtteranceInputError("text: no word in it can be pronounced"
                                      + (f" ({', '.join(said.unpronounceable)})"
                                         if said.unpronounceable else ""))
        word_names = [None if w.text == PAUSE else w.text for w in said.items]
        phones, synthesis = _spoken([w.phones for w in said.items], rate, word_names)
        sources = {w.text: w.source for w in said.words}
        if kind in NEURAL_KINDS:
            natural = _neural(request["text"], rate, phones, synthesis, warnings)
            if natural is not None:
                synthesis, voice_name = natural, neural_voice.VOICE
    elif request.get("phonemes") is not None:
        parsed = parse_phonemes(request["phonemes"])
        phones, synthesis = _spoken([parsed], rate, [None])
        sources = {}
    else:
        phones = parse_phones(request["phones"], rate)
        sources = {}
        if kind in ("natural", "lowpass", "vocoded"):
            synthesis = espeak.get_engine().synthesize(
                [[(p["symbol"], p["stress"])] for p in phones], 1.0)
            inner = [p for p in synthesis.phones if p["index"] is not None]
            bounds_from = [inner[0]["start_s"]] + [p["end_s"] for p in inner]
            bounds_to = [phones[0]["start_s"]] + [p["end_s"] for p in phones]
            synthesis.samples = audio.retime(synthesis.samples, synthesis.sample_rate,
                                             bounds_from, bounds_to)

    timed = [{k: p[k] for k in ("symbol", "stress", "start_s", "end_s")} for p in phones]
    result = _coarticulate(timed, targets)
    voice, audio_url = None, None
    if kind == "articulatory":
        samples, sample_rate = vtl_voice.synthesize(phones)
        voice = vtl_voice.VOICE
    elif kind == "tract":
        if tract_voice is None:
            raise ValueError("audio of kind tract needs the tract_voice function")
        samples, sample_rate = tract_voice(result["tracks"], result["rate_hz"], timed)
        voice = TRACT_VOICE
    elif kind != "none":
        seed = int(utterance_id[:8], 16)
        samples = audio.degrade(synthesis.samples, synthesis.sample_rate, kind,
                                cutoff_hz=options.get("cutoff_hz"),
                                channels=options.get("channels"), seed=seed)
        sample_rate = synthesis.sample_rate
        voice = voice_name
    wav = None
    if voice is not None:
        wav = wav_bytes(samples, sample_rate)
        audio_url = f"/api/v1/utterances/{utterance_id}/audio.wav"

    response = {
        "id": utterance_id,
        "phones": [{"symbol": p["symbol"],
                    "ipa": None if p["symbol"] == PAUSE else lookup(p["symbol"]).ipa,
                    "stress": p["stress"], "word": p["word"], "start_s": p["start_s"],
                    "end_s": p["end_s"]} for p in phones],
        "words": _words(phones, sources),
        "duration_s": phones[-1]["end_s"],
        "rate": rate,
        "rate_hz": result["rate_hz"],
        "n_frames": result["n_frames"],
        "tracks": result["tracks"],
        "cues": result["cues"],
        "audio": {**options, "kind": kind},
        "audio_url": audio_url,
        "voice": voice,
        "warnings": warnings,
    }
    if request.get("dominance"):
        response["dominance"] = _dominance(timed, targets)
    if request.get("flesh_points"):
        if flesh_points is None:
            raise ValueError("a request for flesh points needs the flesh_points function")
        import numpy as np

        response["flesh_points"] = {
            name: (np.round(track, FLESH_POINT_DECIMALS) + 0.0).tolist()  # + 0.0: no -0.0
            for name, track in flesh_points(result["tracks"]).items()}
    data = json.dumps(response, separators=(",", ":")).encode()
    cache.put(utterance_id, data, wav)
    return data


def _words(phones: list[dict], sources: dict) -> list[dict]:
    """The words in order with their time span and the source of their pronunciation."""
    words: list[dict] = []
    previous = None
    for phone in phones:
        index = phone.get("word_index")
        if index is not None and index == previous:
            words[-1]["end_s"] = phone["end_s"]
        elif index is not None:
            words.append({"text": phone["word"], "source": sources.get(phone["word"]),
                          "start_s": phone["start_s"], "end_s": phone["end_s"]})
        previous = index
    return words
