"""The neck: the volume the head shell (``pipeline.head_shell``) takes into its outline below the
jaw, so that the skin covers the larynx, the hyoid and the upper spine instead of ending under
the chin with them hanging below it.

It is fitted to what it must cover, level by level. The points of the hyoid, the larynx's
cartilages and the cervical vertebrae are cut into horizontal slabs ``SLAB_MM`` thick; in each,
the neck's section is an ellipse centred on the mid-sagittal plane whose front lies
``FRONT_MM`` in front of the most anterior point (the skin over the thyroid cartilage is thin),
whose back lies ``BACK_MM`` behind the most posterior (the muscles behind the spinous
processes), and whose width holds every point of the slab with ``SIDE_MM`` to spare, at least
``MIN_HALF_WIDTH_MM`` to a side. The ellipses' centre and semi-axes are then made straight lines
in height (least squares), so the neck is a smooth slanted tube; it ends in a flat cut
``BELOW_MM`` under the lowest point of the cricoid cartilage, or ``UNDER_MM`` under the lowest
covered point (the seventh vertebra), whichever is lower, like a bust's.

``far_radius`` gives, for rays from a point inside the head, the distance to where each leaves
the neck (0 where it misses), found by marching along the ray: the shell takes the smooth
maximum of that and its two ellipsoids.
"""

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

Floats = npt.NDArray[np.float64]

#: Soft tissue in front of the larynx, behind the spine and to the sides, mm.
FRONT_MM, BACK_MM, SIDE_MM = 6.0, 14.0, 10.0
#: The neck is at least this wide to each side of the midline, mm (an adult neck is 100 to
#: 130 mm across).
MIN_HALF_WIDTH_MM = 50.0
#: Thickness of the slabs the covered points are cut into, mm.
SLAB_MM = 10.0
#: Where the neck ends, at the lowest: below the cricoid cartilage's lowest point, and below the
#: lowest point covered, mm.
BELOW_MM, UNDER_MM = 20.0, 4.0
#: Step of the march along a ray, mm, and how far it goes.
MARCH_STEP_MM, MARCH_REACH_MM = 0.5, 400.0


@dataclass(frozen=True)
class Neck:
    """An elliptic tube: at height y its section is centred at x = centre[0] + centre[1] * y
    (z = 0), with semi-axes depth[0] + depth[1] * y (along x) and width[0] + width[1] * y (along
    z); it runs from ``bottom_y`` up to ``top_y``."""

    centre: tuple[float, float]
    depth: tuple[float, float]
    width: tuple[float, float]
    bottom_y: float
    top_y: float

    def inside(self, points: Floats) -> npt.NDArray[np.bool_]:
        """Whether each point (k, 3) lies in the neck."""
        y = points[..., 1]
        cx = self.centre[0] + self.centre[1] * y
        ax = self.depth[0] + self.depth[1] * y
        az = self.width[0] + self.width[1] * y
        ellipse = ((points[..., 0] - cx) / ax) ** 2 + (points[..., 2] / az) ** 2
        return (ellipse <= 1.0) & (y >= self.bottom_y) & (y <= self.top_y)

    def far_radius(self, origin: Floats, dirs: Floats) -> Floats:
        """Distance from ``origin`` along each unit direction (k, 3) to where the ray last
        leaves the neck; 0 where it never enters."""
        t = np.arange(0.0, MARCH_REACH_MM, MARCH_STEP_MM)
        samples = origin[None, None, :] + dirs[:, None, :] * t[None, :, None]
        inside = self.inside(samples)
        last = np.where(inside.any(axis=1), inside.shape[1] - 1 - np.argmax(inside[:, ::-1],
                                                                              axis=1), -1)
        return np.where(last >= 0, t[np.maximum(last, 0)], 0.0)

    def report(self) -> dict:
        def line(pair):
            return [round(float(v), 4) for v in pair]

        return {"centre_x_mm_at_y": line(self.centre), "half_depth_mm_at_y": line(self.depth),
                "half_width_mm_at_y": line(self.width), "bottom_y_mm": round(self.bottom_y, 2),
                "top_y_mm": round(self.top_y, 2),
                "margins_mm": {"front": FRONT_MM, "back": BACK_MM, "side": SIDE_MM}}


def fit_neck(covered: Floats, cricoid: Floats, top_y: float) -> Neck:
    """The neck over the points ``covered`` (k, 3) (hyoid, larynx, vertebrae), ending under the
    cricoid and under them all (see the module), and reaching up to ``top_y``."""
    covered = np.asarray(covered, dtype=np.float64)
    bottom = min(float(np.min(np.asarray(cricoid)[:, 1])) - BELOW_MM,
                 float(covered[:, 1].min()) - UNDER_MM)
    kept = covered[(covered[:, 1] >= bottom) & (covered[:, 1] <= top_y)]
    rows = []
    for low in np.arange(bottom, kept[:, 1].max(), SLAB_MM):
        slab = kept[(kept[:, 1] >= low) & (kept[:, 1] < low + SLAB_MM)]
        if len(slab) < 3:
            continue
        front, back = slab[:, 0].max() + FRONT_MM, slab[:, 0].min() - BACK_MM
        cx, ax = (front + back) / 2.0, (front - back) / 2.0
        # The half width that holds every point of the slab in the ellipse, with the margin.
        across = np.sqrt(np.maximum(1.0 - ((slab[:, 0] - cx) / ax) ** 2, 0.05))
        az = max(float(np.max(np.abs(slab[:, 2]) / across)) + SIDE_MM, MIN_HALF_WIDTH_MM)
        rows.append((low + SLAB_MM / 2.0, cx, ax, az))
    if len(rows) < 2:
        raise ValueError("too few points of the larynx and spine to fit a neck to")
    table = np.array(rows)
    heights = np.column_stack([np.ones(len(table)), table[:, 0]])
    fits = [np.linalg.lstsq(heights, table[:, k], rcond=None)[0] for k in (1, 2, 3)]
    neck = Neck(centre=(float(fits[0][0]), float(fits[0][1])),
                depth=(float(fits[1][0]), float(fits[1][1])),
                width=(float(fits[2][0]), float(fits[2][1])), bottom_y=bottom, top_y=float(top_y))
    # Straight lines can leave a slab's extreme point outside: grow the sections until none is.
    y = kept[:, 1]
    spread = np.sqrt(((kept[:, 0] - (neck.centre[0] + neck.centre[1] * y))
                      / (neck.depth[0] + neck.depth[1] * y)) ** 2
                     + (kept[:, 2] / (neck.width[0] + neck.width[1] * y)) ** 2).max()
    grow = max(1.0, float(spread) * 1.001)
    return Neck(centre=neck.centre, depth=(neck.depth[0] * grow, neck.depth[1] * grow),
                width=(neck.width[0] * grow, neck.width[1] * grow), bottom_y=bottom,
                top_y=float(top_y))
