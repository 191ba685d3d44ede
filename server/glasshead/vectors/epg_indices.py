"""epg-indices.json: real frames of the emuR engassim set, with their EPG indices.

pytest (tests/test_epg_indices.py) checks that the file is what this module makes from the
reference data, and ``tests/js/epgIndices.test.js`` that the JavaScript twin gives the same values.
The inputs are contact patterns (text rows of 0 and 1), so no input is near a threshold.
"""

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
from glasshead.vectors import sources
from glasshead.vectors.common import case, document, tolerance

NAME = "epg-indices.json"
FORMAT_VERSION = 2
TOLERANCES = {
    "index": tolerance(1e-12, "relative", "logarithms and divisions in float64 round differently "
                                          "in the last bits between the twins and between CPUs; "
                                          "relative to max(1, |expected|)"),
}


def _case(description, frame):
    values = indices.index_table(frame)[0]
    return case(description, {"rows": rows_to_strings(frame)},
                {name: float(v) for name, v in zip(indices.INDEX_SLOTS, values, strict=True)})


def build_document(path=None):
    """Cases: for each segment its first, middle, last and fullest frame (distinct patterns only),
    plus an empty and a full palate."""
    path = path or sources.emur_path()
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
    return document(
        NAME,
        "EPG indices (emuR, R/epg.class.R) of real frames from the emuR engassim set (see "
        "fixtures.source) and two edge cases; each case gives the 8 rows, R1 first",
        FORMAT_VERSION, cases,
        constants={
            "rows": EPG_ROWS, "columns": EPG_COLUMNS, "electrodes": EPG_ELECTRODES,
            "missing_cells": list(EPG_MISSING_CELLS),
            "zones": {name: list(bounds) for name, bounds in EPG_ZONES.items()},
            "slots": list(indices.INDEX_SLOTS),
        },
        tolerances=TOLERANCES,
        fixtures={"source": {"file": sources.EMUR_FILE.as_posix(),
                             "credit": "emuR package data, GPL-2 or later"}})


def files():
    return {NAME: build_document()}
