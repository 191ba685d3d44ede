"""The audio options of an utterance, and WAV writing.

- ``natural``: espeak-ng's voice as it is.
- ``lowpass``: a simulated hearing loss, everything above ``cutoff_hz`` removed: an 8th-order
  Butterworth low-pass run forwards and backwards (``sosfiltfilt``: zero phase, so the sound stays
  on the phones' clock, and 16th order in effect, about 96 dB per octave).
- ``vocoded``: a simulated cochlear implant, noise-vocoded speech after Shannon, Zeng, Kamath,
  Wygonski and Ekelid (1995), "Speech recognition with primarily temporal cues", Science 270:
  ``channels`` band-pass filters spaced evenly on the cochlea (Greenwood 1990) between
  ``VOCODER_BAND_HZ``; the envelope of each band (rectified, low-passed at
  ``VOCODER_ENVELOPE_HZ``) modulates noise filtered into the same band. The temporal envelope
  survives; the harmonics (the voice's pitch and the formants' fine structure) do not.
- ``none``: no audio (tracks only).
- ``articulatory``: VocalTractLab's articulatory synthesis of the same phones (``vtl_voice``).
- ``tract``: the head's own tract, frame by frame, through VocalTractLab's tube synthesis
  (``tract_voice``).
"""

import wave
from pathlib import Path

import numpy as np

from glasshead.speech import time_stretch

KINDS = ("natural", "lowpass", "vocoded", "none", "articulatory", "tract")
#: Default and accepted low-pass cut-off, Hz.
DEFAULT_CUTOFF_HZ = 1000.0
CUTOFF_RANGE_HZ = (100.0, 8000.0)
LOWPASS_ORDER = 8
#: Default and accepted number of vocoder channels (Shannon et al. used 1 to 4).
DEFAULT_CHANNELS = 4
CHANNEL_RANGE = (1, 16)
#: The vocoder's analysis range, Hz (Shannon et al.: up to 4 kHz; ours reaches further, as
#: implants' processors do).
VOCODER_BAND_HZ = (100.0, 8000.0)
#: The envelope's low-pass, Hz: below the voice's pitch, so that no periodicity is carried.
VOCODER_ENVELOPE_HZ = 50.0


def _as_float(samples: np.ndarray) -> np.ndarray:
    if samples.dtype == np.int16:
        return samples.astype(np.float64) / 32768.0
    return np.asarray(samples, dtype=np.float64)


def to_int16(samples: np.ndarray) -> np.ndarray:
    """Float samples in -1..1 (clipped) or int16 as int16."""
    if samples.dtype == np.int16:
        return samples
    return (np.clip(samples, -1.0, 1.0) * 32767.0).round().astype(np.int16)


def lowpass(samples: np.ndarray, sample_rate: int, cutoff_hz: float) -> np.ndarray:
    """(n,) samples low-passed at ``cutoff_hz`` with zero phase; (n,) float64."""
    x = _as_float(samples)
    if not 0 < cutoff_hz < sample_rate / 2:
        raise ValueError(f"cut-off {cutoff_hz} Hz must lie between 0 and {sample_rate / 2} Hz")
    from scipy import signal  # here, not at the top: importing it costs the server 1.3 s to start

    sos = signal.butter(LOWPASS_ORDER, cutoff_hz, btype="lowpass", fs=sample_rate, output="sos")
    return signal.sosfiltfilt(sos, x) if len(x) > 3 * (2 * len(sos) + 1) else x * 0.0


def greenwood_edges(n_channels: int, low_hz: float, high_hz: float) -> np.ndarray:
    """(n_channels + 1,) band edges in Hz spaced evenly in cochlear place (Greenwood 1990,
    human: f = 165.4 (10^(2.1 x) - 0.88), x the relative distance from the apex)."""
    def place(f):
        return np.log10(f / 165.4 + 0.88) / 2.1

    x = np.linspace(place(low_hz), place(high_hz), n_channels + 1)
    return 165.4 * (10 ** (2.1 * x) - 0.88)


def vocode(samples: np.ndarray, sample_rate: int, channels: int, seed: int = 0) -> np.ndarray:
    """(n,) samples noise-vocoded with ``channels`` bands (Shannon et al. 1995), at the same RMS;
    (n,) float64. ``seed``: the noise carriers' random seed (the same input gives the same
    output)."""
    from scipy import signal  # here, not at the top: see lowpass

    x = _as_float(samples)
    high = min(VOCODER_BAND_HZ[1], 0.45 * sample_rate)
    edges = greenwood_edges(channels, VOCODER_BAND_HZ[0], high)
    envelope_sos = signal.butter(4, VOCODER_ENVELOPE_HZ, fs=sample_rate, output="sos")
    noise = np.random.default_rng(seed).standard_normal(len(x))
    out = np.zeros_like(x)
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        band_sos = signal.butter(4, [lo, hi], btype="bandpass", fs=sample_rate, output="sos")
        band = signal.sosfiltfilt(band_sos, x)
        envelope = np.maximum(signal.sosfiltfilt(envelope_sos, np.abs(band)), 0.0)
        carrier = signal.sosfiltfilt(band_sos, noise)
        carrier /= max(float(np.sqrt(np.mean(carrier ** 2))), 1e-12)
        out += signal.sosfiltfilt(band_sos, envelope * carrier)
    rms_in = float(np.sqrt(np.mean(x ** 2))) if len(x) else 0.0
    rms_out = float(np.sqrt(np.mean(out ** 2))) if len(x) else 0.0
    return out * (rms_in / rms_out) if rms_out > 0 else out


def degrade(samples: np.ndarray, sample_rate: int, kind: str, *, cutoff_hz: float | None = None,
            channels: int | None = None, seed: int = 0) -> np.ndarray:
    """espeak-ng's samples for audio ``kind`` natural, lowpass or vocoded, as int16."""
    if kind == "natural":
        return to_int16(samples)
    if kind == "lowpass":
        return to_int16(lowpass(samples, sample_rate, cutoff_hz or DEFAULT_CUTOFF_HZ))
    if kind == "vocoded":
        return to_int16(vocode(samples, sample_rate, channels or DEFAULT_CHANNELS, seed))
    raise ValueError(f"unknown audio kind {kind!r}: use one of {', '.join(KINDS)}")


def write_wav(path: Path, samples: np.ndarray, sample_rate: int) -> None:
    """A mono 16-bit PCM WAV file of (n,) samples (int16, or float in -1..1)."""
    with wave.open(str(path), "wb") as out:
        out.setnchannels(1)
        out.setsampwidth(2)
        out.setframerate(int(sample_rate))
        out.writeframes(to_int16(np.asarray(samples)).astype("<i2").tobytes())


def read_wav(path: Path) -> tuple[np.ndarray, int]:
    """A mono 16-bit WAV file's (n,) int16 samples and its sample rate."""
    with wave.open(str(path), "rb") as source:
        if source.getsampwidth() != 2 or source.getnchannels() != 1:
            raise ValueError(f"{path}: not mono 16-bit PCM")
        data = source.readframes(source.getnframes())
        return np.frombuffer(data, dtype="<i2").copy(), source.getframerate()


def retime(samples: np.ndarray, sample_rate: int, source_bounds: list[float],
           target_bounds: list[float]) -> np.ndarray:
    """(n,) samples whose phone boundaries lie at ``source_bounds`` (s, increasing) stretched
    so that they lie at ``target_bounds`` (same length); (m,) float64 lasting to
    ``target_bounds[-1]``. Each phone keeps its pitch and spectrum (``time_stretch``: WSOLA), so
    a phone held longer sounds the same, held."""
    return time_stretch.stretch_to(_as_float(samples), sample_rate, source_bounds, target_bounds)
