"""Real ultrasound tongue contours of speaker it01 (rticulate, MIT): /t/ against /k/, carried
into the project frame through the speaker's palate trace.

The contours (``ultrasound/rticulate-it01-tongue.csv`` in the reference data) are mid-sagittal
tongue outlines on 42 fan lines, in mm in the probe frame (origin near the transducer under the
chin, +X toward the front), each taken at the peak of a tongue-tip gesture (``max_TT``: pata,
poto, putu, the /t/ of it01's Italian) or of a tongue-dorsum gesture (``max_TD``: paca, poco,
pucu, /k/). Ultrasound cannot see the tip (the air under it) nor the root behind the hyoid's
shadow: a contour is what the fan lines found, with gaps where they found nothing.

The same speaker's palate trace (``rticulate-it01-palate.tsv``, the raw Articulate Assistant
export, ``*`` for no value) is on the same fan lines, so the probe frame is registered onto the
project frame by fitting the trace to the mid-sagittal section of our maxilla's palatal vault:
a rigid map in the z = 0 plane (``geometry.midsagittal.Similarity2D`` with scale 1)
that lays our vault onto the trace (``register_trace``). Another speaker's palate does not
match ours, so the residual is reported, not hidden.
"""

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from glasshead.geometry.midsagittal import (
    Similarity2D,
    point_to_polylines,
    resample,
    two_point_similarity,
)
from glasshead.geometry.surface_distance import summarise

TONGUE_FILE = Path("ultrasound/rticulate-it01-tongue.csv")
PALATE_FILE = Path("ultrasound/rticulate-it01-palate.tsv")
#: Fan lines of the probe (both files).
FAN_LINES = 42
#: Columns of the palate export before the fan lines' X, Y pairs.
PALATE_LEADING_COLUMNS = 11
#: The gesture labels and the consonant each marks.
LABELS = {"max_TT": "t", "max_TD": "k"}
#: The vault: the part of the maxilla's midline behind the incisors the trace is fitted to (mm
#: behind the section's most anterior point); ultrasound does not see the teeth.
VAULT_FROM_FRONT_MM = 8.0
#: Spacing (mm) of the points the trace and the maxilla's section are resampled to.
STEP_MM = 0.25


class UltrasoundDataError(ValueError):
    """A contour or palate file that cannot be read; the message names the file and the row."""


@dataclass(frozen=True)
class Contour:
    """One contour: the word, its consonant (t or k), vowel, recording time and points (k, 2)
    mm in the probe frame, front first (the fan lines with a value)."""

    word: str
    consonant: str
    vowel: str
    recorded: str
    points: np.ndarray


def _float(text, where):
    try:
        value = float(text)
    except ValueError:
        raise UltrasoundDataError(f"{where}: {text!r} is not a number") from None
    if not np.isfinite(value):
        raise UltrasoundDataError(f"{where}: {text!r} is not finite")
    return value


def read_contours(path):
    """Every contour of the tongue file, in recording order. UltrasoundDataError when a row
    lacks a column, a coordinate is not a number or a label is unknown."""
    path = Path(path)
    groups: dict[tuple[str, str, str], dict] = {}
    with path.open(newline="", encoding="utf-8") as handle:
        for line, row in enumerate(csv.DictReader(handle), start=2):
            where = f"{path.name} line {line}"
            try:
                key = (row["rec_date"], row["seconds"], row["word"])
                label, fan, x, y = row["label"], row["fan_line"], row["X"], row["Y"]
                vowel = row["vowel"]
            except KeyError as missing:
                raise UltrasoundDataError(f"{where}: no column {missing}") from None
            if label not in LABELS:
                raise UltrasoundDataError(f"{where}: label {label!r} is not one of "
                                          f"{sorted(LABELS)}")
            group = groups.setdefault(key, {"label": label, "vowel": vowel, "points": {}})
            if x and y:
                group["points"][int(_float(fan, where))] = (_float(x, where), _float(y, where))
    contours = []
    for (recorded, seconds, word), group in groups.items():
        fans = sorted(group["points"])
        points = np.array([group["points"][f] for f in fans], dtype=np.float64)
        if len(points) < 3:
            raise UltrasoundDataError(f"{path.name}: contour {word} at {recorded} {seconds} s "
                                      "has fewer than 3 points")
        # Fan line 1 is the front: keep front first.
        contours.append(Contour(word, LABELS[group["label"]], group["vowel"],
                                f"{recorded} {seconds} s", points))
    return contours


def read_palate(path):
    """The palate trace (k, 2) mm in the probe frame, front first, fan lines without a value
    left out. UltrasoundDataError when it has too few values or a value is not a number."""
    path = Path(path)
    fields = path.read_text(encoding="utf-8").rstrip("\n").split("\t")
    values = fields[PALATE_LEADING_COLUMNS:]
    if len(values) != 2 * FAN_LINES:
        raise UltrasoundDataError(f"{path.name}: expected {2 * FAN_LINES} values after "
                                  f"{PALATE_LEADING_COLUMNS} columns, found {len(values)}")
    points = []
    for k in range(FAN_LINES):
        x, y = values[2 * k], values[2 * k + 1]
        if x.strip() == "*" or y.strip() == "*":
            continue
        where = f"{path.name} fan line {k + 1}"
        points.append((_float(x, where), _float(y, where)))
    if len(points) < 5:
        raise UltrasoundDataError(f"{path.name}: only {len(points)} fan lines have a palate value")
    trace = np.array(points)
    return trace[np.argsort(-trace[:, 0])]


def vault_section(maxilla_section):
    """The oral surface of the maxilla's midline behind the incisors (VAULT_FROM_FRONT_MM), as
    points ordered front to back: in each 0.5 mm of x, the lowest point above the incisal edge
    (the section also crosses the palate's nasal side, above it)."""
    points = np.vstack([resample(p, STEP_MM) for p in maxilla_section])
    front, edge = points[:, 0].max(), points[:, 1].min()
    keep = points[(points[:, 0] < front - VAULT_FROM_FRONT_MM) & (points[:, 1] > edge + 2.0)]
    bins = np.floor(keep[:, 0] / 0.5).astype(np.int64)
    lowest: dict[int, np.ndarray] = {}
    for b, point in zip(bins, keep, strict=True):
        if b not in lowest or point[1] < lowest[b][1]:
            lowest[b] = point
    return np.array([lowest[b] for b in sorted(lowest, reverse=True)])


def _moved(params, source):
    angle, tx, ty = params
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return source @ rot.T + np.array([tx, ty])


def register_trace(palate_trace, maxilla_section):
    """The rigid map from the probe frame onto the project frame fitting the palate trace to
    the vault. Returns (Similarity2D with scale 1, report: the fit's RMS and the distances of the
    moved trace to the maxilla's midline where it overlaps the vault, mm).

    Both are in millimetres, so the map is rigid: a turn and a shift in the z = 0 plane. The
    trace runs on past the hard palate onto the velum, which our maxilla does not have, so the
    fit asks that every vault point lie on the moved trace (the RMS of the vault's distances to
    it), minimised by Nelder-Mead from the start below; a point-to-point ICP on a curve this flat
    slips into a mirror image or a collapsed scale.
    """
    from scipy.optimize import minimize

    source = resample(palate_trace, STEP_MM)
    vault = vault_section(maxilla_section)
    # Start: the trace's front end on the vault's front, turned so its highest point lies toward
    # the vault's highest point.
    _, rot, shift = two_point_similarity(source[0], source[np.argmax(source[:, 1])],
                                         vault[np.argmax(vault[:, 0])],
                                         vault[np.argmax(vault[:, 1])])
    x0 = np.array([np.arctan2(rot[1, 0], rot[0, 0]), *(vault[np.argmax(vault[:, 0])]
                                                      - rot @ source[0])])

    def cost(params):
        distances = point_to_polylines(vault, [_moved(params, source)])
        return float(np.sqrt(np.mean(distances ** 2)))

    result = minimize(cost, x0, method="Nelder-Mead",
                      options={"xatol": 1e-7, "fatol": 1e-10, "maxiter": 4000})
    angle, tx, ty = result.x
    rot2 = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    transform = Similarity2D(1.0, rot2, [tx, ty])
    moved = transform.apply(source)
    overlap = moved[(moved[:, 0] >= vault[:, 0].min()) & (moved[:, 0] <= vault[:, 0].max())]
    return transform, {
        "method": "rigid, minimising the vault's RMS distance to the trace (Nelder-Mead)",
        "source_points": len(source), "vault_points": len(vault),
        "vault_rms_mm": round(float(result.fun), 3),
        "trace_over_vault": summarise(point_to_polylines(overlap, maxilla_section)),
        "transform": transform.to_json(),
    }


def highest_point(points):
    """The highest point (x, y) of a contour."""
    points = np.asarray(points)
    return points[np.argmax(points[:, 1])]
