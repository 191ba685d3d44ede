"""Shared test vectors for the EPG indices: real frames of the emuR engassim set, with their values.

Run ``python -m glasshead.epg.vectors`` to rewrite ``tests/vectors/epg-indices.json``; pytest and
``tests/js/epgIndices.test.js`` both check it, and pytest checks that it is up to date.
"""

import json
import sys
from pathlib import Path

import numpy as np

from glasshead.constants import (
    EPG_COLUMNS,
    EPG_ELECTRODES,
    EPG_MISSING_CELLS,
    EPG_ROWS,
    EPG_ZONES,
)
from glasshead.epg import indices
from glasshead.epg.formats import parse_emur_json
from glasshead.epg.sequence import rows_to_strings
from glasshead.settings import REPO_ROOT, get_settings

FORMAT_VERSION = 1
VECTORS_PATH = REPO_ROOT / "tests" / "vectors" / "epg-indices.json"
EMUR_FILE = Path("epg") / "emur-engassim.json"


def emur_path() -> Path:
    """The reference EPG file under GLASSHEAD_DATA_DIR; raises FileNotFoundError if missing."""
    path = get_settings().data_dir / EMUR_FILE
    if not path.is_file():
        raise FileNotFoundError(f"reference EPG data not found at {path}; "
                                "set GLASSHEAD_DATA_DIR to the shared data directory")
    return path


def build_vectors(path: Path) -> dict:
    """Cases: for each segment its first, middle, last and fullest frame (distinct patterns only),
    plus an empty and a full palate."""
    sequences = parse_emur_json(path.read_bytes())
    cases, seen = [], set()
    for seq in sequences:
        totals = seq.frames.sum(axis=(1, 2))
        picks = [0, len(seq.frames) // 2, len(seq.frames) - 1, int(np.argmax(totals))]
        for i in picks:
            key = seq.frames[i].tobytes()
            if key in seen:
                continue
            seen.add(key)
            cases.append(_case(f"{seq.name}, frame {i} (t = {seq.t_s[i]:.3f} s)", seq.frames[i]))
    full = np.ones((EPG_ROWS, EPG_COLUMNS), dtype=np.uint8)
    full.reshape(-1)[list(EPG_MISSING_CELLS)] = 0
    cases.append(_case("no contact at all", np.zeros_like(full)))
    cases.append(_case("every one of the 62 electrodes contacted", full))
    return {
        "description": "EPG indices (emuR, R/epg.class.R) of real frames from the emuR engassim "
                       "set and two edge cases; each case gives the 8 rows, R1 first",
        "format_version": FORMAT_VERSION,
        "source": f"{EMUR_FILE.as_posix()} (emuR package data, GPL-2 or later)",
        "constants": {
            "rows": EPG_ROWS, "columns": EPG_COLUMNS, "electrodes": EPG_ELECTRODES,
            "missing_cells": list(EPG_MISSING_CELLS),
            "zones": {name: list(bounds) for name, bounds in EPG_ZONES.items()},
            "slots": list(indices.INDEX_SLOTS),
        },
        "cases": cases,
    }


def _case(description: str, frame: np.ndarray) -> dict:
    values = indices.index_table(frame)[0]
    return {
        "description": description,
        "input": {"rows": rows_to_strings(frame)},
        "expected": {name: float(v) for name, v in zip(indices.INDEX_SLOTS, values)},
    }


def dumps(vectors: dict) -> str:
    return json.dumps(vectors, indent=1) + "\n"


def main() -> int:
    VECTORS_PATH.write_text(dumps(build_vectors(emur_path())))
    print(f"wrote {VECTORS_PATH}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
