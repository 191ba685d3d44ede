"""Which vertices of the upper jaw are teeth: the height rule the head view colours them by.

Follows ``dentalWeights`` in ``web/src/core/dentalShading.js`` (upper jaw only), so the electrodes
end where the teeth the viewer sees begin. The rule:

- the occlusal level is the lowest point of the mesh (the cusp tips and incisal edges);
- a vertex's "column" is every vertex within 1.5 ``radius`` of it in the horizontal (x, z)
  plane (the reach of the head view's 3 x 3 blocks of ``radius`` mm cells); the column's tip is
  its lowest vertex;
- a column carries a tooth when its tip lies between ``tip_band`` mm below and above the
  occlusal level (this leaves out the palatal vault and a toothless ridge). The head view's band
  is (-1, 4.5) mm; the electrode layout passes ``LAYOUT_TIP_BAND_MM``, wider, so that the last
  molars, which sit higher on the curve of Spee and the tilt of the occlusal plane, count too;
- there, vertices up to ``crown_height`` mm above the tip are crown, with a linear blend of
  ``blend`` mm. Crown heights: about 7.5 (molars) to 10.5 mm (upper central incisors), Ash and
  Nelson, Wheeler's Dental Anatomy.
"""

import numpy as np
from scipy.spatial import cKDTree

#: The head view's defaults (DENTAL_DEFAULTS in dentalShading.js).
RADIUS_MM = 3.0
TIP_BAND_MM = (-1.0, 4.5)
#: The band the electrode layout uses (the Badin molars' cusps are up to 6 mm above the incisal
#: edge; the toothless tuberosity behind them 13 mm).
LAYOUT_TIP_BAND_MM = (-1.0, 7.5)
CROWN_HEIGHT_MM = 8.5
BLEND_MM = 1.2


def tooth_weights(vertices, radius=RADIUS_MM, tip_band=TIP_BAND_MM,
                  crown_height=CROWN_HEIGHT_MM, blend=BLEND_MM) -> np.ndarray:
    """Per-vertex tooth weight in [0, 1] of an upper jaw: (n,) float64.

    vertices : (n, 3) float, project frame (mm, +y superior).
    """
    v = np.asarray(vertices, dtype=np.float64)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) == 0:
        raise ValueError(f"vertices must have shape (n, 3), got {v.shape}")
    y = v[:, 1]
    # The column's tip: the lowest vertex within ``radius`` horizontally (an exact disc, so the
    # rule is as symmetric as the mesh; the head view bins into cells, for speed in the browser).
    tree = cKDTree(v[:, [0, 2]])
    neighbours = tree.query_ball_point(v[:, [0, 2]], r=radius * 1.5)
    tip = np.array([y[k].min() for k in neighbours])
    occlusal = y.min()
    height = y - tip
    lo, hi = crown_height - blend / 2, crown_height + blend / 2
    weights = np.clip((hi - height) / (hi - lo), 0.0, 1.0)
    depth = tip - occlusal
    weights[(depth < tip_band[0]) | (depth > tip_band[1])] = 0.0
    return weights
