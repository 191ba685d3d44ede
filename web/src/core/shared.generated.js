// Generated from server/glasshead/constants.py by server/glasshead/shared_constants.py:
// do not edit. After changing constants.py, regenerate it from the repository root with
//   .venv/bin/python -m glasshead.shared_constants
// (tests/test_shared_constants.py fails while it is stale). Import from ./constants.js.

/** Units of every length in the project frame. */
export const FRAME_UNITS = 'mm';
export const FRAME_AXES = Object.freeze( { x: 'anterior', y: 'superior', z: 'left' } );
/**
 * Origin of the project frame, given as a point of the Badin (ArtiSynth) source frame, in metres.
 * It is a round point inside the oral cavity, above the tongue dorsum and behind the incisors, so
 * that every anatomical coordinate stays within about +-150 mm.
 */
export const BADIN_ORIGIN_M = Object.freeze( [ 0.08, 0.0, 0.1 ] );
/**
 * Rows map Badin axes (x posterior, y subject's right, z superior; right-handed) to project axes.
 */
export const BADIN_TO_PROJECT_AXES = Object.freeze( [
	Object.freeze( [ - 1.0, 0.0, 0.0 ] ),
	Object.freeze( [ 0.0, 0.0, 1.0 ] ),
	Object.freeze( [ 0.0, - 1.0, 0.0 ] ),
] );
/** Metres to millimetres. */
export const M_TO_MM = 1000.0;
/** Rows and columns of the EPG grid. */
export const EPG_ROWS = 8;
export const EPG_COLUMNS = 8;
/** Cells per frame in the flat layout (row-major, R1 first): 8 * 8. */
export const EPG_CELLS = 64;
/** Electrodes on the palate: 8 * 8 minus the two missing corners of R1. */
export const EPG_ELECTRODES = 62;
/** Flat cell indices (row * 8 + column) that have no electrode: R1 columns 1 and 8. */
export const EPG_MISSING_CELLS = Object.freeze( [ 0, 7 ] );
/** Zones as half-open row ranges: alveolar R1-R2, palatal R3-R5, velar R6-R8. */
export const EPG_ZONES = Object.freeze( {
	alveolar: Object.freeze( [ 0, 2 ] ),
	palatal: Object.freeze( [ 2, 5 ] ),
	velar: Object.freeze( [ 5, 8 ] ),
} );
/**
 * The panels of the EPG index plots (epg.plot draws them as SVG, web/src/ui/IndexPlot.js on a
 * canvas): per index its title, a short label for a narrow axis, and the range its definition
 * bounds it to (emuR: percentages 0-100, the centre of gravity 0-8 rows, the rest 0-1).
 */
export const EPG_PLOT_PANELS = Object.freeze( {
	percent: Object.freeze( {
		label: 'Percent contact',
		short_label: '% contact',
		range: Object.freeze( [ 0.0, 100.0 ] ),
	} ),
	cog: Object.freeze( {
		label: 'Centre of gravity',
		short_label: 'COG',
		range: Object.freeze( [ 0.0, 8.0 ] ),
	} ),
	anteriority: Object.freeze( {
		label: 'Anteriority index',
		short_label: 'anteriority',
		range: Object.freeze( [ 0.0, 1.0 ] ),
	} ),
	centrality: Object.freeze( {
		label: 'Centrality index',
		short_label: 'centrality',
		range: Object.freeze( [ 0.0, 1.0 ] ),
	} ),
	dorsopalatal: Object.freeze( {
		label: 'Dorsopalatal index',
		short_label: 'dorsopalatal',
		range: Object.freeze( [ 0.0, 1.0 ] ),
	} ),
	alveolar_percent: Object.freeze( {
		label: 'Alveolar contact %',
		short_label: '% alveolar',
		range: Object.freeze( [ 0.0, 100.0 ] ),
	} ),
	palatal_percent: Object.freeze( {
		label: 'Palatal contact %',
		short_label: '% palatal',
		range: Object.freeze( [ 0.0, 100.0 ] ),
	} ),
	velar_percent: Object.freeze( {
		label: 'Velar contact %',
		short_label: '% velar',
		range: Object.freeze( [ 0.0, 100.0 ] ),
	} ),
} );
/** The panels an index plot shows unless asked for others, top to bottom. */
export const EPG_PLOT_DEFAULT_PANELS = Object.freeze( [
	'percent',
	'cog',
	'anteriority',
	'centrality',
	'dorsopalatal',
] );
/**
 * Codes of a recording compared with a reference, per electrode (POST /epg/recordings/{id}/compare
 * and the palatogram that draws it): both off, both on, contacted in the recording only, in the
 * reference only, and no electrode there (R1 columns 1 and 8).
 */
export const EPG_COMPARE_BOTH_OFF = 0;
export const EPG_COMPARE_BOTH_ON = 1;
export const EPG_COMPARE_ONLY_RECORDING = 2;
export const EPG_COMPARE_ONLY_REFERENCE = 3;
export const EPG_COMPARE_NO_ELECTRODE = 9;
/** Format version of the binary collision tables; a reader refuses any other version. */
export const COLLISION_TABLES_FORMAT_VERSION = 1;
/** Magic bytes that open a collision tables file. */
export const COLLISION_TABLES_MAGIC = 'GHCOLTAB';
/** Liner step in longitude and in latitude, degrees (see docs in geometry/liner.py). */
export const COLLISION_LINER_STEP_DEG = 0.5;
/** Voxels per axis of the voxel table (the paper's 32 x 32 x 32). */
export const COLLISION_VOXELS = 32;
/** Voxel classes: certainly outside, straddling the surface, certainly inside. */
export const VOXEL_OK = 0;
export const VOXEL_BORDER = 1;
export const VOXEL_NOT_OK = 2;
/**
 * Liner cell kinds: no triangle seen from O in the cell (every ray misses); one triangle covers the
 * cell and is the first hit everywhere in it (a plane test); a short triangle list.
 */
export const CELL_EMPTY = 0;
export const CELL_PLANE = 1;
export const CELL_LIST = 2;
/**
 * Per-vertex flags: screened by the voxel table (untouched), tested against the liner and found
 * outside (untouched), corrected (moved along the line toward O onto the surface).
 */
export const FLAG_SCREENED = 0;
export const FLAG_TESTED = 1;
export const FLAG_CORRECTED = 2;
/** Largest vertex count accepted by POST /collision/correct. */
export const COLLISION_MAX_VERTICES = 20000;
/**
 * The arrays of the tables' payload, in payload order, with their dtypes (numpy's notation: "<f4"
 * little-endian float32, "<u4" uint32, "|u1" uint8); see geometry.collision_format.
 */
export const COLLISION_TABLES_ARRAYS = Object.freeze( {
	node_radius: '<f4',
	cell_kind: '|u1',
	cell_rmin: '<f4',
	cell_rmax: '<f4',
	cell_offsets: '<u4',
	cell_triangles: '<u4',
	triangles: '<f4',
	planes: '<f4',
	voxels: '|u1',
} );
/** Every tolerance of the collision tables in one place, with the reason for each. */
export const COLLISION_TOL = Object.freeze( {
	angle: 1e-9,
	length: 1e-5,
	barycentric: 1e-9,
	surface: 0.001,
	depth: 0.1,
} );
/** Format version of the tongue rig definition; both evaluators refuse any other version. */
export const TONGUE_RIG_FORMAT_VERSION = 2;
/**
 * The least radial control value of the tongue surface, mm: no control of a page comes nearer the
 * hub (a deep groove where the curve has come close to it would take the radius through it).
 */
export const TONGUE_CONTROL_FLOOR_MM = 1.0;
/**
 * mm. Largest difference allowed between the Python and JavaScript tongue vertices (JS returns
 * float32 positions: about 4e-6 mm of rounding at 50 mm, far inside this).
 */
export const TONGUE_VERTEX_TOLERANCE_MM = 0.001;
/** Largest relative difference allowed between the two sides' tongue volumes. */
export const TONGUE_VOLUME_RELATIVE_TOLERANCE = 0.0001;
/** Format version of the electrode layout file; both readers refuse any other version. */
export const EPG_LAYOUT_FORMAT_VERSION = 1;
/**
 * mm. An electrode is contacted when the tongue surface crosses its probe: the segment along the
 * electrode's normal from EPG_CONTACT_BEHIND_MM behind it (inside the palate) to this far in front
 * of it (toward the tongue). 1 mm is about the thickness of a real EPG plate's electrode and of the
 * saliva film that closes the circuit.
 */
export const EPG_CONTACT_TOLERANCE_MM = 1.0;
/**
 * mm. How far behind the electrode the probe reaches: a corrected tongue lies on the palate within
 * 0.1 mm (COLLISION_TOL.depth), so half a millimetre catches every touch.
 */
export const EPG_CONTACT_BEHIND_MM = 0.5;
/** Electrode grids: the Reading 62-electrode palate and a dense grid of 12 rows of 8. */
export const EPG_GRIDS = Object.freeze( [ 'reading62', 'dense96' ] );
export const EPG_DENSE_ROWS = 12;
/** Format version of the face rig definition; both evaluators refuse any other version. */
export const FACE_RIG_FORMAT_VERSION = 1;
/** mm. Largest difference allowed between the Python and JavaScript face vertices. */
export const FACE_VERTEX_TOLERANCE_MM = 0.001;
/**
 * The meshes the rig deforms, in the definition's order: the skin, the lips and the shell that
 * closes the head (it shares the skin's rim, which rides on the jaw under the chin).
 */
export const FACE_RIG_MESHES = Object.freeze( [
	'face_skin',
	'upper_lip',
	'lower_lip',
	'head_shell',
] );
/** The two lips, whose mid-sagittal gap the rig measures and closes. */
export const FACE_RIG_LIP_MESHES = Object.freeze( [ 'upper_lip', 'lower_lip' ] );
/** Meshes kept in front of the incisors (the shell never comes near them). */
export const FACE_RIG_TEETH_MESHES = Object.freeze( [ 'face_skin', 'upper_lip', 'lower_lip' ] );
/**
 * Lip parameter names, in the order of the definition's table and of the values both evaluators
 * read.
 */
export const FACE_RIG_LIP_PARAMETERS = Object.freeze( [
	'lip_opening',
	'lip_rounding',
	'lip_protrusion',
	'upper_lip_raise',
	'lower_lip_tuck',
] );
/** Field coefficients per vertex: protrusion, rounding (x and z), raise, tuck, closure. */
export const FACE_RIG_COEFF_COUNT = 6;
/** Format version of the velum rig definition; both evaluators refuse any other version. */
export const VELUM_RIG_FORMAT_VERSION = 1;
/** The velum's one parameter: 0 raised (nasal port closed), 1 lowered (open), ratio. */
export const VELUM_PARAMETER = 'velum_opening';
/** The measured poses, in the order the parameter passes them (0, the rest share r, 1). */
export const VELUM_POSES = Object.freeze( [ 'raised', 'rest', 'lowered' ] );
/** mm. Largest difference allowed between the Python and JavaScript velum vertices (float32). */
export const VELUM_VERTEX_TOLERANCE_MM = 0.001;
/**
 * mm^2. Largest difference allowed between the two sides' nasal port areas (float32 positions of
 * about 60 mm carry 4e-6 mm each; a cut sums some 20 gaps of 1 mm width).
 */
export const VELUM_PORT_TOLERANCE_MM2 = 0.001;
/**
 * mm. The tract collision's origin lies this far in front of the velum's most anterior point (in
 * any pose), at the height of its lowest point, in the mid-sagittal plane.
 */
export const TRACT_ORIGIN_AHEAD_MM = 12.0;
/** The tract meshes the tongue collides with besides the palate, in the order both twins test. */
export const TRACT_COLLISION_MESHES = Object.freeze( [ 'velum', 'pharynx' ] );
/** mm. Nearest the tract origin may be to a tract triangle (the build refuses a closer one). */
export const TRACT_ORIGIN_CLEARANCE_MM = 3.0;
/** The build manifest (meshes, content hashes); written last, so it names only finished files. */
export const MANIFEST_FILE = 'manifest.json';
/** The face.node id of each face_skin vertex (-1: laid onto a lip), beside the skin's GLB. */
export const SKIN_NODES_FILE = 'face_skin_nodes.json';
/** Format version of the manifest; the asset store refuses any other version. */
export const MANIFEST_FORMAT_VERSION = 1;
/** The tongue rig definition (glasshead.geometry.tongue_rig). */
export const TONGUE_RIG_FILE = 'tongue-rig.json';
/** The face rig definition (glasshead.geometry.face). */
export const FACE_RIG_FILE = 'face-rig.json';
/** The liner and voxel tables (glasshead.geometry.collision_format). */
export const COLLISION_TABLES_FILE = 'collision-tables.bin';
/** The EPG electrode layouts (glasshead.epg.layout). */
export const EPG_LAYOUT_FILE = 'epg-layout.json';
/** The velum rig definition (glasshead.geometry.velum). */
export const VELUM_RIG_FILE = 'velum-rig.json';
/**
 * The velum's rest pose and the posterior pharyngeal wall: the meshes the tongue's tract collision
 * reads besides the velum rig (glasshead.geometry.tract_collision).
 */
export const VELUM_REST_GLB = 'velum_rest.glb';
export const PHARYNX_GLB = 'pharynx.glb';
/**
 * The lips at rest: the meshes the flesh points of an utterance pose with the face rig
 * (glasshead.geometry.flesh_points).
 */
export const UPPER_LIP_GLB = 'upper_lip.glb';
export const LOWER_LIP_GLB = 'lower_lip.glb';
/** The teaching landmarks: parts and places of articulation (glasshead.pipeline.landmarks). */
export const LANDMARKS_FILE = 'landmarks.json';
/** Format version of the landmarks file; its readers refuse any other version. */
export const LANDMARKS_FORMAT_VERSION = 1;
/** The articulation target of every phoneme (glasshead.pipeline.phoneme_targets). */
export const PHONEME_TARGETS_FILE = 'phoneme-targets.json';
/** Format version of the phoneme targets file; its readers refuse any other version. */
export const PHONEME_TARGETS_FORMAT_VERSION = 1;
/** VocalTractLab's JD3 shapes in the project frame (glasshead.pipeline.vtl_observations). */
export const VTL_OBSERVATIONS_FILE = 'vtl-observations.json';
/** The 2D fit of every JD3 shape: errors, parameters, rays (glasshead.pipeline.fit_report). */
export const FIT_REPORT_FILE = 'fit-report.json';
/** Format version of the fit report; its readers refuse any other version. */
export const FIT_REPORT_FORMAT_VERSION = 1;
/**
 * Vowel formant norms by speaker group, for the listening displays
 * (glasshead.pipeline.vowel_norms).
 */
export const VOWEL_NORMS_FILE = 'vowel-norms.json';
/** Format version of the vowel norms; its readers refuse any other version. */
export const VOWEL_NORMS_FORMAT_VERSION = 1;
/**
 * The tract's still mid-sagittal section and its stations (``glasshead.pipeline.tract_section``).
 */
export const TRACT_SECTION_FILE = 'tract-section.json';
/** The format of ``TRACT_SECTION_FILE``. */
export const TRACT_SECTION_FORMAT_VERSION = 1;
/**
 * The inversion's codebook: poses of the head's vowel space with their tube's formants
 * (``glasshead.pipeline.inversion_codebook``).
 */
export const INVERSION_CODEBOOK_FILE = 'inversion-codebook.json';
/** The format of ``INVERSION_CODEBOOK_FILE``. */
export const INVERSION_CODEBOOK_FORMAT_VERSION = 1;
/**
 * The vowels of the vowel norms, by Peterson & Barney's codes (ARPAbet in lower case): the vowels a
 * spoken try can be measured against (a lesson item's ``listen``).
 */
export const VOWEL_NORMS_VOWELS = Object.freeze( [
	'iy',
	'ih',
	'eh',
	'ae',
	'ah',
	'aa',
	'ao',
	'uh',
	'uw',
	'er',
] );
/** The fit report's overlay plots, one SVG per shape, under the assets directory. */
export const FIT_PLOTS_DIR = 'fit-plots';
/** The fit report as a page for a browser: a table of every shape with its plot. */
export const FIT_REPORT_PAGE = 'fit-report.html';
/** The command that rebuilds every asset, named in the API's 503 answers. */
export const REBUILD_COMMAND = 'glasshead build';
/**
 * The labelled parts and places of articulation (GET /anatomy/landmarks, kinds "part" and "place"),
 * in the label layer's order: the names a lesson item's ``views.labels`` may list.
 */
export const LABEL_NAMES = Object.freeze( [
	'lips',
	'teeth',
	'alveolar_ridge',
	'hard_palate',
	'velum',
	'uvula',
	'tongue_tip',
	'tongue_blade',
	'tongue_front',
	'tongue_back',
	'tongue_root',
	'pharynx',
	'larynx',
	'nasal_port',
	'bilabial',
	'labiodental',
	'dental',
	'alveolar',
	'postalveolar',
	'palatal',
	'velar',
	'uvular',
	'glottal',
] );
/** The camera views a lesson item may open on (web/src/scene/viewPresets.js). */
export const CAMERA_VIEWS = Object.freeze( [ 'profile', 'three-quarter', 'front' ] );
/** How close a lesson item's camera comes: 1 frames the mouth and throat, 2 is twice as close. */
export const LESSON_ZOOM_RANGE = Object.freeze( [ 1.0, 2.5 ] );
/** What a lesson item shows when it leaves a view out (the lesson format's defaults). */
export const LESSON_VIEW_DEFAULTS = Object.freeze( {
	skin_transparency: 0.6,
	cutaway: false,
	diagram: false,
	cues: true,
	labels: false,
	epg: false,
	camera: 'profile',
	zoom: 1.0,
} );
/**
 * Air in the warm, moist tract (SI): density kg/m³, speed of sound m/s, viscosity Pa·s, heat
 * conductivity W/(m·K), specific heat J/(kg·K), and the ratio of specific heats.
 */
export const TUBE_AIR = Object.freeze( {
	density: 1.14,
	sound_speed: 350.0,
	viscosity: 1.86e-5,
	heat_conductivity: 0.0055,
	specific_heat: 1005.0,
	heat_ratio: 1.4,
} );
/**
 * The walls per unit area, as Ishizaka, French and Flanagan (1975) measured the relaxed cheek: mass
 * kg/m², resistance Pa·s/m, stiffness Pa/m.
 */
export const TUBE_WALL = Object.freeze( { mass: 21.0, resistance: 8000.0, stiffness: 8450000.0 } );
/** The band searched for formants, Hz, and the step of the grid they are found on, Hz. */
export const TUBE_FORMANT_BAND_HZ = Object.freeze( [ 100.0, 5000.0 ] );
export const TUBE_GRID_STEP_HZ = 20.0;
/** Stations along the tract's midline are this far apart, mm. */
export const TRACT_STATION_STEP_MM = 2.0;
/**
 * Cross-section area from mid-sagittal width d, A = alpha d^beta (A in cm², d in cm), in the mouth
 * and in the pharynx (below the uvula); the lips' opening is an ellipse of the lips' gap by a mouth
 * width_mm narrowed by narrowing_mm per unit of lip_rounding, never below min_mm.
 */
export const TRACT_AREA_LAWS = Object.freeze( {
	oral: Object.freeze( { alpha: 2.5, beta: 1.5 } ),
	pharynx: Object.freeze( { alpha: 1.0, beta: 1.5 } ),
	lips: Object.freeze( { width_mm: 45.0, narrowing_mm: 4.0, min_mm: 8.0 } ),
} );
/** The larynx's tube from the glottis to the airway's lower end: length mm and area mm². */
export const TRACT_LARYNX_TUBE = Object.freeze( { length_mm: 10.0, area_mm2: 50.0 } );
/**
 * A section narrower than this (mm, mid-sagittal) is shut: the rigs do not press tissue together,
 * so a stop's section keeps a gap (the targets' stops leave 0.28 to 0.71 mm, the narrowest
 * fricative, /ʃ/, 1.57 mm).
 */
export const TRACT_CLOSURE_MM = 1.0;
/** A shut section still passes this area (mm²), so that a closed tract has a transfer function. */
export const TRACT_MIN_AREA_MM2 = 0.1;
/**
 * How far a measured formant may lie from a codebook pose's, in natural-log units, for one unit of
 * cost (F1, F2, F3): a frame's acoustic cost is the mean of the three squared ratios.
 */
export const INVERSION_FORMANT_SD = Object.freeze( [ 0.1, 0.08, 0.15 ] );
/**
 * Weight of the prior: the pose's mean squared distance, in each parameter's spread over the
 * anchors, from its nearest anchor target.
 */
export const INVERSION_PRIOR_WEIGHT = 1.0;
/**
 * Weight of continuity: the mean squared distance, in the same units, from the frame before's pose.
 */
export const INVERSION_CONTINUITY_WEIGHT = 2.0;
/** Poses kept per frame for the search over a whole track (the best by acoustic cost and prior). */
export const INVERSION_CANDIDATES = 16;
/**
 * A frame whose best pose costs more than this acoustically is one the tract cannot make: no tongue
 * is estimated for it.
 */
export const INVERSION_REJECT_COST = 9.0;
