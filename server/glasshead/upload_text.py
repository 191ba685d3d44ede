"""What the upload readers share (``uploads``, ``uploads_flesh``): the error they raise, which the
API answers with its status, and the text and lines of a file."""

import re
from collections.abc import Iterator

#: Columns of a text upload are parted by commas, semicolons, tabs or spaces.
FIELD_SPLIT = re.compile(r"\s*[,;\t]\s*|\s+")


class ObservationError(ValueError):
    """An upload that cannot be fitted: ``status`` (413, 415 or 422) and a message naming why."""

    def __init__(self, message: str, status: int = 422):
        super().__init__(message)
        self.status = status


def decoded(content: bytes, what: str) -> str:
    """The file as text (UTF-8, a byte-order mark allowed); 415 naming ``what`` otherwise."""
    try:
        return content.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ObservationError(f"field file: not a text {what} file (it is not UTF-8)",
                               status=415) from None


def data_lines(text: str) -> Iterator[tuple[int, str, list[str]]]:
    """(1-based line number, the line stripped, its columns) of every line that is not blank
    or a ``#`` comment."""
    for number, line in enumerate(text.splitlines(), start=1):
        line = line.strip()
        if line and not line.startswith("#"):
            yield number, line, [f for f in FIELD_SPLIT.split(line) if f]
