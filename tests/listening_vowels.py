"""Vowel identification from measured tracks: as in Hillenbrand et al. (1995).

A token's features are what a tracker measures in it: the median F0 of its voiced frames between
the authors' vowel start and end, F1-F3 at 20, 50 and 80 % of the vowel, and the vowel's
duration. The times, and so the duration, are the authors' (timedata.dat): the test is of the
measures, not of finding the vowel in the /hVd/.

Speaker normalisation from a short calibration (Nearey's log-mean, per formant): a talker's
"heed", "who'd" and "hod" (iy, uw, ah) give, per formant, the mean of log F over those three
tokens and the three times, and the same for log F0 and log duration; every feature of that
talker is its log minus that mean. The calibration uses the talker's own tokens only, so a
held-out talker is normalised exactly as a new learner would be.

The classifier is a linear discriminant analysis (the 12 vowels' means and their pooled
within-vowel covariance; equal priors, so a token goes to the nearest mean in Mahalanobis
distance), evaluated leave-one-talker-out: each of the 48 talkers is classified by a model
trained on the other 47. A missing measure takes the training tokens' mean of that feature.
On the authors' own measurements this identifies 94.4 % of the vowels (men and women 96.1 %,
children 91.7 %); a quadratic analysis did less well on them (91.7 %), with 47 talkers' tokens
to estimate each vowel's covariance of 11 features.
"""

import numpy as np

from listening_support import Token, Track, sample

#: The calibration vowels: heed, who'd, hod.
CALIBRATION = ("iy", "uw", "ah")

#: The shares of the vowel at which F1-F3 are read.
SHARES = (0.2, 0.5, 0.8)


def features(token: Token, track: Track) -> np.ndarray:
    """(11,) float: F0 (Hz), F1-F3 at 20, 50, 80 % (Hz, formant-major: F1@20, F1@50, ...),
    duration (ms); NaN where the track has no value."""
    inside = (track.t >= token.start_s) & (track.t <= token.end_s)
    voiced = track.f0[inside & ~np.isnan(track.f0)]
    f0 = float(np.median(voiced)) if voiced.size else np.nan
    at = np.array([sample(track.t, track.formants[:, :3], token.at_share(s)) for s in SHARES])
    duration = 1000.0 * (token.end_s - token.start_s)
    return np.concatenate([[f0], at.T.reshape(-1), [duration]])


def published_features(token: Token) -> np.ndarray:
    """The same (11,) features from the authors' measurements (F0 at the steady state)."""
    ref = token.ref
    formants = [ref[f"F{k}_{int(100 * s)}"] for k in (1, 2, 3) for s in SHARES]
    return np.array([ref["f0_ss"], *formants, 1000.0 * (token.end_s - token.start_s)])


def normalise(tokens, table):
    """(n, 11) features -> (n, 11) log features minus each talker's calibration means."""
    logs = np.log(np.where(table > 0, table, np.nan))
    out = np.empty_like(logs)
    # Columns that share a calibration mean: F0, F1 x 3 times, F2 x 3, F3 x 3, duration.
    blocks = [slice(0, 1), slice(1, 4), slice(4, 7), slice(7, 10), slice(10, 11)]
    talkers = np.array([t.talker for t in tokens])
    calibration = np.array([t.vowel in CALIBRATION for t in tokens])
    for talker in np.unique(talkers):
        mine = talkers == talker
        for block in blocks:
            reference = np.nanmean(logs[mine & calibration, block])
            out[mine, block] = logs[mine, block] - reference
    return out


def _fit(x, labels, classes):
    """(means (k, d), inverse of the pooled within-class covariance (d, d))."""
    means = np.array([x[labels == c].mean(axis=0) for c in classes])
    within = x - means[np.searchsorted(classes, labels)]
    pooled = within.T @ within / (len(x) - len(classes))
    return means, np.linalg.inv(pooled)


def _predict(model, x):
    means, inverse = model
    d = x[:, None, :] - means[None, :, :]
    return np.argmin(np.einsum("nki,ij,nkj->nk", d, inverse, d), axis=1)


def identify(tokens, table):
    """Leave-one-talker-out vowel identification of ``tokens`` from their (n, 11) features:
    (n,) bool, True where the vowel was identified."""
    x = normalise(tokens, np.asarray(table, dtype=np.float64))
    labels = np.array([t.vowel for t in tokens])
    talkers = np.array([t.talker for t in tokens])
    classes = np.unique(labels)
    correct = np.zeros(len(tokens), dtype=bool)
    for talker in np.unique(talkers):
        test = talkers == talker
        train = x[~test]
        fill = np.nanmean(train, axis=0)
        train = np.where(np.isnan(train), fill, train)
        held = np.where(np.isnan(x[test]), fill, x[test])
        model = _fit(train, labels[~test], classes)
        correct[test] = classes[_predict(model, held)] == labels[test]
    return correct
