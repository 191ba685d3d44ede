"""Project-wide constants: the frame, tolerances and table formats.

Mirrored in ``web/src/core/constants.js``; the shared vectors in ``tests/vectors/constants.json``
assert that both sides agree.

The project frame: millimetres; +x anterior (toward the lips), +y superior, +z toward the
subject's left; the mid-sagittal plane is z = 0.  Note that (anterior, superior, left) is a
mirror of a right-handed anatomical frame, so converting a right-handed source flips the
winding of its triangles; ``geometry.frame`` handles that.
"""

import numpy as np

#: Units of every length in the project frame.
FRAME_UNITS = "mm"
FRAME_AXES = {"x": "anterior", "y": "superior", "z": "left"}

#: Origin of the project frame, given as a point of the Badin (ArtiSynth) source frame, in metres.
#: It is a round point inside the oral cavity, above the tongue dorsum and behind the incisors,
#: so that every anatomical coordinate stays within about +-150 mm.
BADIN_ORIGIN_M = np.array([0.080, 0.0, 0.100])

#: Rows map Badin axes (x posterior, y subject's right, z superior; right-handed) to project axes.
BADIN_TO_PROJECT_AXES = np.array(
    [
        [-1.0, 0.0, 0.0],  # project x (anterior) = -Badin x (posterior)
        [0.0, 0.0, 1.0],  # project y (superior) = Badin z
        [0.0, -1.0, 0.0],  # project z (left) = -Badin y (right)
    ]
)

#: Metres to millimetres.
M_TO_MM = 1000.0
