"""The articulatory voice: VocalTractLab (JD3 speaker) speaks our phones with their durations.

VocalTractLab's segment file lists phones (its SAMPA names) and durations; from it
``phoneme_file_to_gesture_file`` makes a gestural score and ``gesture_file_to_audio`` the
articulatory synthesis (44.1 kHz). JD3 is a German speaker: English phones it has no gesture
for take the nearest it has (``VTL_NAMES``), so the sound is an approximation, but it comes from
a vocal tract, not a diphone voice. Each phone keeps its duration, so the audio stays on the
phones' clock. The VocalTractLab library holds one speaker's state: calls are serialised.
"""

import tempfile
import threading
from pathlib import Path

import numpy as np

VOICE = "VocalTractLab JD3"

#: ARPAbet -> VocalTractLab JD3 phone (SAMPA); "" is a pause.
VTL_NAMES = {
    "AA": "a", "AE": "E", "AH": "6", "AO": "O", "AW": "aU", "AY": "aI", "EH": "E", "ER": "@",
    "EY": "e", "IH": "I", "IY": "i", "OW": "o", "OY": "OY", "UH": "U", "UW": "u",
    "B": "b", "CH": "tS", "D": "d", "DH": "z", "F": "f", "G": "g", "HH": "h", "JH": "dZ",
    "K": "k", "L": "l", "M": "m", "N": "n", "NG": "N", "P": "p", "R": "R", "S": "s", "SH": "S",
    "T": "t", "TH": "s", "V": "v", "W": "U", "Y": "j", "Z": "z", "ZH": "Z", "sil": "",
}
#: JD3 has these as one gesture each only through their parts.
_SPLIT = {"tS": ("t", "S"), "dZ": ("d", "Z")}

#: VocalTractLab holds one speaker and one synthesiser: every voice that calls it holds this.
VTL_LOCK = threading.Lock()


def segment_file_text(phones: list[dict]) -> str:
    """VocalTractLab's segment file for phones (``symbol``, ``start_s``, ``end_s``); an
    affricate is its stop and fricative, half the duration each."""
    lines = []
    for phone in phones:
        name = VTL_NAMES[phone["symbol"]]
        duration = phone["end_s"] - phone["start_s"]
        parts = _SPLIT.get(name, (name,))
        for part in parts:
            lines.append(f"name = {part}; duration_s = {duration / len(parts):.6f};")
    return "\n".join(lines) + "\n"


def synthesize(phones: list[dict]) -> tuple[np.ndarray, int]:
    """(n,) float64 samples in -1..1 and their sample rate: VocalTractLab's articulatory speech
    of ``phones``, as long as they are."""
    import vocaltractlab_cython as vtl

    with VTL_LOCK, tempfile.TemporaryDirectory(prefix="glasshead-vtl-") as folder:
        segments = Path(folder) / "segments.txt"
        gestures = Path(folder) / "gestures.txt"
        segments.write_text(segment_file_text(phones))
        vtl.phoneme_file_to_gesture_file(str(segments), str(gestures))
        samples = np.asarray(vtl.gesture_file_to_audio(str(gestures)), dtype=np.float64)
        rate = int(vtl.get_constants()["sr_audio"])
    peak = float(np.max(np.abs(samples))) if len(samples) else 0.0
    if peak > 0:
        samples = samples * (0.9 / peak)
    return samples, rate
