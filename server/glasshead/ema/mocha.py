"""MOCHA-TIMIT articulography: an EST track (``.ema``) and an xlabel phone file (``.lab``).

MOCHA's EMA (500 Hz) is 2D, in the midsagittal plane: channels ``<coil>_x`` and ``<coil>_y``
(found by name, in any order) for the coils ``MOCHA_SENSORS``. Assumptions (docs/ema.md, each
overridable):

- units: 1/100 mm (``units_mm=0.01``; MOCHAtools, Qin and Carreira-Perpiñán 2009, divide the
  values by 100 to plot them in mm);
- axes ``"-x 0 +y"``: MOCHA's x grows toward the back of the head and its y upward (MOCHAtools
  plot the raw values with the mouth at small x and the pharynx at large x), so anterior = -x,
  up = +y, and the lateral coordinate is 0;
- the origin is the file's own (the coils are not re-centred on the upper incisor; the
  ``upper_incisor`` sensor is there for a caller who wants that).
"""

from pathlib import Path

from glasshead.ema.est import parse_est_track
from glasshead.ema.labels import read_phones
from glasshead.ema.recording import (
    MAX_GAP_S,
    EmaFormatError,
    EmaRecording,
    Phone,
    build_recording,
    orient,
)

#: MOCHA coil code -> sensor name.
MOCHA_SENSORS = {"ui": "upper_incisor", "li": "lower_incisor", "ul": "upper_lip",
                 "ll": "lower_lip", "tt": "tongue_tip", "tb": "tongue_blade",
                 "td": "tongue_dorsum", "v": "velum", "bn": "nose_bridge"}
#: Millimetres per unit of MOCHA's EMA values.
MOCHA_UNITS_MM = 0.01
#: MOCHA's axes in the frame: anterior = -x, no lateral axis, up = +y.
MOCHA_AXES = "-x 0 +y"


def read_mocha(ema_path: str | Path, lab_path: str | Path | None = None, *,
               units_mm: float = MOCHA_UNITS_MM, axes: str = MOCHA_AXES,
               sample_rate_hz: float | None = None, sensors: list[str] | None = None,
               max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """Read a MOCHA ``.ema`` file and its phones (``lab_path``, else the ``.lab`` beside it when
    there is one). See ``parse_mocha`` for the options."""
    ema_path = Path(ema_path)
    if lab_path is None and ema_path.with_suffix(".lab").is_file():
        lab_path = ema_path.with_suffix(".lab")
    lab = Path(lab_path).read_bytes() if lab_path is not None else None
    return parse_mocha(ema_path.read_bytes(), lab, name=ema_path.stem, source=str(ema_path),
                       labels_source=str(lab_path) if lab_path is not None else None,
                       units_mm=units_mm, axes=axes, sample_rate_hz=sample_rate_hz,
                       sensors=sensors, max_gap_s=max_gap_s)


def parse_mocha(ema: bytes, lab: bytes | None = None, *, name: str, source: str | None = None,
                labels_source: str | None = None, units_mm: float = MOCHA_UNITS_MM,
                axes: str = MOCHA_AXES, sample_rate_hz: float | None = None,
                sensors: list[str] | None = None,
                max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """A MOCHA recording from the bytes of its ``.ema`` (and ``.lab``) files.

    ``units_mm``: millimetres per file unit. ``axes``: which file axis (x or y, signed) is
    anterior, lateral and up (``orient``). ``sample_rate_hz``: None takes it from the frame times.
    ``sensors``: names that must be present. Break frames are missing samples (filled up to
    ``max_gap_s``, else refused).
    """
    source = source or name
    if not (units_mm > 0):
        raise EmaFormatError(f"units_mm {units_mm} is not a positive number", source=source)
    track = parse_est_track(ema, source)
    columns: dict[str, dict[str, int]] = {}
    for index, channel in enumerate(track.channels):
        code, _, axis = channel.rpartition("_")
        if not code or axis.lower() not in ("x", "y"):
            raise EmaFormatError(f"channel {index} {channel!r} is not <coil>_x or <coil>_y",
                                 source=source)
        sensor = MOCHA_SENSORS.get(code.lower(), code.lower())
        if axis.lower() in columns.setdefault(sensor, {}):
            raise EmaFormatError(f"channel {index} {channel!r} repeats {sensor} {axis}",
                                 source=source)
        columns[sensor][axis.lower()] = index
    positions = {}
    for sensor, found in columns.items():
        if set(found) != {"x", "y"}:
            lacking = "y" if "x" in found else "x"
            raise EmaFormatError(f"sensor {sensor} has no {lacking} channel", source=source)
        xy = track.values[:, [found["x"], found["y"]]] * units_mm
        positions[sensor] = orient(xy, axes, source=source, allowed="xy")
    phones: tuple[Phone, ...] = ()
    phone_lines = None
    if lab is not None:
        phones, phone_lines = read_phones(lab, labels_source or f"{name}.lab")
    return build_recording(name=name, source=source, source_format="mocha", t_s=track.t_s,
                           sensors=positions, sample_rate_hz=sample_rate_hz, phones=phones,
                           labels_source=labels_source or f"{name}.lab",
                           phone_lines=phone_lines, frame_lines=track.frame_lines,
                           required=sensors, max_gap_s=max_gap_s)

