"""WAV files made in tests: a tone of a given rate and length, in the layout the server keeps."""

import io
import wave

import numpy as np


def tone_wav(rate: int, seconds: float, hz: float = 220.0, channels: int = 1,
             width: int = 2) -> bytes:
    """A sine of ``hz`` at half scale, as a PCM WAV file."""
    t = np.arange(round(rate * seconds)) / rate
    samples = (0.5 * np.sin(2 * np.pi * hz * t) * 32767).astype("<i2")
    frames = np.repeat(samples, channels)
    if width == 1:
        frames = ((frames >> 8) + 128).astype(np.uint8)
    out = io.BytesIO()
    with wave.open(out, "wb") as writer:
        writer.setnchannels(channels)
        writer.setsampwidth(width)
        writer.setframerate(rate)
        writer.writeframes(frames.tobytes())
    return out.getvalue()
