"""Articulation and cue tracks for a timed phone sequence, by Cohen and Massaro's (1993)
coarticulation model (DESIGN.md part 7; the paper's section on coarticulation).

Each segment s has, per parameter p, a target T_sp and a dominance function
D_sp(t) = alpha_sp * exp(-theta_s * |t - centre_s|^c) (``speech.dominance``); the track is the
dominance-weighted average

    F_p(t) = sum_s D_sp(t) T_sp / sum_s D_sp(t),

a convex combination of the targets, so a track never leaves the range its targets lie in. The
weights are computed relative to each frame's most dominant segment, so that frames far from
every segment's centre (a long phone's middle) do not underflow to 0 / 0.

Targets come from the built phoneme targets (``pipeline.phoneme_targets``, docs/targets.md): a
measured consonant takes its variant fitted in the vowel context nearest after it (else before
it, within the same stretch of speech between silences), so /k/ before /i/ is fronted; silence
takes the rig's rest pose (the /h/ target) with a low dominance, so speech reaches into it; a
diphthong is two segments, its first element and the glide to its second (``GLIDES``).

Cue tracks (voicing, nasal airflow, frication, 0..1) come from the phones' features, a box of
``CUE_SMOOTHING_S`` seconds moved over the phones' steps, integrated exactly.

Pure: no I/O, no settings; ``coarticulate`` reads only its arguments and the constants
``speech.dominance.load_constants`` gives by default. docs/coarticulation.md.
"""

import math

import numpy as np

from glasshead import phonemes
from glasshead.speech import dominance

#: Seconds: the width of the box the cue steps are smoothed with (onsets take this long).
CUE_SMOOTHING_S = 0.01
#: Frames: n_frames = ceil(duration_s * rate_hz - FRAME_TOLERANCE), so that a duration that is a
#: whole number of frames (0.3 s at 100 Hz) is not given one more by the float product.
FRAME_TOLERANCE = 1e-9
#: Seconds: how far a phone may start before the previous one ends (float noise in timings).
TIME_TOLERANCE_S = 1e-9
#: Cue names, in the order of ``_cue_values``.
CUES = ("voicing", "nasal_airflow", "frication")
#: The symbol whose target stands for silence: /h/'s target is the rig's rest pose.
REST_TARGET = "HH"
#: Diphthongs glide: a diphthong's target is its first element (docs/targets.md), so its last
#: ``GLIDE_SHARE`` is a segment of its own with the target (and class) of its second element,
#: the share VocalTractLab's segment rules give the second vowel gesture of /aɪ aʊ ɔɪ/.
GLIDES = {"AY": "IH", "EY": "IH", "OY": "IH", "AW": "UH", "OW": "UH"}
GLIDE_SHARE = 1.0 / 3.0
#: Frames blended at a time (``windowed_tracks``).
BLEND_CHUNK_FRAMES = 256
#: A segment whose decay lies this far above a frame's least decayed one weighs at most
#: exp(-50) (2e-22) of that one, times the largest alpha ratio (1,000): below what a double
#: holds, so it is left out of the frame's blend and a long utterance costs linear time.
NEGLIGIBLE_DECAY = 50.0


def _phone_label(k: int, phone) -> str:
    symbol = phone.get("symbol") if isinstance(phone, dict) else None
    return f"phone {k} ({symbol!r})" if symbol is not None else f"phone {k}"


def _number(k: int, phone: dict, key: str) -> float:
    value = phone.get(key)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValueError(f"{_phone_label(k, phone)}: {key} must be a finite number of seconds, "
                         f"not {value!r}")
    return float(value)


def validate_phones(phones: list[dict]) -> list[dict]:
    """The phones checked and normalised: ``{"symbol", "stress", "start_s", "end_s"}`` with the
    symbol in upper-case ARPAbet (or ``"sil"``). ValueError naming the first phone that is not a
    dict, has an unknown symbol, starts before 0, ends before it starts or starts before the
    previous phone ends."""
    if not isinstance(phones, list | tuple) or not phones:
        raise ValueError("phones must be a non-empty list of {symbol, start_s, end_s}")
    out = []
    previous_end = 0.0
    for k, phone in enumerate(phones):
        if not isinstance(phone, dict):
            raise ValueError(f"phone {k} must be a dict with symbol, start_s and end_s")
        symbol = phone.get("symbol")
        if not isinstance(symbol, str):
            raise ValueError(f"{_phone_label(k, phone)}: symbol must be a string")
        if symbol.strip().lower() == dominance.SILENCE:
            name = dominance.SILENCE
        else:
            try:
                name = phonemes.lookup(symbol).arpabet
            except phonemes.UnknownPhonemeError as error:
                raise ValueError(f"{_phone_label(k, phone)}: unknown symbol: {error}") from None
        start, end = _number(k, phone, "start_s"), _number(k, phone, "end_s")
        if start < 0:
            raise ValueError(f"{_phone_label(k, phone)} starts before 0 s ({start} s)")
        if end < start:
            raise ValueError(f"{_phone_label(k, phone)} runs backwards: ends at {end} s, before "
                             f"its start at {start} s")
        if k and start < previous_end - TIME_TOLERANCE_S:
            raise ValueError(f"{_phone_label(k, phone)} overlaps the phone before it: starts at "
                             f"{start} s, before that one ends at {previous_end} s")
        previous_end = end
        out.append({"symbol": name, "stress": phone.get("stress"), "start_s": start,
                    "end_s": end})
    return out


def segments(phones: list[dict]) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    """The dominance segments of validated phones: every phone is one, a diphthong two (its
    first element, then the glide to its second, ``GLIDES``). Returns (symbols, starts (s),
    ends (s), owners: the index of each segment's phone)."""
    symbols, starts, ends, owners = [], [], [], []
    for k, phone in enumerate(phones):
        start, end, symbol = phone["start_s"], phone["end_s"], phone["symbol"]
        if symbol in GLIDES:
            middle = end - GLIDE_SHARE * (end - start)
            symbols += [symbol, GLIDES[symbol]]
            starts += [start, middle]
            ends += [middle, end]
            owners += [k, k]
        else:
            symbols.append(symbol)
            starts.append(start)
            ends.append(end)
            owners.append(k)
    return symbols, np.array(starts), np.array(ends), np.array(owners)


def frame_count(duration_s: float, rate_hz: float) -> int:
    """Frames of a track: ceil(duration_s * rate_hz), frame i at t = i / rate_hz, so the last
    frame lies within the duration (``FRAME_TOLERANCE`` absorbs the product's float error)."""
    return max(1, math.ceil(duration_s * rate_hz - FRAME_TOLERANCE))


def parameter_names(targets: dict) -> list[str]:
    """Every articulation parameter the targets document sets: tongue (with the jaw), lips,
    velum, in the document's order."""
    groups = targets["parameters"]
    return [*groups["tongue"], *groups["lips"], *groups["velum"]]


def parameter_groups(names: list[str], targets: dict) -> np.ndarray:
    """(n_params,) int: each parameter's index in ``dominance.GROUPS``."""
    velum = tuple(targets["parameters"]["velum"])
    return np.array([dominance.GROUPS.index(dominance.parameter_group(n, velum))
                     for n in names])


def vowel_context(symbol: str) -> str:
    """The measured vowel context (/a i u/) a vowel stands nearest to: rounded vowels /u/;
    front vowels from close-mid up (IY IH EY) /i/; every other vowel /a/."""
    p = phonemes.lookup(symbol)
    if p.rounded:
        return "u"
    if p.place == "front" and p.manner in ("close", "near-close", "close-mid"):
        return "i"
    return "a"


def _is_vowel(symbol: str) -> bool:
    return symbol != dominance.SILENCE and phonemes.lookup(symbol).kind != "consonant"


def phone_contexts(symbols: list[str]) -> list[str | None]:
    """Per phone, the vowel context of the vowel nearest after it, else before it, looking no
    further than a silence; None for vowels and silence, and for a consonant with no vowel in
    its stretch."""
    out: list[str | None] = [None] * len(symbols)
    for k, symbol in enumerate(symbols):
        if symbol == dominance.SILENCE or _is_vowel(symbol):
            continue
        found = None
        for step in (1, -1):
            j = k + step
            while 0 <= j < len(symbols) and symbols[j] != dominance.SILENCE:
                if _is_vowel(symbols[j]):
                    found = vowel_context(symbols[j])
                    break
                j += step
            if found:
                break
        out[k] = found
    return out


def _targets_by_symbol(targets: dict) -> dict:
    return {t["arpabet"]: t for t in targets["targets"]}


def target_matrix(symbols: list[str], targets: dict, names: list[str]) -> np.ndarray:
    """(n_phones, n_params) float64: each phone's target, the context variant for a measured
    consonant (a target adjusted after its fit keeps its own values: its variants are the
    unadjusted fits), the rest pose for silence."""
    by_symbol = _targets_by_symbol(targets)
    contexts = phone_contexts(symbols)
    rows = []
    for symbol, context in zip(symbols, contexts, strict=True):
        key = REST_TARGET if symbol == dominance.SILENCE else symbol
        if key not in by_symbol:
            raise ValueError(f"the phoneme targets have no target for {symbol!r}")
        target = by_symbol[key]
        params = target["params"]
        variants = target.get("contexts") or {}
        if context in variants and target["source"].get("kind") == "fit":
            params = variants[context]["params"]
        rows.append([params[name] for name in names])
    return np.asarray(rows, dtype=np.float64)


def dominance_arrays(symbols: list[str], constants: dict):
    """alpha (n_phones, n_groups), theta_anticipation and theta_carryover (n_phones,)."""
    classes = constants["classes"]
    alpha = np.empty((len(symbols), len(dominance.GROUPS)))
    before = np.empty(len(symbols))
    after = np.empty(len(symbols))
    for k, symbol in enumerate(symbols):
        entry = classes[dominance.phone_class(symbol)]
        alpha[k, :-1] = [entry["alpha"][g] for g in dominance.CLASS_GROUPS]
        alpha[k, -1] = constants["velum_alpha"][dominance.velum_class(symbol)]
        before[k], after[k] = entry["theta_anticipation"], entry["theta_carryover"]
    return alpha, before, after


def decay(centres: np.ndarray, times: np.ndarray, before: np.ndarray, after: np.ndarray,
          c: float) -> np.ndarray:
    """(n_phones, n_frames): theta * |tau|^c, tau = t - centre, with the anticipation rate where
    tau < 0 and the carry-over rate where tau > 0 (so D = alpha * exp(-decay))."""
    tau = times[None, :] - centres[:, None]
    theta = np.where(tau < 0, before[:, None], after[:, None])
    return theta * np.abs(tau) ** c


def blend(values: np.ndarray, alpha: np.ndarray, groups: np.ndarray, e: np.ndarray) -> np.ndarray:
    """(n_params, n_frames): the dominance-weighted average of the targets ``values``
    (n_phones, n_params), with ``alpha`` (n_phones, n_groups), each parameter's group ``groups``
    (n_params,) and ``e`` = ``decay`` (n_phones, n_frames). The weights are taken relative to
    each frame's least decayed segment (every factor <= 1, one of them 1), which leaves the
    ratio unchanged and keeps frames far from every centre from underflowing to 0 / 0."""
    shape = np.exp(-(e - e.min(axis=0)))
    tracks = np.empty((values.shape[1], e.shape[1]))
    for g in range(alpha.shape[1]):
        members = np.flatnonzero(groups == g)
        if not len(members):
            continue
        weights = alpha[:, g, None] * shape  # (n_phones, n_frames)
        tracks[members] = (values[:, members].T @ weights) / weights.sum(axis=0)
    return tracks


def windowed_tracks(values: np.ndarray, alpha: np.ndarray, groups: np.ndarray,
                    centres: np.ndarray, times: np.ndarray, before: np.ndarray,
                    after: np.ndarray, c: float) -> np.ndarray:
    """``blend(values, alpha, groups, decay(centres, times, before, after, c))``, frames taken
    BLEND_CHUNK_FRAMES at a time with only the segments that can weigh in them.

    For a chunk of frames [t0, t1], U is the largest over its frames of the least decay among
    the segments near it (those whose intervals hold its frames, and one either side); every
    frame's least decayed segment decays at most U there. A segment whose least decay anywhere
    in [t0, t1] exceeds U + NEGLIGIBLE_DECAY weighs nothing a double holds, and is left out."""
    tracks = np.empty((values.shape[1], len(times)))
    order = np.argsort(centres, kind="stable")
    sorted_centres = centres[order]
    for f0 in range(0, len(times), BLEND_CHUNK_FRAMES):
        chunk = times[f0:f0 + BLEND_CHUNK_FRAMES]
        t0, t1 = chunk[0], chunk[-1]
        lo = max(int(np.searchsorted(sorted_centres, t0)) - 1, 0)
        hi = min(int(np.searchsorted(sorted_centres, t1, side="right")) + 1, len(centres))
        near = order[lo:hi]
        bound = decay(centres[near], chunk, before[near], after[near], c).min(axis=0).max()
        least = np.where(centres < t0, after * np.abs(t0 - centres) ** c,
                         np.where(centres > t1, before * np.abs(centres - t1) ** c, 0.0))
        kept = np.flatnonzero(least <= bound + NEGLIGIBLE_DECAY)
        e = decay(centres[kept], chunk, before[kept], after[kept], c)
        tracks[:, f0:f0 + len(chunk)] = blend(values[kept], alpha[kept], groups, e)
    return tracks


def _cue_values(symbols: list[str]) -> np.ndarray:
    """(n_phones, 3): voicing, nasal airflow and frication of each phone, 0 or 1 (/h/ is
    aspiration noise, counted as frication)."""
    out = np.zeros((len(symbols), len(CUES)))
    for k, symbol in enumerate(symbols):
        if symbol == dominance.SILENCE:
            continue
        p = phonemes.lookup(symbol)
        out[k] = (p.voiced, p.nasal, p.manner in ("fricative", "affricate"))
    return out


def cue_tracks(starts, ends, values, times, width=CUE_SMOOTHING_S) -> np.ndarray:
    """(n_cues, n_frames): each cue's step function (``values`` (n_phones, n_cues) over the
    phones' intervals, 0 in gaps) averaged over a box of ``width`` seconds centred on each
    frame, integrated exactly."""
    half = 0.5 * width
    lo = np.maximum(starts[:, None], times[None, :] - half)
    hi = np.minimum(ends[:, None], times[None, :] + half)
    share = np.clip(hi - lo, 0.0, None) / width  # (n_phones, n_frames)
    return np.clip(values.T @ share, 0.0, 1.0)


def coarticulate(phones: list[dict], targets: dict, *, rate_hz: float = 100.0,
                 constants: dict | None = None) -> dict:
    """Tracks of every articulation parameter and cue for ``phones`` (see the module docstring).

    phones: ``[{"symbol", "stress", "start_s", "end_s"}]`` in time order, not overlapping;
    symbols ARPAbet or ``"sil"``. targets: the built phoneme targets document. rate_hz: frames
    per second, frame i at t = i / rate_hz, n_frames = ceil(duration_s * rate_hz) with
    duration_s the last phone's end. constants: dominance constants (``speech.dominance``;
    default the trained ones), or any of their keys to override, and ``return_dominance``: True
    to have each parameter's dominance of each phone per frame.

    Returns ``{"rate_hz", "n_frames", "duration_s", "tracks": {parameter: [float] * n_frames},
    "cues": {"voicing", "nasal_airflow", "frication": [0..1] * n_frames}}`` and, when asked,
    ``"dominance": {parameter: [[float] * n_frames per phone]}``. ValueError naming the problem
    for bad phones, rate or constants.
    """
    arrays = coarticulate_arrays(phones, targets, rate_hz=rate_hz, constants=constants)
    result = {"rate_hz": arrays["rate_hz"], "n_frames": arrays["n_frames"],
              "duration_s": arrays["duration_s"],
              "tracks": {n: row.tolist() for n, row in zip(arrays["names"], arrays["tracks"],
                                                         strict=True)},
              "cues": {n: row.tolist() for n, row in zip(CUES, arrays["cues"], strict=True)}}
    if "dominance" in arrays:
        result["dominance"] = {n: arrays["dominance"][g].tolist()
                               for n, g in zip(arrays["names"], arrays["groups"], strict=True)}
    return result


def _constants(constants: dict | None) -> tuple[dict, bool]:
    """The constants in use (the shipped ones with ``constants``' keys over them, checked) and
    whether the dominance is wanted. The shipped ones, checked when loaded, are read in place."""
    extra = dict(constants or {})
    wanted = bool(extra.pop("return_dominance", False))
    if not extra:
        return dominance.shipped_constants(), wanted
    merged = dominance.load_constants()
    merged.update(extra)
    return dominance.validate_constants(merged), wanted


def coarticulate_arrays(phones: list[dict], targets: dict, *, rate_hz: float = 100.0,
                        constants: dict | None = None) -> dict:
    """``coarticulate`` as arrays: ``names`` (n_params), ``groups`` (n_params, index into
    ``dominance.GROUPS``), ``tracks`` (n_params, n_frames), ``cues`` (3, n_frames), ``times``
    (n_frames,) and, when asked, ``dominance`` (n_groups, n_phones, n_frames: a diphthong's is
    the sum of its two segments')."""
    if isinstance(rate_hz, bool) or not isinstance(rate_hz, int | float) \
            or not math.isfinite(rate_hz) or rate_hz <= 0:
        raise ValueError(f"rate_hz must be a positive number, not {rate_hz!r}")
    constants, want_dominance = _constants(constants)
    phones = validate_phones(phones)
    symbols = [p["symbol"] for p in phones]
    starts = np.array([p["start_s"] for p in phones])
    ends = np.array([p["end_s"] for p in phones])
    duration = float(ends[-1])
    n_frames = frame_count(duration, float(rate_hz))
    times = np.arange(n_frames) / float(rate_hz)

    names = parameter_names(targets)
    parts, part_starts, part_ends, owners = segments(phones)
    values = target_matrix(parts, targets, names)
    alpha, before, after = dominance_arrays(parts, constants)
    groups = parameter_groups(names, targets)

    centres = 0.5 * (part_starts + part_ends)
    c = float(constants["c"])
    tracks = windowed_tracks(values, alpha, groups, centres, times, before, after, c)
    out = {"rate_hz": float(rate_hz), "n_frames": n_frames, "duration_s": duration,
           "names": names, "groups": groups, "tracks": tracks, "times": times,
           "cues": cue_tracks(starts, ends, _cue_values(symbols), times)}
    if want_dominance:
        e = decay(centres, times, before, after, c)
        d = alpha.T[:, :, None] * np.exp(-e)[None]  # (n_groups, n_segments, n_frames)
        if len(parts) != len(phones):
            combine = np.zeros((len(phones), len(parts)))
            combine[owners, np.arange(len(parts))] = 1.0
            d = np.einsum("ps,gsf->gpf", combine, d)
        out["dominance"] = d
    return out


def sample(tracks: dict, t_s: float) -> dict:
    """Every track of a ``coarticulate`` result (tracks and cues) at time ``t_s``, linearly
    interpolated between frames and held at the ends: {name: float}."""
    position = min(max(float(t_s) * tracks["rate_hz"], 0.0), tracks["n_frames"] - 1.0)
    i = min(int(position), tracks["n_frames"] - 1)
    j = min(i + 1, tracks["n_frames"] - 1)
    share = position - i
    out = {}
    for table in (tracks["tracks"], tracks["cues"]):
        for name, row in table.items():
            out[name] = (1.0 - share) * row[i] + share * row[j]
    return out
