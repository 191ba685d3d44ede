"""The audio options on real espeak-ng speech: low-pass, noise vocoder, retiming, WAV, and the
articulatory voice."""

import numpy as np
import pytest
from scipy import signal

from glasshead.speech import audio, time_stretch, vtl_voice
from glasshead.speech.espeak import get_engine
from glasshead.speech.pronounce import pronounce

CUTOFF_HZ = 1000.0
#: Share of the energy the low-pass may leave above 1.25 x the cut-off (measured: 4e-6).
LOWPASS_LEAK = 1e-4
#: Envelopes: 10 ms RMS frames of the original and the vocoded speech (measured: 0.91).
ENVELOPE_CORRELATION = 0.8


@pytest.fixture(scope="module")
def speech():
    engine = get_engine()
    said = pronounce("she sees the sea, and stew", engine)
    synthesis = engine.synthesize([w.phones for w in said.items], 1.0)
    return synthesis, synthesis.samples.astype(np.float64) / 32768.0


def _share_above(x, rate, hz):
    power = np.abs(np.fft.rfft(x)) ** 2
    return power[np.fft.rfftfreq(len(x), 1 / rate) > hz].sum() / power.sum()


def _envelope(x, frame):
    k = len(x) // frame
    return np.sqrt((x[:k * frame].reshape(k, frame) ** 2).mean(axis=1))


def _periodicity(x, rate):
    """The highest normalised autocorrelation at a lag of one voice period (70..400 Hz)."""
    x = x - x.mean()
    energy = np.dot(x, x)
    return max(np.dot(x[:-lag], x[lag:]) / energy
               for lag in range(int(rate / 400), int(rate / 70)))


def test_the_low_pass_leaves_little_energy_above_the_cut_off(speech):
    synthesis, x = speech
    y = audio.lowpass(x, synthesis.sample_rate, CUTOFF_HZ)
    assert _share_above(x, synthesis.sample_rate, 1.25 * CUTOFF_HZ) > 0.1  # /s ʃ/ are high
    assert _share_above(y, synthesis.sample_rate, 1.25 * CUTOFF_HZ) < LOWPASS_LEAK
    assert len(y) == len(x)


def test_the_low_pass_is_zero_phase_so_the_vowels_stay_in_place(speech):
    synthesis, x = speech
    y = audio.lowpass(x, synthesis.sample_rate, CUTOFF_HZ)
    frame = synthesis.sample_rate // 100
    lag = np.argmax(np.correlate(_envelope(y, frame), _envelope(x, frame), "full"))
    assert lag - (len(x) // frame - 1) == 0


def test_a_four_channel_vocoder_keeps_the_envelope_but_not_the_harmonics(speech):
    synthesis, x = speech
    rate = synthesis.sample_rate
    v = audio.vocode(x, rate, 4, seed=1)
    correlation = np.corrcoef(_envelope(x, rate // 100), _envelope(v, rate // 100))[0, 1]
    assert correlation > ENVELOPE_CORRELATION
    vowels = [p for p in synthesis.phones if p["symbol"] in ("IY", "UW")]
    assert len(vowels) == 4
    before = np.mean([_periodicity(x[int(p["start_s"] * rate):int(p["end_s"] * rate)], rate)
                      for p in vowels])
    after = np.mean([_periodicity(v[int(p["start_s"] * rate):int(p["end_s"] * rate)], rate)
                     for p in vowels])
    assert before > 0.5
    assert after < 0.5 * before
    np.testing.assert_allclose(np.sqrt(np.mean(v ** 2)), np.sqrt(np.mean(x ** 2)), rtol=1e-6)


def test_the_vocoder_bands_are_spaced_on_the_cochlea_between_the_limits():
    edges = audio.greenwood_edges(4, 100.0, 8000.0)
    np.testing.assert_allclose(edges[[0, -1]], [100.0, 8000.0], rtol=1e-9)
    assert np.all(np.diff(edges) > 0) and np.all(np.diff(np.log(edges)) > 0.5)


def test_retiming_moves_each_boundary_where_it_is_asked_within_a_frame():
    rate = 1000
    x = np.concatenate([np.zeros(100), np.ones(100)])  # a step at 0.1 s
    y = audio.retime(x, rate, [0.0, 0.1, 0.2], [0.0, 0.3, 0.4])
    assert len(y) == 400
    reach = int(time_stretch.FRAME_S / 2 * rate)  # the crossfade between two phones' frames
    assert np.all(y[:300 - reach] < 1e-9) and np.allclose(y[300 + reach:], 1.0)


def _zero_crossing_hz(samples, rate):
    rising = np.sum((samples[:-1] < 0) & (samples[1:] >= 0))
    return rising / (len(samples) / rate)


def _spectral_centroid_hz(samples, rate):
    power = np.abs(np.fft.rfft(samples)) ** 2
    return float(np.sum(power * np.fft.rfftfreq(len(samples), 1 / rate)) / np.sum(power))


@pytest.mark.parametrize("stretch", [0.5, 3.0, 5.0])
def test_a_phone_held_longer_or_shorter_keeps_its_pitch_and_its_loudness(stretch):
    rate = 22050
    t = np.arange(int(0.6 * rate)) / rate
    tone = 0.5 * np.sin(2 * np.pi * 200 * t)
    y = audio.retime(tone, rate, [0.0, 0.6], [0.0, 0.6 * stretch])
    assert len(y) == int(round(0.6 * stretch * rate))
    steady = y[int(0.03 * rate):-int(0.03 * rate)]
    assert abs(_zero_crossing_hz(steady, rate) - 200.0) < 6.0  # resampling would give 200/stretch
    assert abs(np.sqrt(np.mean(steady ** 2)) - 0.5 / np.sqrt(2)) < 0.05


def test_a_hiss_held_five_times_as_long_keeps_its_band():
    rate = 22050
    band = signal.butter(6, [4000, 8000], "bandpass", fs=rate, output="sos")
    hiss = signal.sosfilt(band, np.random.default_rng(7).standard_normal(int(0.13 * rate)))
    held = audio.retime(hiss, rate, [0.0, 0.13], [0.0, 0.7])
    before = _spectral_centroid_hz(hiss, rate)
    after = _spectral_centroid_hz(held[int(0.05 * rate):-int(0.05 * rate)], rate)
    assert before > 5000 and abs(after - before) < 0.05 * before  # resampled: about 1.1 kHz


def test_a_wav_file_keeps_the_samples_and_rate(tmp_path, speech):
    synthesis, _ = speech
    path = tmp_path / "speech.wav"
    audio.write_wav(path, synthesis.samples, synthesis.sample_rate)
    samples, rate = audio.read_wav(path)
    assert rate == synthesis.sample_rate
    np.testing.assert_array_equal(samples, synthesis.samples)


def test_vocaltractlab_speaks_the_phones_for_as_long_as_they_last():
    phones = [{"symbol": s, "start_s": a, "end_s": b} for s, a, b in
              [("sil", 0.0, 0.1), ("S", 0.1, 0.2), ("T", 0.2, 0.28), ("UW", 0.28, 0.5),
               ("CH", 0.5, 0.6), ("sil", 0.6, 0.7)]]
    assert "name = t; duration_s = 0.050000;" in vtl_voice.segment_file_text(phones)
    samples, rate = vtl_voice.synthesize(phones)
    assert rate == 44100
    assert abs(len(samples) / rate - 0.7) < 0.03
    vowel = samples[int(0.3 * rate):int(0.48 * rate)]
    pause = samples[:int(0.05 * rate)]
    assert np.sqrt(np.mean(vowel ** 2)) > 10 * np.sqrt(np.mean(pause ** 2))
