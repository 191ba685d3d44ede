"""Praat TextGrid files (long and short text formats) as timed phones.

The first interval tier is read; each interval is a phone (``symbol``, ``start_s``, ``end_s``),
and an empty label is silence ("sil"). Both of Praat's text formats are the same sequence of
values once the long format's ``name =`` labels and ``[i]`` indices are dropped: strings in
double quotes (a doubled quote inside), numbers and the ``<exists>`` flag.
"""

import re

_VALUE = re.compile(r'"((?:[^"]|"")*)"|(?<![\[\w.])(-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)(?![\]\w])'
                    r"|<(exists|absent)>")


class TextGridError(ValueError):
    """Not a TextGrid we can read; the message says what is wrong."""


def _values(text: str) -> list:
    out: list = []
    for match in _VALUE.finditer(text):
        string, number, flag = match.groups()
        if string is not None:
            out.append(string.replace('""', '"'))
        elif number is not None:
            out.append(float(number))
        else:
            out.append(f"<{flag}>")
    return out


def read_textgrid(data: bytes) -> list[dict]:
    """The first interval tier of a TextGrid (UTF-8, UTF-16 with a byte-order mark) as phones
    ``{"symbol", "start_s", "end_s"}``; TextGridError otherwise."""
    if data[:2] in (b"\xff\xfe", b"\xfe\xff"):
        text = data.decode("utf-16")
    else:
        text = data.decode("utf-8-sig", errors="replace")
    values = _values(text)
    if values[:2] != ["ooTextFile", "TextGrid"]:
        raise TextGridError("not a Praat TextGrid text file (it must start with "
                            "File type = \"ooTextFile\" and Object class = \"TextGrid\")")
    try:
        position = 5  # header: file type, class, xmin, xmax, <exists>
        n_tiers = int(values[position])
        position += 1
        for _ in range(n_tiers):
            kind, _name, _xmin, _xmax, count = values[position:position + 5]
            position += 5
            count = int(count)
            if kind == "IntervalTier":
                phones = []
                for k in range(count):
                    start, end, label = values[position + 3 * k:position + 3 * k + 3]
                    phones.append({"symbol": str(label).strip() or "sil",
                                   "start_s": float(start), "end_s": float(end)})
                if not phones:
                    raise TextGridError("the first interval tier has no intervals")
                return phones
            position += 2 * count  # a point tier: (time, mark) pairs
    except (IndexError, TypeError, ValueError) as exc:
        if isinstance(exc, TextGridError):
            raise
        raise TextGridError(f"the TextGrid ends early or is malformed ({exc})") from None
    raise TextGridError("the TextGrid has no interval tier")
