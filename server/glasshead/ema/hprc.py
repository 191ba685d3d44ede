"""The Haskins Production Rate Comparison (HPRC) recordings as ../shared/data/ema/hprc holds them.

One utterance is four files side by side: ``<utt>_ema.csv`` (``time_s``, then six columns per
sensor ``<S>_x, <S>_y, <S>_z, <S>_ang1, <S>_ang2, <S>_ang3``), ``<utt>_phones.tsv`` and
``<utt>_words.tsv`` (``start_s end_s label``) and ``<utt>_meta.json`` (``ema_sr``,
``ema_frames``, ``sensors``). Positions are in mm, x anterior, y to the speaker's left, z up,
origin at the upper incisor: already the frame of ``glasshead.ema``. The angles are ignored. An
empty or ``nan`` cell is a missing sample.
"""

import json
import math
from pathlib import Path

import numpy as np

from glasshead.ema.labels import read_phones, read_words
from glasshead.ema.recording import (
    MAX_GAP_S,
    SENSOR_CODES,
    EmaFormatError,
    EmaRecording,
    Phone,
    Word,
    build_recording,
)

#: HPRC's sensor codes -> sensor names (docs/ema.md). Other codes are kept in lower case.
HPRC_SENSORS = {code: SENSOR_CODES[code]
                for code in ("TT", "TB", "TR", "UL", "LL", "JAW", "JAWL", "ML")}
POSITION_AXES = ("x", "y", "z")
ANGLE_COLUMNS = ("ang1", "ang2", "ang3")


def hprc_siblings(csv_path: str | Path) -> dict[str, Path]:
    """The utterance's files beside ``<utt>_ema.csv``: phones, words and meta."""
    csv_path = Path(csv_path)
    utt = csv_path.name.removesuffix(".csv").removesuffix("_ema")
    return {kind: csv_path.with_name(f"{utt}_{kind}{suffix}")
            for kind, suffix in (("phones", ".tsv"), ("words", ".tsv"), ("meta", ".json"))}


def read_hprc(csv_path: str | Path, *, phones_path: str | Path | None = None,
              sensors: list[str] | None = None, max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """Read an HPRC utterance from its ``_ema.csv``; the phone labels (``phones_path``, else the
    ``_phones.tsv`` beside it) are required, the words and the meta file are read when there."""
    csv_path = Path(csv_path)
    siblings = hprc_siblings(csv_path)
    phones = Path(phones_path) if phones_path is not None else siblings["phones"]
    if not phones.is_file():
        raise EmaFormatError(f"no phone labels: expected {phones.name} beside it",
                             source=str(csv_path))
    words, meta = siblings["words"], siblings["meta"]
    return parse_hprc(
        csv_path.read_bytes(), phones=phones.read_bytes(),
        words=words.read_bytes() if words.is_file() else None,
        meta=meta.read_bytes() if meta.is_file() else None,
        name=csv_path.name.removesuffix(".csv").removesuffix("_ema"), source=str(csv_path),
        phones_source=str(phones), words_source=str(words), meta_source=str(meta),
        sensors=sensors, max_gap_s=max_gap_s)


def parse_hprc(csv: bytes, *, phones: bytes | None, words: bytes | None = None,
               meta: bytes | None = None, name: str, source: str | None = None,
               phones_source: str | None = None, words_source: str | None = None,
               meta_source: str | None = None, sensors: list[str] | None = None,
               max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """An HPRC recording from the bytes of its files (``words`` and ``meta`` optional)."""
    source = source or f"{name}_ema.csv"
    phones_source = phones_source or f"{name}_phones.tsv"
    words_source = words_source or f"{name}_words.tsv"
    t_s, positions = _parse_csv(csv, source)
    rate = None
    if meta is not None:
        rate = _check_meta(meta, meta_source or f"{name}_meta.json", len(t_s), positions)
    phone_list: tuple[Phone, ...] = ()
    word_list: tuple[Word, ...] = ()
    phone_lines = word_lines = None
    if phones is not None:
        phone_list, phone_lines = read_phones(phones, phones_source)
    if words is not None:
        word_list, word_lines = read_words(words, words_source)
    named = {HPRC_SENSORS.get(code, code.lower()): xyz for code, xyz in positions.items()}
    return build_recording(name=name, source=source, source_format="hprc", t_s=t_s,
                           sensors=named, sample_rate_hz=rate, phones=phone_list,
                           words=word_list, labels_source=phones_source,
                           words_source=words_source, phone_lines=phone_lines,
                           word_lines=word_lines,
                           frame_lines=list(range(2, len(t_s) + 2)),
                           required=sensors, max_gap_s=max_gap_s)


def _parse_csv(content: bytes, source: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """(times, sensor code -> (n, 3) positions with NaN where missing)."""
    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise EmaFormatError(f"not UTF-8 text ({error.reason})", source=source) from None
    lines = text.splitlines()
    if not lines or not lines[0].strip():
        raise EmaFormatError("no header row", source=source, line=1)
    header = [h.strip() for h in lines[0].split(",")]
    if header[0] != "time_s":
        raise EmaFormatError(f"the first column is {header[0]!r}, not time_s", source=source,
                             line=1)
    columns: dict[str, dict[str, int]] = {}
    for index, column in enumerate(header[1:], start=1):
        code, _, part = column.rpartition("_")
        if not code or part not in POSITION_AXES + ANGLE_COLUMNS:
            raise EmaFormatError(f"column {column!r} is not <sensor>_x/_y/_z/_ang1-3",
                                 source=source, line=1)
        if part in columns.setdefault(code, {}):
            raise EmaFormatError(f"column {column!r} appears twice", source=source, line=1)
        columns[code][part] = index
    for code, parts in columns.items():
        lacking = [a for a in POSITION_AXES if a not in parts]
        if lacking:
            names = ", ".join(f"{code}_{a}" for a in lacking)
            raise EmaFormatError(f"sensor {code} has no {names} column", source=source, line=1)
    rows = []
    for number, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        cells = line.split(",")
        if len(cells) != len(header):
            raise EmaFormatError(f"expected {len(header)} columns, got {len(cells)}",
                                 source=source, line=number)
        row = []
        for column, cell in zip(header, cells, strict=True):
            cell = cell.strip()
            if not cell or cell.lower() == "nan":
                row.append(math.nan)
                continue
            try:
                row.append(float(cell))
            except ValueError:
                raise EmaFormatError(f"{column}: {cell!r} is not a number", source=source,
                                     line=number) from None
        rows.append(row)
    if not rows:
        raise EmaFormatError("no samples", source=source)
    table = np.array(rows, dtype=np.float64)
    positions = {code: table[:, [parts[a] for a in POSITION_AXES]]
                 for code, parts in columns.items()}
    return table[:, 0], positions


def _check_meta(content: bytes, source: str, n_frames: int,
                positions: dict[str, np.ndarray]) -> float | None:
    """The meta file's sample rate, after checking its frame count and sensors against the CSV."""
    try:
        meta = json.loads(content)
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise EmaFormatError(f"not valid JSON ({error})", source=source) from None
    if not isinstance(meta, dict):
        raise EmaFormatError("expected a JSON object", source=source)
    frames = meta.get("ema_frames")
    if frames is not None and frames != n_frames:
        raise EmaFormatError(f"ema_frames says {frames} frames, the CSV has {n_frames}",
                             source=source)
    listed = meta.get("sensors") or []
    absent = [s for s in listed if s not in positions]
    if absent:
        raise EmaFormatError(f"sensors lists {', '.join(map(str, absent))}, which the CSV has no "
                             "columns for", source=source)
    rate = meta.get("ema_sr")
    if rate is None:
        return None
    if isinstance(rate, bool) or not isinstance(rate, (int, float)) or not math.isfinite(rate) \
            or rate <= 0:
        raise EmaFormatError(f"sample rate ema_sr {rate!r} is not a positive number",
                             source=source)
    return float(rate)
