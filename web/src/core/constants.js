// Project-wide constants, mirrored from server/glasshead/constants.py.
// tests/vectors/constants.json holds the Python values; tests/js/constants.test.js checks them.

/** Units of every length in the project frame. */
export const FRAME_UNITS = 'mm';

/** +x anterior, +y superior, +z toward the subject's left; z = 0 is the mid-sagittal plane. */
export const FRAME_AXES = Object.freeze( { x: 'anterior', y: 'superior', z: 'left' } );

// --- Electropalatography (the Reading 62-electrode palate) ---------------------------------------
// A frame is 64 bytes, row-major: row 0 = R1 (front, alveolar) ... row 7 = R8 (back, velar);
// column 0 = electrode column 1 ... column 7 = column 8. R1 has no electrode in columns 1 and 8.

/** Rows and columns of the EPG grid. */
export const EPG_ROWS = 8;
export const EPG_COLUMNS = 8;
/** Cells per frame in the flat layout (row-major, R1 first): 8 * 8. */
export const EPG_CELLS = EPG_ROWS * EPG_COLUMNS;
/** Electrodes on the palate: 8 * 8 minus the two missing corners of R1. */
export const EPG_ELECTRODES = EPG_CELLS - 2;
/** Flat cell indices (row * 8 + column) that have no electrode: R1 columns 1 and 8. */
export const EPG_MISSING_CELLS = Object.freeze( [ 0, 7 ] );
/** Zones as half-open row ranges: alveolar R1-R2, palatal R3-R5, velar R6-R8. */
export const EPG_ZONES = Object.freeze( {
	alveolar: Object.freeze( [ 0, 2 ] ),
	palatal: Object.freeze( [ 2, 5 ] ),
	velar: Object.freeze( [ 5, 8 ] ),
} );

// --- Tongue-palate collision (the paper's liner and voxel table) ---------------------------------
// Mirrors server/glasshead/constants.py; tests/vectors/collision-constants.json checks both.

/** Format version of the binary collision tables; the loader refuses any other version. */
export const COLLISION_TABLES_FORMAT_VERSION = 1;
/** Magic bytes that open a collision tables file ("GHCOLTAB"). */
export const COLLISION_TABLES_MAGIC = 'GHCOLTAB';
/** Liner step in longitude and in latitude, degrees. */
export const COLLISION_LINER_STEP_DEG = 0.5;
/** Voxels per axis of the voxel table. */
export const COLLISION_VOXELS = 32;
/** Voxel classes: certainly outside, straddling the surface, certainly inside. */
export const VOXEL_OK = 0;
export const VOXEL_BORDER = 1;
export const VOXEL_NOT_OK = 2;
/** Liner cell kinds: every ray misses; one triangle is the first hit (plane test); a short list. */
export const CELL_EMPTY = 0;
export const CELL_PLANE = 1;
export const CELL_LIST = 2;
/** Per-vertex flags: screened (untouched), tested and outside (untouched), corrected. */
export const FLAG_SCREENED = 0;
export const FLAG_TESTED = 1;
export const FLAG_CORRECTED = 2;
/** Largest vertex count accepted by POST /collision/correct. */
export const COLLISION_MAX_VERTICES = 20000;
/** Tolerances of the collision kernels; see CollisionTolerance in constants.py for the reasons. */
export const COLLISION_TOL = Object.freeze( {
	angle: 1e-9,
	length: 1e-5,
	barycentric: 1e-9,
	surface: 1e-3,
	depth: 0.1,
} );

// --- Project frame (mirrors the Badin conversion in server/glasshead/constants.py) ---------------

/** Origin of the project frame as a point of the Badin (ArtiSynth) source frame, metres. */
export const BADIN_ORIGIN_M = Object.freeze( [ 0.080, 0.0, 0.100 ] );
/** Rows map Badin axes (x posterior, y right, z superior) to project axes (anterior, superior, left). */
export const BADIN_TO_PROJECT_AXES = Object.freeze( [
	Object.freeze( [ - 1.0, 0.0, 0.0 ] ),
	Object.freeze( [ 0.0, 0.0, 1.0 ] ),
	Object.freeze( [ 0.0, - 1.0, 0.0 ] ),
] );
/** Metres to millimetres. */
export const M_TO_MM = 1000.0;

// --- Tongue rig ----------------------------------------------------------------------------------

/** Format version of the tongue rig definition; the evaluator refuses any other version. */
export const TONGUE_RIG_FORMAT_VERSION = 1;
/** mm. Largest difference allowed between the Python and JavaScript tongue vertices. */
export const TONGUE_VERTEX_TOLERANCE_MM = 1e-3;
/** Largest relative difference allowed between the two sides' tongue volumes. */
export const TONGUE_VOLUME_RELATIVE_TOLERANCE = 1e-4;

// --- Synthetic EPG: electrode layout and contact (mirrors server/glasshead/constants.py) --------

/** Format version of the electrode layout file; the loader refuses any other version. */
export const EPG_LAYOUT_FORMAT_VERSION = 1;
/** mm. An electrode is contacted when the tongue surface crosses its probe: the segment along its
 * normal from EPG_CONTACT_BEHIND_MM behind it to this far in front of it (toward the tongue). */
export const EPG_CONTACT_TOLERANCE_MM = 1.0;
/** mm. How far behind the electrode (into the palate) the probe reaches. */
export const EPG_CONTACT_BEHIND_MM = 0.5;
/** Electrode grids: the Reading 62-electrode palate and a dense grid of 12 rows of 8. */
export const EPG_GRIDS = Object.freeze( [ 'reading62', 'dense96' ] );
export const EPG_DENSE_ROWS = 12;

// --- Face rig: skin and lips on the jaw, lip parameters (mirrors server/glasshead/constants.py) --

/** Format version of the face rig definition; the evaluator refuses any other version. */
export const FACE_RIG_FORMAT_VERSION = 1;
/** mm. Largest difference allowed between the Python and JavaScript face vertices. */
export const FACE_VERTEX_TOLERANCE_MM = 1e-3;
