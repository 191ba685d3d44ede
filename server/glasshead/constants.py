"""Project-wide constants: the frame, tolerances and table formats.

Written once, here: ``python -m glasshead.shared_constants`` generates the browser's copy of
every upper-case name, ``web/src/core/shared.generated.js``, and ``tests/test_shared_constants.py``
fails while that file is stale. The shared vectors in ``tests/vectors/constants.json`` assert that
both sides agree.

The project frame: millimetres; +x anterior (toward the lips), +y superior, +z toward the
subject's left; the mid-sagittal plane is z = 0.  Note that (anterior, superior, left) is a
mirror of a right-handed anatomical frame, so converting a right-handed source flips the
winding of its triangles; ``geometry.frame`` handles that.
"""

from typing import Any

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

# --- Electropalatography (the Reading 62-electrode palate) -------------------------------------
# A frame is an 8 x 8 grid of contacts: row 0 = R1 (front, alveolar) ... row 7 = R8 (back, velar);
# column 0 = electrode column 1 ... column 7 = column 8. R1 has no electrode in columns 1 and 8.

#: Rows and columns of the EPG grid.
EPG_ROWS = 8
EPG_COLUMNS = 8
#: Cells per frame in the flat layout (row-major, R1 first): 8 * 8.
EPG_CELLS = EPG_ROWS * EPG_COLUMNS
#: Electrodes on the palate: 8 * 8 minus the two missing corners of R1.
EPG_ELECTRODES = EPG_CELLS - 2
#: Flat cell indices (row * 8 + column) that have no electrode: R1 columns 1 and 8.
EPG_MISSING_CELLS = (0, 7)
#: Zones as half-open row ranges: alveolar R1-R2, palatal R3-R5, velar R6-R8.
EPG_ZONES = {"alveolar": (0, 2), "palatal": (2, 5), "velar": (5, 8)}
#: The panels of the EPG index plots (epg.plot draws them as SVG, web/src/ui/IndexPlot.js on a
#: canvas): per index its title, a short label for a narrow axis, and the range its definition
#: bounds it to (emuR: percentages 0-100, the centre of gravity 0-8 rows, the rest 0-1).
EPG_PLOT_PANELS: dict[str, dict[str, Any]] = {
    "percent": {"label": "Percent contact", "short_label": "% contact", "range": (0.0, 100.0)},
    "cog": {"label": "Centre of gravity", "short_label": "COG", "range": (0.0, float(EPG_ROWS))},
    "anteriority": {"label": "Anteriority index", "short_label": "anteriority",
                    "range": (0.0, 1.0)},
    "centrality": {"label": "Centrality index", "short_label": "centrality", "range": (0.0, 1.0)},
    "dorsopalatal": {"label": "Dorsopalatal index", "short_label": "dorsopalatal",
                     "range": (0.0, 1.0)},
    "alveolar_percent": {"label": "Alveolar contact %", "short_label": "% alveolar",
                         "range": (0.0, 100.0)},
    "palatal_percent": {"label": "Palatal contact %", "short_label": "% palatal",
                        "range": (0.0, 100.0)},
    "velar_percent": {"label": "Velar contact %", "short_label": "% velar",
                      "range": (0.0, 100.0)},
}
#: The panels an index plot shows unless asked for others, top to bottom.
EPG_PLOT_DEFAULT_PANELS = ("percent", "cog", "anteriority", "centrality", "dorsopalatal")
#: Codes of a recording compared with a reference, per electrode (POST
#: /epg/recordings/{id}/compare and the palatogram that draws it): both off, both on, contacted in
#: the recording only, in the reference only, and no electrode there (R1 columns 1 and 8).
EPG_COMPARE_BOTH_OFF = 0
EPG_COMPARE_BOTH_ON = 1
EPG_COMPARE_ONLY_RECORDING = 2
EPG_COMPARE_ONLY_REFERENCE = 3
EPG_COMPARE_NO_ELECTRODE = 9

# --- Tongue-palate collision (the paper's liner and voxel table) -------------------------------
# Tables are built by glasshead.pipeline.collision_tables and read by geometry.collision and
# web/src/core/tables.js; tests/vectors/collision-constants.json asserts both sides agree.

#: Format version of the binary collision tables; a reader refuses any other version.
COLLISION_TABLES_FORMAT_VERSION = 1
#: Magic bytes that open a collision tables file.
COLLISION_TABLES_MAGIC = b"GHCOLTAB"
#: Liner step in longitude and in latitude, degrees (see docs in geometry/liner.py).
COLLISION_LINER_STEP_DEG = 0.5
#: Voxels per axis of the voxel table (the paper's 32 x 32 x 32).
COLLISION_VOXELS = 32
#: Voxel classes: certainly outside, straddling the surface, certainly inside.
VOXEL_OK, VOXEL_BORDER, VOXEL_NOT_OK = 0, 1, 2
#: Liner cell kinds: no triangle seen from O in the cell (every ray misses); one triangle covers
#: the cell and is the first hit everywhere in it (a plane test); a short triangle list.
CELL_EMPTY, CELL_PLANE, CELL_LIST = 0, 1, 2
#: Per-vertex flags: screened by the voxel table (untouched), tested against the liner and
#: found outside (untouched), corrected (moved along the line toward O onto the surface).
FLAG_SCREENED, FLAG_TESTED, FLAG_CORRECTED = 0, 1, 2
#: Largest vertex count accepted by POST /collision/correct.
COLLISION_MAX_VERTICES = 20000
#: The arrays of the tables' payload, in payload order, with their dtypes (numpy's notation:
#: "<f4" little-endian float32, "<u4" uint32, "|u1" uint8); see geometry.collision_format.
COLLISION_TABLES_ARRAYS = {
    "node_radius": "<f4",
    "cell_kind": "|u1",
    "cell_rmin": "<f4",
    "cell_rmax": "<f4",
    "cell_offsets": "<u4",
    "cell_triangles": "<u4",
    "triangles": "<f4",
    "planes": "<f4",
    "voxels": "|u1",
}


class CollisionTolerance:
    """Every tolerance of the collision tables in one place, with the reason for each."""

    #: rad. Cells are widened by this before they are bounded, so that rounding in atan2
    #: (about 1e-16 rad) can never put a direction in a cell whose bounds exclude it.
    angle = 1e-9
    #: mm. Voxel boxes are widened, and radius bounds loosened, by this: the float32 rounding of
    #: table values (about 3e-6 mm at 50 mm) is far below it and the tongue never notices it.
    length = 1e-5
    #: Moller-Trumbore barycentric slack, so that a ray through an edge shared by two triangles
    #: cannot slip between them through rounding.
    barycentric = 1e-9
    #: mm. Points closer than this to the surface count as on it when a result is compared with
    #: an exact reference computed from the float64 mesh (tables store float32 triangles).
    surface = 1e-3
    #: mm. The largest depth inside the maxilla that a corrected tongue may keep (the issue's
    #: exactness bound).
    depth = 0.1


COLLISION_TOL = CollisionTolerance()

# --- Tongue rig ----------------------------------------------------------------------------------
# The rig definition (assets/build/tongue-rig.json) is read by geometry.tongue_surface and
# web/src/core/tongue.js; tests/vectors/tongue-surface.json asserts both evaluate it alike.

#: Format version of the tongue rig definition; both evaluators refuse any other version.
TONGUE_RIG_FORMAT_VERSION = 2
#: The least radial control value of the tongue surface, mm: no control of a page comes nearer
#: the hub (a deep groove where the curve has come close to it would take the radius through it).
TONGUE_CONTROL_FLOOR_MM = 1.0
#: mm. Largest difference allowed between the Python and JavaScript tongue vertices (JS returns
#: float32 positions: about 4e-6 mm of rounding at 50 mm, far inside this).
TONGUE_VERTEX_TOLERANCE_MM = 1e-3
#: Largest relative difference allowed between the two sides' tongue volumes.
TONGUE_VOLUME_RELATIVE_TOLERANCE = 1e-4

# --- Synthetic EPG: electrode layout and contact ------------------------------------------------
# The layout (assets/build/epg-layout.json) is built by glasshead.pipeline.epg_layout and read by
# glasshead.epg.contacts and web/src/core/epgContacts.js; tests/vectors/epg-contacts.json asserts
# both sides compute the same contacts.

#: Format version of the electrode layout file; both readers refuse any other version.
EPG_LAYOUT_FORMAT_VERSION = 1
#: mm. An electrode is contacted when the tongue surface crosses its probe: the segment along the
#: electrode's normal from EPG_CONTACT_BEHIND_MM behind it (inside the palate) to this far in
#: front of it (toward the tongue). 1 mm is about the thickness of a real EPG plate's electrode
#: and of the saliva film that closes the circuit.
EPG_CONTACT_TOLERANCE_MM = 1.0
#: mm. How far behind the electrode the probe reaches: a corrected tongue lies on the palate
#: within 0.1 mm (COLLISION_TOL.depth), so half a millimetre catches every touch.
EPG_CONTACT_BEHIND_MM = 0.5
#: Electrode grids: the Reading 62-electrode palate and a dense grid of 12 rows of 8.
EPG_GRIDS = ("reading62", "dense96")
EPG_DENSE_ROWS = 12

# --- Face rig: skin and lips on the jaw, lip parameters ------------------------------------------
# The rig definition (assets/build/face-rig.json) is built by glasshead.pipeline.face_rig and read
# by geometry.face_rig and web/src/core/faceRig.js; tests/vectors/face-rig.json asserts both pose
# the face alike.

#: Format version of the face rig definition; both evaluators refuse any other version.
FACE_RIG_FORMAT_VERSION = 1
#: mm. Largest difference allowed between the Python and JavaScript face vertices.
FACE_VERTEX_TOLERANCE_MM = 1e-3
#: The meshes the rig deforms, in the definition's order: the skin, the lips and the shell that
#: closes the head (it shares the skin's rim, which rides on the jaw under the chin).
FACE_RIG_MESHES = ("face_skin", "upper_lip", "lower_lip", "head_shell")
#: The two lips, whose mid-sagittal gap the rig measures and closes.
FACE_RIG_LIP_MESHES = ("upper_lip", "lower_lip")
#: Meshes kept in front of the incisors (the shell never comes near them).
FACE_RIG_TEETH_MESHES = ("face_skin", "upper_lip", "lower_lip")
#: Lip parameter names, in the order of the definition's table and of the values both evaluators
#: read.
FACE_RIG_LIP_PARAMETERS = ("lip_opening", "lip_rounding", "lip_protrusion", "upper_lip_raise",
                           "lower_lip_tuck")
#: Field coefficients per vertex: protrusion, rounding (x and z), raise, tuck, closure.
FACE_RIG_COEFF_COUNT = 6

# --- Velum rig: the soft palate's three measured poses and the nasal port ------------------------
# The rig definition (assets/build/velum-rig.json) is built by glasshead.pipeline.velum_rig and read
# by geometry.velum and web/src/core/velum.js; tests/vectors/velum.json asserts both pose it alike.

#: Format version of the velum rig definition; both evaluators refuse any other version.
VELUM_RIG_FORMAT_VERSION = 1
#: The velum's one parameter: 0 raised (nasal port closed), 1 lowered (open), ratio.
VELUM_PARAMETER = "velum_opening"
#: The measured poses, in the order the parameter passes them (0, the rest share r, 1).
VELUM_POSES = ("raised", "rest", "lowered")
#: mm. Largest difference allowed between the Python and JavaScript velum vertices (float32).
VELUM_VERTEX_TOLERANCE_MM = 1e-3
#: mm^2. Largest difference allowed between the two sides' nasal port areas (float32 positions
#: of about 60 mm carry 4e-6 mm each; a cut sums some 20 gaps of 1 mm width).
VELUM_PORT_TOLERANCE_MM2 = 1e-3

# --- Tract collision: the tongue against the velum and the pharyngeal wall ---------------------
# geometry.tract_collision and web/src/core/tractCollision.js (docs/collision.md).

#: mm. The tract collision's origin lies this far in front of the velum's most anterior point
#: (in any pose), at the height of its lowest point, in the mid-sagittal plane.
TRACT_ORIGIN_AHEAD_MM = 12.0
#: The tract meshes the tongue collides with besides the palate, in the order both twins test.
TRACT_COLLISION_MESHES = ("velum", "pharynx")
#: mm. Nearest the tract origin may be to a tract triangle (the build refuses a closer one).
TRACT_ORIGIN_CLEARANCE_MM = 3.0

# --- Built assets: what `glasshead build` writes to the assets directory -------------------------
# Written by glasshead.pipeline, loaded once by glasshead.asset_store and served by the API.

#: The build manifest (meshes, content hashes); written last, so it names only finished files.
MANIFEST_FILE = "manifest.json"
#: The face.node id of each face_skin vertex (-1: laid onto a lip), beside the skin's GLB.
SKIN_NODES_FILE = "face_skin_nodes.json"
#: Format version of the manifest; the asset store refuses any other version.
MANIFEST_FORMAT_VERSION = 1
#: The tongue rig definition (glasshead.geometry.tongue_rig).
TONGUE_RIG_FILE = "tongue-rig.json"
#: The face rig definition (glasshead.geometry.face).
FACE_RIG_FILE = "face-rig.json"
#: The liner and voxel tables (glasshead.geometry.collision_format).
COLLISION_TABLES_FILE = "collision-tables.bin"
#: The EPG electrode layouts (glasshead.epg.layout).
EPG_LAYOUT_FILE = "epg-layout.json"
#: The velum rig definition (glasshead.geometry.velum).
VELUM_RIG_FILE = "velum-rig.json"
#: The velum's rest pose and the posterior pharyngeal wall: the meshes the tongue's tract
#: collision reads besides the velum rig (glasshead.geometry.tract_collision).
VELUM_REST_GLB = "velum_rest.glb"
PHARYNX_GLB = "pharynx.glb"
#: The lips at rest: the meshes the flesh points of an utterance pose with the face rig
#: (glasshead.geometry.flesh_points).
UPPER_LIP_GLB = "upper_lip.glb"
LOWER_LIP_GLB = "lower_lip.glb"
#: The teaching landmarks: parts and places of articulation (glasshead.pipeline.landmarks).
LANDMARKS_FILE = "landmarks.json"
#: Format version of the landmarks file; its readers refuse any other version.
LANDMARKS_FORMAT_VERSION = 1
#: The articulation target of every phoneme (glasshead.pipeline.phoneme_targets).
PHONEME_TARGETS_FILE = "phoneme-targets.json"
#: Format version of the phoneme targets file; its readers refuse any other version.
PHONEME_TARGETS_FORMAT_VERSION = 1
#: VocalTractLab's JD3 shapes in the project frame (glasshead.pipeline.vtl_observations).
VTL_OBSERVATIONS_FILE = "vtl-observations.json"
#: The 2D fit of every JD3 shape: errors, parameters, rays (glasshead.pipeline.fit_report).
FIT_REPORT_FILE = "fit-report.json"
#: Format version of the fit report; its readers refuse any other version.
FIT_REPORT_FORMAT_VERSION = 1
#: Vowel formant norms by speaker group, for the listening displays
#: (glasshead.pipeline.vowel_norms).
VOWEL_NORMS_FILE = "vowel-norms.json"
#: Format version of the vowel norms; its readers refuse any other version.
VOWEL_NORMS_FORMAT_VERSION = 1
#: The tract's still mid-sagittal section and its stations (``glasshead.pipeline.tract_section``).
TRACT_SECTION_FILE = "tract-section.json"
#: The format of ``TRACT_SECTION_FILE``.
TRACT_SECTION_FORMAT_VERSION = 1
#: The inversion's codebook: poses of the head's vowel space with their tube's formants
#: (``glasshead.pipeline.inversion_codebook``).
INVERSION_CODEBOOK_FILE = "inversion-codebook.json"
#: The format of ``INVERSION_CODEBOOK_FILE``.
INVERSION_CODEBOOK_FORMAT_VERSION = 1
#: The vowels of the vowel norms, by Peterson & Barney's codes (ARPAbet in lower case): the
#: vowels a spoken try can be measured against (a lesson item's ``listen``).
VOWEL_NORMS_VOWELS = ("iy", "ih", "eh", "ae", "ah", "aa", "ao", "uh", "uw", "er")
#: The fit report's overlay plots, one SVG per shape, under the assets directory.
FIT_PLOTS_DIR = "fit-plots"
#: The fit report as a page for a browser: a table of every shape with its plot.
FIT_REPORT_PAGE = "fit-report.html"
#: The command that rebuilds every asset, named in the API's 503 answers.
REBUILD_COMMAND = "glasshead build"

# --- Lessons: what an item shows ------------------------------------------------------------------
#: The labelled parts and places of articulation (GET /anatomy/landmarks, kinds "part" and
#: "place"), in the label layer's order: the names a lesson item's ``views.labels`` may list.
LABEL_NAMES = ("lips", "teeth", "alveolar_ridge", "hard_palate", "velum", "uvula", "tongue_tip",
               "tongue_blade", "tongue_front", "tongue_back", "tongue_root", "pharynx", "larynx",
               "nasal_port", "bilabial", "labiodental", "dental", "alveolar", "postalveolar",
               "palatal", "velar", "uvular", "glottal")
#: The camera views a lesson item may open on (web/src/scene/viewPresets.js).
CAMERA_VIEWS = ("profile", "three-quarter", "front")
#: How close a lesson item's camera comes: 1 frames the mouth and throat, 2 is twice as close.
LESSON_ZOOM_RANGE = (1.0, 2.5)
#: What a lesson item shows when it leaves a view out (the lesson format's defaults).
LESSON_VIEW_DEFAULTS: dict[str, Any] = {
    "skin_transparency": 0.6, "cutaway": False, "diagram": False, "cues": True, "labels": False,
    "epg": False, "camera": "profile", "zoom": 1.0}

# --- The tract as a lossy tube (glasshead.acoustics.tube, web/src/core/tubeAcoustics.js) -------
#: Air in the warm, moist tract (SI): density kg/m³, speed of sound m/s, viscosity Pa·s, heat
#: conductivity W/(m·K), specific heat J/(kg·K), and the ratio of specific heats.
TUBE_AIR = {"density": 1.14, "sound_speed": 350.0, "viscosity": 1.86e-5,
            "heat_conductivity": 0.0055, "specific_heat": 1005.0, "heat_ratio": 1.4}
#: The walls per unit area, as Ishizaka, French and Flanagan (1975) measured the relaxed cheek:
#: mass kg/m², resistance Pa·s/m, stiffness Pa/m.
TUBE_WALL = {"mass": 21.0, "resistance": 8000.0, "stiffness": 8.45e6}
#: The band searched for formants, Hz, and the step of the grid they are found on, Hz.
TUBE_FORMANT_BAND_HZ = (100.0, 5000.0)
TUBE_GRID_STEP_HZ = 20.0

# --- The tract's area function (glasshead.acoustics.area_function, core/areaFunction.js) -------
#: Stations along the tract's midline are this far apart, mm.
TRACT_STATION_STEP_MM = 2.0
#: Cross-section area from mid-sagittal width d, A = alpha d^beta (A in cm², d in cm), in the
#: mouth and in the pharynx (below the uvula); the lips' opening is an ellipse of the lips' gap
#: by a mouth width_mm narrowed by narrowing_mm per unit of lip_rounding, never below min_mm.
TRACT_AREA_LAWS = {"oral": {"alpha": 2.5, "beta": 1.5}, "pharynx": {"alpha": 1.0, "beta": 1.5},
                   "lips": {"width_mm": 45.0, "narrowing_mm": 4.0, "min_mm": 8.0}}
#: The larynx's tube from the glottis to the airway's lower end: length mm and area mm².
TRACT_LARYNX_TUBE = {"length_mm": 10.0, "area_mm2": 50.0}
#: A section narrower than this (mm, mid-sagittal) is shut: the rigs do not press tissue together,
#: so a stop's section keeps a gap (the targets' stops leave 0.28 to 0.71 mm, the narrowest
#: fricative, /ʃ/, 1.57 mm).
TRACT_CLOSURE_MM = 1.0
#: A shut section still passes this area (mm²), so that a closed tract has a transfer function.
TRACT_MIN_AREA_MM2 = 0.1

# --- The tongue from the voice (glasshead.acoustics.inversion, core/listen/inversion.js) -------
#: How far a measured formant may lie from a codebook pose's, in natural-log units, for one unit
#: of cost (F1, F2, F3): a frame's acoustic cost is the mean of the three squared ratios.
INVERSION_FORMANT_SD = (0.10, 0.08, 0.15)
#: Weight of the prior: the pose's mean squared distance, in each parameter's spread over the
#: anchors, from its nearest anchor target.
INVERSION_PRIOR_WEIGHT = 1.0
#: Weight of continuity: the mean squared distance, in the same units, from the frame before's pose.
INVERSION_CONTINUITY_WEIGHT = 2.0
#: Poses kept per frame for the search over a whole track (the best by acoustic cost and prior).
INVERSION_CANDIDATES = 16
#: A frame whose best pose costs more than this acoustically is one the tract cannot make: no
#: tongue is estimated for it.
INVERSION_REJECT_COST = 9.0
