"""Real EPG frames as observations: the consonants of the emuR engassim recordings, one frame per
consonant, grouped into the classes the articulation targets are checked and fitted against.

Each engassim segment (``epg/emur-engassim.json``; Reading-62 palate, 62 electrodes, R1 front)
runs over a consonant pair across a word boundary, labelled ``C1->C2``: /s/ or /n/ then /k/ or
/g/. The first consonant's frame is the frame of the first half with the most contacts in the
front four rows (its closure or constriction at its fullest); the second's is the frame of the
second half with the most contacts in the back three rows. The classes:

- ``alveolar_stop``: /n/ (standing for /t d n/; the same closure, the velum aside);
- ``alveolar_fricative``: /s/ (/s z/);
- ``velar_stop``: /k/ and /g/.

The majority pattern of a class is each electrode's majority over its frames; ``agreement`` is the
share of the 62 electrodes on which a pattern agrees with it.
"""

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from glasshead.epg.sequence import EpgSequence

#: The class of each consonant symbol of the engassim labels.
CLASS_OF = {"n": "alveolar_stop", "s": "alveolar_fricative", "k": "velar_stop",
            "g": "velar_stop"}
#: The phonemes (ARPAbet) each class stands for.
PHONEMES_OF = {"alveolar_stop": ("T", "D", "N"), "alveolar_fricative": ("S", "Z"),
               "velar_stop": ("K", "G", "NG")}
FRONT_ROWS = 4
BACK_ROWS = 3
#: Electrodes of the 8 x 8 frame: R1 has none in columns 1 and 8.
ELECTRODES = np.ones((8, 8), dtype=bool)
ELECTRODES[0, [0, 7]] = False

Frames = npt.NDArray[np.uint8]


class EpgObservationError(ValueError):
    """Recordings that do not give the classes' frames; the message names the segment."""


@dataclass(frozen=True)
class ClassFrames:
    """The frames (k, 8, 8) of one class, with the segment and consonant each came from."""

    name: str
    frames: Frames
    sources: tuple[str, ...]

    @property
    def majority(self) -> Frames:
        return majority_pattern(self.frames)


def _consonants(sequence: EpgSequence) -> tuple[str, str]:
    label = sequence.meta.get("label", "")
    parts = label.split("->")
    if len(parts) != 2 or any(p not in CLASS_OF for p in parts):
        raise EpgObservationError(f"segment {sequence.name!r}: label {label!r} is not C1->C2 "
                                  f"with consonants among {sorted(CLASS_OF)}")
    return parts[0], parts[1]


def consonant_frames(sequence: EpgSequence) -> tuple[Frames, Frames]:
    """The first and the second consonant's frame of one segment (see the module docstring)."""
    frames = sequence.frames
    if len(frames) < 4:
        raise EpgObservationError(f"segment {sequence.name!r} has {len(frames)} frames; "
                                  "at least 4 are needed")
    half = len(frames) // 2
    front = frames[:half, :FRONT_ROWS].reshape(half, -1).sum(axis=1)
    back = frames[half:, -BACK_ROWS:].reshape(len(frames) - half, -1).sum(axis=1)
    return frames[int(np.argmax(front))], frames[half + int(np.argmax(back))]


def class_frames(sequences: list[EpgSequence]) -> dict[str, ClassFrames]:
    """The frames of each class over all segments, in segment order."""
    grouped: dict[str, list] = {name: [] for name in PHONEMES_OF}
    for sequence in sequences:
        first, second = _consonants(sequence)
        for symbol, frame in zip((first, second), consonant_frames(sequence), strict=True):
            grouped[CLASS_OF[symbol]].append((f"{sequence.name} /{symbol}/", frame))
    return {name: ClassFrames(name, np.array([f for _, f in items], dtype=np.uint8),
                              tuple(s for s, _ in items))
            for name, items in grouped.items() if items}


def majority_pattern(frames: Frames) -> Frames:
    """Each electrode's majority (contact in at least half the frames) over (k, 8, 8) frames."""
    frames = np.asarray(frames)
    return ((frames.mean(axis=0) >= 0.5) & ELECTRODES).astype(np.uint8)


def agreement(pattern: Frames, reference: Frames) -> float:
    """The share of the 62 electrodes on which two (8, 8) patterns agree."""
    same = (np.asarray(pattern) == np.asarray(reference)) & ELECTRODES
    return float(same.sum() / ELECTRODES.sum())


def front_closure(frame: Frames) -> bool:
    """A complete row of contact across one of the front rows (R1 to R4)."""
    touched = np.asarray(frame).astype(bool) | ~ELECTRODES
    return bool(touched[:FRONT_ROWS].all(axis=1).any())


def back_closure(frame: Frames) -> bool:
    """A complete row of contact across one of the back rows (R6 to R8)."""
    return bool(np.asarray(frame).astype(bool)[-BACK_ROWS:].all(axis=1).any())


def side_contact(frame: Frames) -> bool:
    """Contact along both sides: the outer column on each side touched in most rows."""
    frame = np.asarray(frame).astype(bool)
    return bool(frame[1:, 0].mean() >= 0.5 and frame[1:, 7].mean() >= 0.5)


def central_groove(frame: Frames) -> bool:
    """Contact along the sides with the middle columns (4 and 5) open in every front row."""
    frame = np.asarray(frame).astype(bool)
    return side_contact(frame) and not frame[:FRONT_ROWS, 3:5].all(axis=1).any() \
        and bool(frame[:FRONT_ROWS, [3, 4]].sum() < FRONT_ROWS * 2)
