"""The tract voice: speech from Glasshead's own tracks, through the head's own tube.

Each frame of the parameter tracks (``utterance.RATE_HZ``) is posed and its area function
computed (``speech.tract_shape``); VocalTractLab's time-domain tube synthesis
(``synthesis_add_tube``, Birkholz's TDS with its geometric glottis, subglottal tract and nasal
cavity) then runs through those tubes, one state per ``SAMPLES_PER_STATE`` samples at 44.1 kHz,
the areas interpolated between frames. What is heard is the tract that is drawn.

- The tube: the area function resampled to VocalTractLab's 40 sections of equal length, each
  the harmonic mean of the areas it covers (the sections' inertance, length over area, is
  kept, so a closure stays shut); each section's articulator is the tongue behind the incisors,
  the lower lip in front of them; the incisors' position and the nasal port's area come with it.
- The voice source: the glottis takes VocalTractLab's shape for each phone's phonation
  (``GLOTTIS_SHAPES``: modal for voiced sounds, the speaker's voiceless fricative and plosive
  shapes for voiceless ones), eased between phones (``GLOTTIS_EASE_S``); F0 falls from
  ``F0_START_HZ`` to ``F0_END_HZ`` over the utterance; the lungs' pressure rises over
  ``ONSET_S`` at the start and after each pause, and falls before each pause and at the end.

- A fricative's narrowest sections pass at most ``FRICATIVE_CHANNEL_MM2``: the mid-sagittal
  width cannot see the groove of an /s/.

The VocalTractLab library holds one synthesiser: calls are serialised
(``vtl_voice.VTL_LOCK``).
"""

from collections.abc import Mapping, Sequence

import numpy as np
import numpy.typing as npt

from glasshead.phonemes import lookup
from glasshead.speech.espeak_phones import PAUSE

VOICE = "Glasshead tract (VocalTractLab tube synthesis)"
#: VocalTractLab's tube: sections, audio samples per tube state, audio rate.
SECTIONS = 40
SAMPLES_PER_STATE = 110
SAMPLE_RATE = 44100
#: VocalTractLab's articulator codes (Tube.h): the tongue, the lower incisors, the lower lip,
#: anything else. The section at the incisors is theirs: the jet of an alveolar fricative meets
#: them there, where VocalTractLab puts its obstacle noise source.
TONGUE, LOWER_INCISORS, LOWER_LIP, OTHER = 1, 2, 3, 4
#: The glottis shape of each phonation.
GLOTTIS_SHAPES = {"voiced": "modal", "voiceless fricative": "voiceless-fricative",
                  "voiceless stop": "voiceless-plosive"}
#: Seconds over which the glottis moves from one phone's shape to the next's, and the lungs'
#: pressure rises or falls at a pause.
GLOTTIS_EASE_S = 0.02
ONSET_S = 0.03
#: The declining F0 of a statement, Hz.
F0_START_HZ, F0_END_HZ = 125.0, 100.0
#: The options of VocalTractLab's tube model while the head speaks: no piriform fossa and no
#: sound radiated from the skin, as the head's own tube (``acoustics.tube``) has neither, so
#: that the voice has the formants the tube computes; then VocalTractLab's defaults again.
TDS_OPTIONS = {"generate_noise_sources": True, "turbulence_losses": True, "soft_walls": True,
               "radiation_from_skin": False, "piriform_fossa": False,
               "inner_length_corrections": False, "transvelar_coupling": False}
TDS_DEFAULTS = {**TDS_OPTIONS, "radiation_from_skin": True, "piriform_fossa": True}
#: A fricative's narrowest section passes at most this (mm²): the groove of a voiceless /s/
#: (Stevens 1998), which the mid-sagittal width, blind to the groove, overestimates.
FRICATIVE_CHANNEL_MM2 = 10.0
#: Pauses: the symbols of silence in the phones.
PAUSES = {PAUSE, ""}

Floats = npt.NDArray[np.float64]


def vtl_tube(area_function: Mapping) -> tuple[Floats, Floats, npt.NDArray, float, float]:
    """VocalTractLab's tube of an area function (``area_function.area_function`` with
    ``nasal_port_mm2``): lengths (40,) cm, areas (40,) cm², articulators (40,) int, the
    incisors' position from the glottis cm, the nasal port cm²."""
    lengths = np.asarray(area_function["length_mm"], dtype=np.float64)
    areas = np.asarray(area_function["area_mm2"], dtype=np.float64)
    regions = np.asarray(area_function["region"])
    edges = np.concatenate([[0.0], np.cumsum(lengths)])
    cuts = np.linspace(0.0, edges[-1], SECTIONS + 1)
    lo = np.clip(edges[None, :-1], cuts[:-1, None], cuts[1:, None])
    hi = np.clip(edges[None, 1:], cuts[:-1, None], cuts[1:, None])
    covered = hi - lo  # (40, m): how much of each original section each new one covers
    tube_areas = covered.sum(axis=1) / (covered / areas[None]).sum(axis=1)
    main = regions[np.argmax(covered, axis=1)]
    articulators = np.where(main == 2, LOWER_LIP, np.where(main >= 0, TONGUE, OTHER))
    lips = np.flatnonzero(regions == 2)
    incisor = edges[lips[0]] if len(lips) else edges[-1]
    articulators[min(int(np.searchsorted(cuts, incisor, side="right")) - 1, SECTIONS - 1)] = \
        LOWER_INCISORS
    return (np.diff(cuts) / 10.0, tube_areas / 100.0, articulators.astype(np.int64),
            float(incisor) / 10.0, float(area_function.get("nasal_port_mm2", 0.0)) / 100.0)


def phonation(symbol: str) -> str | None:
    """The key of ``GLOTTIS_SHAPES`` for a phone (ARPAbet), or None for a pause."""
    if symbol in PAUSES:
        return None
    phoneme = lookup(symbol)
    if phoneme.voiced:
        return "voiced"
    return "voiceless stop" if phoneme.manner in ("stop", "affricate") else "voiceless fricative"


def _eased(times: Floats, steps: Sequence[tuple[float, Floats]], ease_s: float) -> Floats:
    """Values (n, k) at ``times`` of a piecewise-constant sequence [(start_s, (k,) value)],
    each change ramped linearly over ``ease_s`` centred on its start."""
    values = np.repeat(steps[0][1][None], len(times), axis=0)
    for (_, before), (start, after) in zip(steps, steps[1:], strict=False):
        share = np.clip((times - start) / ease_s + 0.5, 0.0, 1.0)[:, None]
        values += share * (after - before)[None]
    return values


def source_tracks(phones: Sequence[Mapping], glottis_shapes: Mapping[str, Floats],
                  times: Floats) -> Floats:
    """The glottis parameters (n, 11) at ``times`` for timed phones ({symbol, start_s, end_s}):
    each phone's phonation eased into the next, F0 falling, the lungs' pressure (parameter 1)
    rising after each pause and falling before it."""
    voiced = glottis_shapes["voiced"]
    steps, pressure_steps = [], []
    for phone in phones:
        kind = phonation(phone["symbol"])
        steps.append((phone["start_s"], glottis_shapes[kind] if kind else voiced))
        pressure_steps.append((phone["start_s"], np.array([0.0 if kind is None else 1.0])))
    pressure_steps.append((phones[-1]["end_s"], np.array([0.0])))
    values = _eased(times, steps, GLOTTIS_EASE_S)
    lungs = _eased(times, [(-1.0, np.array([0.0]))] + pressure_steps, ONSET_S)[:, 0]
    values[:, 1] *= np.clip(lungs, 0.0, 1.0)
    end = max(phones[-1]["end_s"], 1e-9)
    values[:, 0] = F0_START_HZ + (F0_END_HZ - F0_START_HZ) * np.clip(times / end, 0.0, 1.0)
    return values


def fricative_frames(count: int, rate_hz: float, phones: Sequence[Mapping]) -> npt.NDArray:
    """(count,) bool: the frames (one every 1 / rate_hz s) within a fricative or an affricate."""
    flags = np.zeros(count, dtype=bool)
    times = np.arange(count) / rate_hz
    for phone in phones:
        if phone["symbol"] in PAUSES or lookup(phone["symbol"]).manner not in (
                "fricative", "affricate"):
            continue
        flags |= (times >= phone["start_s"]) & (times < phone["end_s"])
    return flags


def tubes_of_frames(area_functions: Sequence[Mapping],
                    fricatives: npt.ArrayLike | None = None) -> dict:
    """Each frame's VocalTractLab tube: {"lengths" (f, 40), "areas" (f, 40), "articulators"
    (f, 40), "incisor" (f,), "velum" (f,)}; in the frames flagged in ``fricatives`` the
    narrowest section in front of the larynx passes at most ``FRICATIVE_CHANNEL_MM2``."""
    tubes = [vtl_tube(a) for a in area_functions]
    if fricatives is not None:
        for tube, fricative in zip(tubes, np.asarray(fricatives, dtype=bool), strict=True):
            if fricative:
                oral = np.flatnonzero(tube[2] != OTHER)
                narrowest = oral[np.argmin(tube[1][oral])]
                channel = slice(max(narrowest - 1, oral[0]), min(narrowest + 2, SECTIONS))
                tube[1][channel] = np.minimum(tube[1][channel], FRICATIVE_CHANNEL_MM2 / 100.0)
    return {"lengths": np.array([t[0] for t in tubes]), "areas": np.array([t[1] for t in tubes]),
            "articulators": np.array([t[2] for t in tubes]),
            "incisor": np.array([t[3] for t in tubes]), "velum": np.array([t[4] for t in tubes])}


def _run(vtl, frames: dict, first, second, share, source: Floats, states: int) -> list[Floats]:
    """The audio of each tube state after the first (which sets the synthesiser up), the
    tubes interpolated between frames ``first`` and ``second`` by ``share``."""
    vtl.synthesis_reset()
    chunks = []
    for k in range(states + 1):
        i, j, s = first[k], second[k], share[k]
        lengths = frames["lengths"][i] * (1 - s) + frames["lengths"][j] * s
        areas = frames["areas"][i] * (1 - s) + frames["areas"][j] * s
        incisor = float(frames["incisor"][i] * (1 - s[0]) + frames["incisor"][j] * s[0])
        velum = float(frames["velum"][i] * (1 - s[0]) + frames["velum"][j] * s[0])
        chunk = vtl.synthesis_add_tube(0 if k == 0 else SAMPLES_PER_STATE, lengths, areas,
                                       frames["articulators"][i], incisor, velum, 0.0, source[k])
        if k:
            chunks.append(np.asarray(chunk, dtype=np.float64))
    return chunks


def synthesize(frames: dict, rate_hz: float, phones: Sequence[Mapping]) -> tuple[Floats, int]:
    """(n,) float64 samples in -1..1 at ``SAMPLE_RATE``: the tubes of ``tubes_of_frames``
    (one frame every 1 / rate_hz s) spoken with the phones' voice source, as long as the
    phones are."""
    import vocaltractlab_cython as vtl

    from glasshead.speech.vtl_voice import VTL_LOCK

    duration = phones[-1]["end_s"]
    states = max(1, int(np.ceil(duration * SAMPLE_RATE / SAMPLES_PER_STATE)))
    times = np.arange(states + 1) * SAMPLES_PER_STATE / SAMPLE_RATE
    at = np.clip(times * rate_hz, 0.0, len(frames["areas"]) - 1)
    first = np.minimum(at.astype(np.int64), len(frames["areas"]) - 1)
    second = np.minimum(first + 1, len(frames["areas"]) - 1)
    share = (at - first)[:, None]
    with VTL_LOCK:
        shapes = {kind: np.asarray(vtl.get_shape(name, "glottis"), dtype=np.float64)
                  for kind, name in GLOTTIS_SHAPES.items()}
        source = source_tracks(phones, shapes, times)
        vtl.tds_set_options(**TDS_OPTIONS)
        try:
            chunks = _run(vtl, frames, first, second, share, source, states)
        finally:
            vtl.tds_set_options(**TDS_DEFAULTS)
    samples = np.concatenate(chunks) if chunks else np.zeros(0)
    samples = np.nan_to_num(samples, nan=0.0, posinf=0.0, neginf=0.0)
    peak = float(np.max(np.abs(samples))) if len(samples) else 0.0
    if peak > 0:
        samples = samples * (0.9 / peak)
    return samples, SAMPLE_RATE


def speak(shape, tracks: Mapping[str, Sequence[float]], rate_hz: float,
          phones: Sequence[Mapping]) -> tuple[Floats, int]:
    """The tract voice of an utterance: its tracks posed on ``shape`` (a TractShape), frame by
    frame, and spoken (``synthesize``)."""
    area_functions = shape.frames(tracks)
    fricatives = fricative_frames(len(area_functions), rate_hz, phones)
    return synthesize(tubes_of_frames(area_functions, fricatives), rate_hz, phones)
