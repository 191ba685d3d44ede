"""One espeak-ng synthesis through libespeak-ng: the samples and the time of every phone.

The utterance's sound and its phone timings come from the same synthesis, so they share one
clock: espeak-ng reports a phoneme event (``espeakEVENT_PHONEME``) at the sample where each phone
starts, and we collect those events and the samples in the synth callback of a synchronous
synthesis (``AUDIO_OUTPUT_SYNCHRONOUS``). espeak-ng is fed the phones in its own notation
(``[[...]]``), so the phones it times are the ones asked for; where it still changes one (an
allophone such as the flap ``t#``, or a marker it inserts), the events are aligned back to the
request (``align_events``).

The library keeps global state and is not re-entrant: every call holds ``_LOCK``. When the
library is missing, ``get_engine`` raises ``EspeakUnavailableError``, which says what to install;
the server still starts.

Notation: ``espeak_phones.py`` maps between ARPAbet and espeak-ng's phoneme mnemonics.
"""

import ctypes
import threading
from dataclasses import dataclass, field
from difflib import SequenceMatcher

import numpy as np

from glasshead.speech.espeak_phones import PAUSE, arpabet_to_espeak, espeak_to_arpabet

LIBRARY = "libespeak-ng.so.1"
#: The voice; its name is what the response's ``voice`` reports.
VOICE = "en-us"
INSTALL_HINT = "espeak-ng is not installed: apt-get install espeak-ng (Debian's espeak-ng package)"

#: espeak-ng's default speaking rate, words per minute; rate 1 is this, rate r is r times it.
BASE_WPM = 175
#: espeak-ng's accepted range of words per minute.
WPM_RANGE = (80, 450)
#: Longest word, in phones, handed to espeak-ng in one piece: its synthesis faults (a general
#: protection fault) on a word of about 240 phones or more. Longer words are spoken in pieces.
MAX_WORD_PHONES = 48
#: Most characters of espeak-ng's phoneme text spoken in one synthesis. Past about 700 it
#: splits the clause and reads the rest as English text: the 146th "one" of 500 came out as
#: "double-u vee en". Longer requests are spoken in batches.
MAX_SYNTH_CHARS = 400
#: A silence at either end of the audio shorter than this joins the neighbouring phone, s.
EDGE_SILENCE_S = 0.02
#: The least the last phone lasts (``sounding_end``), s.
LAST_PHONE_MIN_S = 0.02

# speak_lib.h
_AUDIO_OUTPUT_SYNCHRONOUS = 2
_INITIALIZE_PHONEME_EVENTS = 0x0001
_INITIALIZE_DONT_EXIT = 0x8000
_EVENT_LIST_TERMINATED = 0
_EVENT_PHONEME = 7
_POS_CHARACTER = 1
_CHARS_UTF8 = 0x1
_PHONEMES = 0x100
_RATE = 1
_EE_OK = 0

_LOCK = threading.Lock()
_ENGINE = None


class EspeakUnavailableError(RuntimeError):
    """libespeak-ng cannot be loaded or initialised; the message says what to install."""


class _EventId(ctypes.Union):
    _fields_ = [("number", ctypes.c_int), ("name", ctypes.c_char_p),
                ("string", ctypes.c_char * 8)]


class _Event(ctypes.Structure):
    """speak_lib.h's espeak_EVENT."""

    _fields_ = [("type", ctypes.c_int), ("unique_identifier", ctypes.c_uint),
                ("text_position", ctypes.c_int), ("length", ctypes.c_int),
                ("audio_position", ctypes.c_int), ("sample", ctypes.c_int),
                ("user_data", ctypes.c_void_p), ("id", _EventId)]


_CALLBACK = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.POINTER(ctypes.c_short), ctypes.c_int,
                             ctypes.POINTER(_Event))


@dataclass
class Synthesis:
    """One synthesis. ``samples``: (n,) int16 at ``sample_rate``; ``phones``: dicts of ``symbol``
    (ARPAbet without stress, or "sil"), ``start_s``, ``end_s`` and ``index`` (the position in the
    requested sequence, None for a silence espeak-ng added at either end)."""

    samples: np.ndarray
    sample_rate: int
    phones: list[dict] = field(default_factory=list)

    @property
    def duration_s(self) -> float:
        return len(self.samples) / self.sample_rate


def load_library() -> ctypes.CDLL:
    """libespeak-ng as a ctypes library; OSError when it is not installed."""
    return ctypes.CDLL(LIBRARY)


class Espeak:
    """The initialised library. Use ``get_engine()``; every method holds the module's lock."""

    def __init__(self, lib: ctypes.CDLL):
        self._lib = lib
        lib.espeak_Initialize.restype = ctypes.c_int
        lib.espeak_TextToPhonemes.restype = ctypes.c_char_p
        rate = lib.espeak_Initialize(_AUDIO_OUTPUT_SYNCHRONOUS, 0, None,
                                     _INITIALIZE_PHONEME_EVENTS | _INITIALIZE_DONT_EXIT)
        if rate <= 0:
            raise EspeakUnavailableError(f"espeak-ng did not initialise ({INSTALL_HINT})")
        if lib.espeak_SetVoiceByName(VOICE.encode()) != _EE_OK:
            raise EspeakUnavailableError(f"espeak-ng has no voice {VOICE!r} ({INSTALL_HINT})")
        self.sample_rate = int(rate)
        self._chunks: list[bytes] = []
        self._events: list[tuple[int, str]] = []
        self._callback = _CALLBACK(self._collect)  # kept referenced while the library holds it
        lib.espeak_SetSynthCallback(self._callback)

    def _collect(self, wav, n_samples, events) -> int:
        if wav and n_samples > 0:
            self._chunks.append(ctypes.string_at(wav, n_samples * 2))
        i = 0
        while events[i].type != _EVENT_LIST_TERMINATED:
            if events[i].type == _EVENT_PHONEME:
                self._events.append((events[i].sample, events[i].id.string.decode("ascii",
                                                                                  "replace")))
            i += 1
        return 0

    def text_to_phonemes(self, text: str) -> str:
        """espeak-ng's phonemes of ``text`` in its mnemonics, phones separated by "|" and words
        by spaces, e.g. "blorfing" -> "b|l|'o@|f|I|N"."""
        buffer = ctypes.create_string_buffer(text.encode("utf-8"))
        pointer = ctypes.c_void_p(ctypes.addressof(buffer))
        parts = []
        with _LOCK:
            while pointer.value:
                result = self._lib.espeak_TextToPhonemes(ctypes.byref(pointer), _CHARS_UTF8,
                                                         ord("|") << 8)
                if result:
                    parts.append(result.decode("utf-8", "replace"))
        return " ".join(p.strip() for p in parts if p.strip())

    def synthesize(self, words: list[list[tuple[str, int | None]]], rate: float = 1.0
                   ) -> Synthesis:
        """Speak ``words`` (each a list of (ARPAbet, stress) phones; a pause is [("sil", None)])
        at ``rate`` times the default speed. The phones come back aligned to the flat sequence
        of the request, with silences espeak-ng left at either end added.

        A long request is spoken in batches of at most MAX_SYNTH_CHARS of espeak-ng's text,
        split before a pause where there is one, each aligned on its own (so the alignment
        stays linear in the length) and joined with the silence after each batch but the last
        cut off."""
        pieces = [word[i:i + MAX_WORD_PHONES] for word in words
                  for i in range(0, len(word), MAX_WORD_PHONES)]
        wpm = int(round(min(max(BASE_WPM * rate, WPM_RANGE[0]), WPM_RANGE[1])))
        texts = [arpabet_to_espeak(piece) for piece in pieces]
        batches = synthesis_batches(texts, [all(s == PAUSE for s, _ in piece) for piece in pieces])
        parts, phones, offset, first_index = [], [], 0, 0
        for lo, hi in batches:
            wanted = [symbol for piece in pieces[lo:hi] for symbol, _ in piece]
            text = "[[" + " ".join(texts[lo:hi]) + "]]"
            samples, events = self._speak(text, wpm)
            samples = samples[: sounding_end(samples, events, self.sample_rate)]
            start = offset / self.sample_rate
            batch = [{**phone, "start_s": start + phone["start_s"],
                      "end_s": start + phone["end_s"],
                      "index": None if phone["index"] is None else first_index + phone["index"]}
                     for phone in align_events(wanted, events, len(samples), self.sample_rate)]
            if batch:  # the batches abut exactly, whatever the sums round to
                batch[0]["start_s"] = phones[-1]["end_s"] if phones else 0.0
                batch[-1]["end_s"] = (offset + len(samples)) / self.sample_rate
            phones.extend(batch)
            parts.append(samples)
            offset += len(samples)
            first_index += len(wanted)
        samples = np.concatenate(parts) if parts else np.zeros(0, dtype="<i2")
        return Synthesis(samples, self.sample_rate, phones)

    def _speak(self, text: str, wpm: int) -> tuple[np.ndarray, list[tuple[int, str]]]:
        """One call of the library: the samples and the phoneme events of ``text``."""
        data = text.encode("utf-8")
        with _LOCK:
            self._chunks, self._events = [], []
            self._lib.espeak_SetParameter(_RATE, wpm, 0)
            status = self._lib.espeak_Synth(data, len(data) + 1, 0, _POS_CHARACTER, 0,
                                            _CHARS_UTF8 | _PHONEMES, None, None)
            self._lib.espeak_Synchronize()
            chunks, events = self._chunks, self._events
            self._chunks, self._events = [], []
        if status != _EE_OK:
            raise RuntimeError(f"espeak-ng could not synthesise {text!r} (status {status})")
        return np.frombuffer(b"".join(chunks), dtype="<i2").copy(), events


def synthesis_batches(texts: list[str], pauses: list[bool],
                      limit: int = MAX_SYNTH_CHARS) -> list[tuple[int, int]]:
    """``texts`` (one per piece, joined by spaces) cut into runs [lo, hi) of at most ``limit``
    characters (a single longer piece alone). A full run ends before its last pause, when that
    pause lies in the run's second half, so that a batch starts with a pause, not mid-phrase."""
    batches: list[tuple[int, int]] = []
    lo, length = 0, 0  # length: of " ".join(texts[lo:k])
    for k, text in enumerate(texts):
        if k > lo and length + 1 + len(text) > limit:
            inside = [j for j in range(lo + 1, k) if pauses[j]]
            cut = inside[-1] if inside and inside[-1] - lo >= (k - lo) / 2 else k
            batches.append((lo, cut))
            lo = cut
            length = len(" ".join(texts[lo:k]))
        length += (1 if k > lo else 0) + len(text)
    if texts:
        batches.append((lo, len(texts)))
    return batches


def event_phones(mnemonic: str) -> list[tuple[str, int | None]]:
    """The ARPAbet phones of a phoneme event's mnemonic, its stress and length marks dropped."""
    return espeak_to_arpabet(mnemonic.lstrip("',%="))


def sounding_end(samples: np.ndarray, events: list[tuple[int, str]], sample_rate: int) -> int:
    """Where a synthesis ends: after its last sound. The run of digital silence espeak-ng ends
    with depends on what it spoke before (a word ending in /t/ added 40 ms to every later one),
    so it is cut (espeak-ng's closing pause event moves with it), and a request lasts the same
    whatever the worker spoke before. The last phone keeps at least LAST_PHONE_MIN_S, even where
    espeak-ng gave it no sound (the last of 500 digits)."""
    sounding = np.flatnonzero(samples)
    if not sounding.size:
        return len(samples)
    end = int(sounding[-1]) + 1
    spoken = [sample for sample, mnemonic in events
              if any(symbol != PAUSE for symbol, _ in event_phones(mnemonic))]
    if spoken:
        end = max(end, spoken[-1] + round(LAST_PHONE_MIN_S * sample_rate))
    return min(end, len(samples))


def align_events(wanted: list[str], events: list[tuple[int, str]], n_samples: int,
                 sample_rate: int) -> list[dict]:
    """The requested phones with times from espeak-ng's phoneme events ((sample, mnemonic),
    each the start of a phone that lasts to the next event).

    Events are mapped to ARPAbet and matched to ``wanted`` (difflib); where the two differ, the
    phones asked for share the time of the events espeak-ng spoke in their place evenly, and a
    phone espeak-ng dropped or an event it added joins the group before it.
    """
    timed = []
    for k, (sample, mnemonic) in enumerate(events):
        # An event may lie past the audio's end (a closing pause after the cut silence).
        end = min(events[k + 1][0], n_samples) if k + 1 < len(events) else n_samples
        symbols = event_phones(mnemonic)
        if end <= sample or not symbols:
            if timed and end > sample:  # an unmapped marker's time joins the phone before it
                timed[-1][2] = end
            continue
        step = (end - sample) / len(symbols)
        for j, (symbol, _) in enumerate(symbols):
            timed.append([symbol, sample + j * step, sample + (j + 1) * step])
    # Silences at the ends are not part of the request: add them as "sil" or let them join.
    lead, trail = [], []
    while timed and timed[0][0] == PAUSE and (not wanted or wanted[0] != PAUSE):
        lead.append(timed.pop(0))
    while timed and timed[-1][0] == PAUSE and (not wanted or wanted[-1] != PAUSE):
        trail.insert(0, timed.pop())
    first = timed[0][1] if timed else 0
    last = timed[-1][2] if timed else first

    groups = []  # [want_lo, want_hi, got_lo, got_hi]
    got = [t[0] for t in timed]
    for _, i1, i2, j1, j2 in SequenceMatcher(None, wanted, got, autojunk=False).get_opcodes():
        if i2 - i1 == j2 - j1:
            groups.extend([i, i + 1, j, j + 1] for i, j in zip(range(i1, i2), range(j1, j2),
                                                              strict=True))
        else:
            groups.append([i1, i2, j1, j2])
    merged: list[list[int]] = []
    for group in groups:
        if merged and (group[0] == group[1] or group[2] == group[3]
                       or merged[-1][0] == merged[-1][1] or merged[-1][2] == merged[-1][3]):
            merged[-1][1], merged[-1][3] = group[1], group[3]
        else:
            merged.append(list(group))

    phones = []
    if lead and first / sample_rate >= EDGE_SILENCE_S:
        phones.append({"symbol": PAUSE, "start_s": 0.0, "end_s": first / sample_rate,
                       "index": None})
    for want_lo, want_hi, got_lo, got_hi in merged:
        lo = timed[got_lo][1] if got_lo < got_hi else (timed[got_lo - 1][2] if got_lo else first)
        hi = timed[got_hi - 1][2] if got_lo < got_hi else lo
        n = want_hi - want_lo
        for k in range(n):
            phones.append({"symbol": wanted[want_lo + k],
                           "start_s": (lo + (hi - lo) * k / n) / sample_rate,
                           "end_s": (lo + (hi - lo) * (k + 1) / n) / sample_rate,
                           "index": want_lo + k})
    if phones:
        phones[0]["start_s"] = 0.0
        if trail and (n_samples - last) / sample_rate >= EDGE_SILENCE_S:
            phones.append({"symbol": PAUSE, "start_s": phones[-1]["end_s"],
                           "end_s": n_samples / sample_rate, "index": None})
        else:
            phones[-1]["end_s"] = n_samples / sample_rate
    return phones


def get_engine() -> Espeak:
    """The process's one espeak-ng, initialised on first use; EspeakUnavailableError (saying what
    to install) when the library is missing."""
    global _ENGINE
    with _LOCK:
        if _ENGINE is None:
            try:
                lib = load_library()
            except OSError as exc:
                raise EspeakUnavailableError(f"{INSTALL_HINT} ({exc})") from None
            _ENGINE = Espeak(lib)
        return _ENGINE
