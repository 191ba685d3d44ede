"""The paper's 3D error of a rig pose against a measured tongue surface.

For each observed vertex P and an origin O (the rig hub on z = 0, inside the tongue), the ray
from O through P first crosses the rig surface at O + t (P - O); the residual is the distance
along the ray between the observed vertex and that crossing, (t - 1) |P - O| (positive when the
rig surface lies beyond the observed vertex). The error is the RMS of the residuals of the rays
kept by the mask.

A ray that crosses no rig triangle (the origin outside the rig surface, or a ray through a gap)
is given the residual ``miss_penalty_mm`` when set, else |P - O|: the error the ray would have if
the rig surface had shrunk onto the origin. The penalty is a constant per ray, so it keeps the
error finite and bounded but gives no gradient; an optimiser should start from a pose where the
origin lies inside the rig surface (the rig's hub always does at rest).

First crossings come from ``fitting.ray_walk.RayWalker``: exact (equal to the exhaustive
search), walking from the hits of the previous call; with the origin inside the rig surface
(winding number 1) most rays are certified by counting crossings, the rest by a sphere search.
"""

import numpy as np
import numpy.typing as npt

from glasshead.fitting.first_hits import FirstHits, check_rays
from glasshead.fitting.ray_walk import RayWalker

Floats = npt.NDArray[np.float64]


class RayError3D:
    """Stateful 3D error: keeps the previous first hits so that each call walks from them.

    triangles (m, 3) and rest_vertices (n, 3): the rig's fixed topology and a pose to group the
    triangles by; observed (k, 3) mm; origin (3,) mm; mask (k,) bool, True for the rays to keep
    (None: all); miss_penalty_mm: the residual of a ray that crosses nothing (None: |P - O|).
    """

    def __init__(self, triangles: npt.ArrayLike, rest_vertices: npt.ArrayLike,
                 observed: npt.ArrayLike, origin: npt.ArrayLike,
                 mask: npt.ArrayLike | None = None, miss_penalty_mm: float | None = None):
        self.origin, self.directions = check_rays(origin, np.asarray(observed, dtype=np.float64)
                                                  - np.asarray(origin, dtype=np.float64))
        k = len(self.directions)
        keep = np.ones(k, dtype=bool) if mask is None else np.asarray(mask)
        if keep.shape != (k,) or keep.dtype != bool:
            raise ValueError(f"mask must be a ({k},) bool array, got {keep.dtype} {keep.shape}")
        if not np.any(keep):
            raise ValueError("mask leaves no rays")
        if miss_penalty_mm is not None and not (np.isfinite(miss_penalty_mm)
                                                and miss_penalty_mm >= 0):
            raise ValueError(f"miss_penalty_mm must be finite and >= 0, got {miss_penalty_mm}")
        self.mask = keep
        self.length = np.sqrt((self.directions ** 2).sum(axis=1))
        self.penalty = self.length if miss_penalty_mm is None else np.full(k, miss_penalty_mm)
        self.walker = RayWalker(triangles, rest_vertices)
        self.previous: np.ndarray | None = None
        #: The last call's first hits (triangle, t, point, fallback and overturned rays).
        self.hits: FirstHits | None = None

    def reset(self) -> None:
        """Forget the previous hits: the next call searches exhaustively."""
        self.previous = None

    def residuals(self, vertices: npt.ArrayLike) -> Floats:
        """(k,) float64 mm, every ray (masked ones included): (t - 1) |P - O|, or the penalty."""
        hits = self.walker.first_hits(self.origin, self.directions, vertices, self.previous)
        self.hits = hits
        # a ray that missed walks next time from where it was
        self.previous = hits.triangle if self.previous is None \
            else np.where(hits.triangle >= 0, hits.triangle, self.previous)
        with np.errstate(invalid="ignore"):
            r = (hits.t - 1.0) * self.length
        return np.where(hits.triangle >= 0, r, self.penalty)

    def __call__(self, vertices: npt.ArrayLike) -> float:
        """RMS (mm) of the residuals of the kept rays for the rig surface at ``vertices``."""
        r = self.residuals(vertices)[self.mask]
        return float(np.sqrt(np.mean(r * r)))
