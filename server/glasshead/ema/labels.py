"""Phone and word label files, and the check of phone symbols against ARPAbet.

Three layouts are read (``parse_label_file`` tells them apart):

``tsv``: ``start_s end_s label`` per line (tabs or spaces), with an optional header row whose
    first two fields are not numbers (HPRC's ``start_s	end_s	label``).
``xlabel``: the ESPS/waves+ label file (MOCHA-TIMIT's ``.lab``): header lines up to a line
    ``#``, then ``<end_time> <colour> <label>`` per line; each label ends at its time and starts
    where the previous one ended (the first at 0).
``plain``: ``start end label`` lines with no header, as some MOCHA conversions write them.

Phones must be one of CMUdict's 39 ARPAbet symbols (any case), a vowel optionally followed by a
stress digit 0, 1 or 2, or a pause symbol (``PAUSE_SYMBOLS``); pauses become ``PAUSE``.
"""

import math
from typing import NamedTuple

from glasshead.ema.recording import TIME_TOL_S, EmaFormatError, Phone, Word
from glasshead.phonemes import INVENTORY

#: The one symbol pauses are normalised to (the symbol the speech package uses).
PAUSE = "sil"
#: Labels read as a pause: HPRC's and HTK's short pause, silence, TIMIT's and ESPS's pause
#: marks, and MOCHA's in-breath (silent; the articulators move but no phone is made).
PAUSE_SYMBOLS = frozenset({"sp", "sil", "pau", "h#", "#", "breath", "br"})
#: ARPAbet symbol -> True for a vowel (which may carry stress), False for a consonant.
ARPABET = {p.arpabet: p.kind != "consonant" for p in INVENTORY}


class LabelLine(NamedTuple):
    """One label as the file gives it, with its 1-based line."""

    start_s: float
    end_s: float
    text: str
    line: int


def parse_label_file(content: bytes, source: str) -> list[LabelLine]:
    """A label file's labels, in file order, checked to be in order without overlaps."""
    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise EmaFormatError(f"not UTF-8 text ({error.reason})", source=source) from None
    lines = text.splitlines()
    header_end = next((i for i, line in enumerate(lines) if line.strip() == "#"), None)
    if header_end is not None:
        labels = _parse_xlabel(lines, header_end, source)
    else:
        labels = _parse_intervals(lines, source)
    check_sequence(labels, source)
    return labels


def finite_number(text: str, what: str, source: str, line: int | None) -> float:
    """``text`` as a finite float; else an EmaFormatError naming ``what``, the file and line."""
    try:
        value = float(text)
    except ValueError:
        raise EmaFormatError(f"{what} {text!r} is not a number", source=source,
                             line=line) from None
    if not math.isfinite(value):
        raise EmaFormatError(f"{what} {text!r} is not a finite number", source=source, line=line)
    return value


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _fields(line: str) -> list[str]:
    return [f.strip() for f in line.split("\t")] if "\t" in line else line.split(None, 2)


def _parse_intervals(lines: list[str], source: str) -> list[LabelLine]:
    labels = []
    first = True
    for number, line in enumerate(lines, start=1):
        if not line.strip():
            continue
        fields = _fields(line)
        if first and len(fields) >= 2 and not _is_number(fields[0]) \
                and not _is_number(fields[1]):
            first = False
            continue  # the header row
        first = False
        if len(fields) != 3 or not fields[2]:
            raise EmaFormatError(f"expected 'start end label', got {line.strip()!r}",
                                 source=source, line=number)
        start = finite_number(fields[0], "start time", source, number)
        end = finite_number(fields[1], "end time", source, number)
        labels.append(LabelLine(start, end, fields[2], number))
    return labels


def _parse_xlabel(lines: list[str], header_end: int, source: str) -> list[LabelLine]:
    labels: list[LabelLine] = []
    previous = 0.0
    for number, line in enumerate(lines[header_end + 1:], start=header_end + 2):
        if not line.strip():
            continue
        fields = line.split(None, 2)
        if len(fields) != 3:
            raise EmaFormatError(f"expected '<end time> <colour> <label>', got {line.strip()!r}",
                                 source=source, line=number)
        end = finite_number(fields[0], "end time", source, number)
        labels.append(LabelLine(previous, end, fields[2].strip(), number))
        previous = end
    return labels


def check_sequence(labels: list[LabelLine], source: str) -> None:
    """Labels start at or after 0, end after they start, and follow one another without
    overlapping (gaps are allowed)."""
    for k, label in enumerate(labels):
        if label.start_s < -TIME_TOL_S:
            raise EmaFormatError(f"label {label.text!r} starts before 0 ({label.start_s} s)",
                                 source=source, line=label.line)
        if label.end_s < label.start_s - TIME_TOL_S:
            raise EmaFormatError(f"label {label.text!r} ends ({label.end_s} s) before it "
                                 f"starts ({label.start_s} s)", source=source, line=label.line)
        if k and label.start_s < labels[k - 1].end_s - TIME_TOL_S:
            before = labels[k - 1]
            problem = ("out of order" if label.start_s < before.start_s - TIME_TOL_S
                       else "overlapping")
            raise EmaFormatError(
                f"labels {problem}: {label.text!r} starts at {label.start_s} s, before "
                f"{before.text!r} (line {before.line}) ends at {before.end_s} s",
                source=source, line=label.line)


def to_phones(labels: list[LabelLine], source: str) -> tuple[Phone, ...]:
    """Checked phones: ARPAbet symbols with the stress digit split off, pauses as ``PAUSE``."""
    return tuple(Phone(label.start_s, label.end_s, *split_phone(label.text, source, label.line))
                 for label in labels)


def split_phone(text: str, source: str, line: int | None = None) -> tuple[str, int | None]:
    """An ARPAbet label -> (symbol, stress); a pause -> (PAUSE, None). EmaFormatError names an
    unknown symbol, or a stress digit on a consonant."""
    if text.lower() in PAUSE_SYMBOLS:
        return PAUSE, None
    symbol, stress = text.upper(), None
    if symbol[-1:].isdigit():
        symbol, digit = symbol[:-1], symbol[-1]
        if digit not in "012":
            raise EmaFormatError(f"phone {text!r}: stress {digit} is not 0, 1 or 2",
                                 source=source, line=line)
        stress = int(digit)
    if symbol not in ARPABET:
        raise EmaFormatError(
            f"unknown phone symbol {text!r}: not one of the 39 ARPAbet phones (with a stress "
            f"digit on vowels) nor a pause ({', '.join(sorted(PAUSE_SYMBOLS))})",
            source=source, line=line)
    if stress is not None and not ARPABET[symbol]:
        raise EmaFormatError(f"phone {text!r}: a stress digit on a consonant", source=source,
                             line=line)
    return symbol, stress


def to_words(labels: list[LabelLine]) -> tuple[Word, ...]:
    """Words as written, pauses as ``PAUSE``."""
    return tuple(Word(label.start_s, label.end_s,
                      PAUSE if label.text.lower() in PAUSE_SYMBOLS else label.text)
                 for label in labels)


def read_phones(content: bytes, source: str
                ) -> tuple[tuple[Phone, ...], list[tuple[int, str]]]:
    """Phones of a label file, and the line and label as written of each."""
    labels = parse_label_file(content, source)
    return to_phones(labels, source), [(label.line, label.text) for label in labels]


def read_words(content: bytes, source: str) -> tuple[tuple[Word, ...], list[tuple[int, str]]]:
    """Words of a label file, and the line and label as written of each."""
    labels = parse_label_file(content, source)
    return to_words(labels), [(label.line, label.text) for label in labels]
