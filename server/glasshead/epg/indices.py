"""EPG contact indices, exactly as the emuR package computes them.

Source: emuR, R/epg.class.R (Harrington et al.): ``epgsum``, ``epgcog``, ``epgai``, ``epgci``,
``epgdi``, with their default arguments. The formulae come from
- Hardcastle, Gibbon & Nicolaidis (1991), EPG data reduction methods and their implications for
  studies of lingual coarticulation, J. Phonetics 19, 251-266 (percent contact, centre of gravity);
- Fontdevila, Pallarès & Recasens (1994), The contact index method of electropalatographic data
  reduction, J. Phonetics 22, 141-154 (the contact indices);
- Recasens & Pallarès (2001), Coarticulation, assimilation and blending in Catalan consonant
  clusters, J. Phonetics 29, 273-301, p. 283 (the weights of the anteriority, centrality and
  dorsopalatal indices used by emuR).

Frames are ``(n, 8, 8)`` uint8 arrays of 0/1 contacts: axis 1 is the row, R1 (front) first; axis 2
the electrode column, column 1 first. R1 has no electrode in columns 1 and 8; those cells are 0.
emuR sums whole rows and columns, so a missing electrode simply never counts; the divisors below
(6 for R1, 14 for columns 1 and 8) are emuR's.

The JavaScript twin is ``web/src/core/epgIndices.js``; ``tests/vectors/epg-indices.json`` holds
real frames and their indices, checked by both.
"""

import numpy as np

from glasshead.constants import (
    EPG_COLUMNS,
    EPG_ELECTRODES,
    EPG_MISSING_CELLS,
    EPG_ROWS,
    EPG_ZONES,
)

#: epgcog: weights of rows R1..R8 (``seq(7.5, 0.5, by = -1)``); larger = further forward.
COG_ROW_WEIGHTS = np.arange(7.5, 0.0, -1.0)
#: epgai: weights of rows R1..R5. 4921 = round(9^4 * 6/8): R1 has 6 electrodes, not 8.
AI_ROW_WEIGHTS = np.array([4921.0, 729.0, 81.0, 9.0, 1.0])
#: epgai: electrodes per row R1..R5, the divisor of each row's sum.
AI_ROW_SIZES = np.array([6.0, 8.0, 8.0, 8.0, 8.0])
#: epgci: weights of the column pairs (1, 8), (2, 7), (3, 6), (4, 5): outer to central.
CI_PAIR_WEIGHTS = np.array([1.0, 17.0, 289.0, 4913.0])
#: epgci: electrodes per column pair; the outer pair lacks the two R1 corners.
CI_PAIR_SIZES = np.array([14.0, 16.0, 16.0, 16.0])
#: epgdi: electrodes in rows R6-R8.
DI_ELECTRODES = 24.0

#: Names of the per-frame values, in the order of a row of ``index_table`` (and of the JS target).
INDEX_SLOTS = (
    "contacts", "percent",
    "row1", "row2", "row3", "row4", "row5", "row6", "row7", "row8",
    "alveolar", "palatal", "velar",
    "alveolar_percent", "palatal_percent", "velar_percent",
    "cog", "anteriority", "centrality", "dorsopalatal",
)
SLOT = {name: i for i, name in enumerate(INDEX_SLOTS)}
#: Electrodes in each zone: alveolar 6 + 8, palatal 3 * 8, velar 3 * 8.
ZONE_SIZES = {"alveolar": 14.0, "palatal": 24.0, "velar": 24.0}


def as_frames(frames) -> np.ndarray:
    """Check and return contacts as a ``(n, 8, 8)`` uint8 array (an ``(8, 8)`` frame becomes n = 1).

    Raises ValueError for another shape, a value other than 0 or 1, or a contact in a cell that
    has no electrode (R1 columns 1 and 8).
    """
    array = np.asarray(frames)
    if array.shape == (EPG_ROWS, EPG_COLUMNS):
        array = array[None]
    if array.ndim != 3 or array.shape[1:] != (EPG_ROWS, EPG_COLUMNS):
        raise ValueError(f"EPG frames must have shape (n, 8, 8); got {array.shape}")
    if array.dtype.kind not in "biu":
        raise ValueError(f"EPG frames must be integers 0/1; got dtype {array.dtype}")
    if array.size and not np.isin(array, (0, 1)).all():
        frame = int(np.argwhere(~np.isin(array, (0, 1)))[0, 0])
        raise ValueError(f"EPG frame {frame} holds a value other than 0 or 1")
    flat = array.reshape(len(array), -1)
    for cell in EPG_MISSING_CELLS:
        if flat[:, cell].any():
            frame = int(np.argmax(flat[:, cell]))
            raise ValueError(f"EPG frame {frame}: R1 column {cell + 1} has no electrode, "
                             "so it must be 0")
    return array.astype(np.uint8, copy=False)


def row_contacts(frames) -> np.ndarray:
    """Contacts per row R1..R8 (emuR ``epgsum(p, 1)``): ``(n, 8)`` float64."""
    return as_frames(frames).sum(axis=2, dtype=np.float64)


def percent_contact(frames) -> np.ndarray:
    """Contacted electrodes as a percentage of all 62 (``100 * epgsum(p) / 62``): ``(n,)``."""
    return 100.0 * row_contacts(frames).sum(axis=1) / EPG_ELECTRODES


def zone_contacts(frames) -> dict[str, np.ndarray]:
    """Contacts per zone (alveolar R1-R2, palatal R3-R5, velar R6-R8): name -> ``(n,)`` float64."""
    rows = row_contacts(frames)
    return {name: rows[:, lo:hi].sum(axis=1) for name, (lo, hi) in EPG_ZONES.items()}


def centre_of_gravity(frames) -> np.ndarray:
    """emuR ``epgcog``: sum over rows of weight * row contacts, over all contacts; 0 if none.

    Weights 7.5 (R1) to 0.5 (R8), so a higher value means contact further forward. ``(n,)``.
    """
    rows = row_contacts(frames)
    total = rows.sum(axis=1)
    weighted = rows @ COG_ROW_WEIGHTS
    return np.divide(weighted, total, out=np.zeros_like(total), where=total > 0)


def anteriority_index(frames) -> np.ndarray:
    """emuR ``epgai``: log(1 + sum_r w_r * c_r / size_r) / log(1 + sum w) over rows R1-R5.

    Returns ``(n,)``."""
    rows = row_contacts(frames)[:, :5]
    numerator = np.log(1.0 + (rows / AI_ROW_SIZES) @ AI_ROW_WEIGHTS)
    return numerator / np.log(1.0 + AI_ROW_WEIGHTS.sum())


def centrality_index(frames) -> np.ndarray:
    """emuR ``epgci``: log(1 + sum_k w_k * c_k / size_k) / log(1 + sum w), column pairs outer to
    central, all rows. ``(n,)``."""
    columns = as_frames(frames).sum(axis=1, dtype=np.float64)
    pairs = np.stack([columns[:, k] + columns[:, 7 - k] for k in range(4)], axis=1)
    numerator = np.log(1.0 + (pairs / CI_PAIR_SIZES) @ CI_PAIR_WEIGHTS)
    return numerator / np.log(1.0 + CI_PAIR_WEIGHTS.sum())


def dorsopalatal_index(frames) -> np.ndarray:
    """emuR ``epgdi``: contacts in rows R6-R8 over 24. ``(n,)``."""
    return row_contacts(frames)[:, 5:].sum(axis=1) / DI_ELECTRODES


def index_table(frames) -> np.ndarray:
    """All indices per frame: ``(n, len(INDEX_SLOTS))`` float64, columns in ``INDEX_SLOTS``
    order."""
    frames = as_frames(frames)
    rows = row_contacts(frames)
    table = np.empty((len(frames), len(INDEX_SLOTS)))
    table[:, SLOT["contacts"]] = rows.sum(axis=1)
    table[:, SLOT["percent"]] = percent_contact(frames)
    table[:, SLOT["row1"]:SLOT["row8"] + 1] = rows
    for name, counts in zone_contacts(frames).items():
        table[:, SLOT[name]] = counts
        table[:, SLOT[f"{name}_percent"]] = 100.0 * counts / ZONE_SIZES[name]
    table[:, SLOT["cog"]] = centre_of_gravity(frames)
    table[:, SLOT["anteriority"]] = anteriority_index(frames)
    table[:, SLOT["centrality"]] = centrality_index(frames)
    table[:, SLOT["dorsopalatal"]] = dorsopalatal_index(frames)
    return table


def epg_indices(frames) -> dict[str, np.ndarray]:
    """All indices per frame as name -> ``(n,)`` float64, names from ``INDEX_SLOTS``."""
    table = index_table(frames)
    return {name: table[:, i] for i, name in enumerate(INDEX_SLOTS)}
