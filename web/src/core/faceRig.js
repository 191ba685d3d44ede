// Face deformation: the skin and lips following the jaw, and the lip parameters. Twin of
// server/glasshead/geometry/face_rig.py (the teeth of step 4: faceTeeth.js and face_teeth.py; the
// jaw's screw: jaw.js); tests/vectors/face-rig.json keeps the two in agreement. The rig definition (GET /face/rig, built by glasshead.pipeline.face_rig) holds
// every number used here.
//
// A posed vertex is found in four steps, each a function of its rest position and its jaw weight
// w only, so two meshes sharing a point (a lip and the skin, the skin and the head shell) move it
// identically:
//   1. shape offsets (protrusion, rounding, upper-lip raise, lower-lip tuck): compact bumps about
//      the mouth times a direction, added at rest;
//   2. jaw skinning: the fraction w of the jaw's screw motion (Chasles' theorem; screw linear
//      interpolation as in Kavan, Collins, Zara and O'Sullivan 2008, "Geometric skinning with
//      approximate dual quaternion blending", section 3);
//   3. closure: the lips' mid-sagittal gap is measured and, as far as lip_opening asks, closed by
//      the mouth bump times (w - a) times one vector C solved from the gap;
//   4. teeth: skin and lip points behind the labial faces of the incisors are pushed out along the
//      faces' normals (upper faces on the maxilla, lower ones carried by the jaw; faceTeeth.js).
// Vertices whose weight and field coefficients are all 0 never move and are skipped.

import { FACE_RIG_FORMAT_VERSION, FACE_RIG_LIP_PARAMETERS, FACE_RIG_MESHES, FACE_RIG_TEETH_MESHES } from './constants.js';
import { COEFF_CLOSURE, COEFF_COUNT, COEFF_PROTRUSION, COEFF_RAISE, COEFF_ROUND_X, COEFF_ROUND_Z, COEFF_TUCK, fieldCoefficients } from './faceField.js';
import { clampToTeeth, primeTeeth, teethTable } from './faceTeeth.js';
import { GAP_LIPS, GAP_NATURAL, measureGap, solveClosure } from './lipClosure.js';
import { jawScrew, SCREW_MIN_ANGLE, SCREW_SIZE } from './jaw.js';

// The meshes (FACE_RIG_MESHES), those kept in front of the incisors (FACE_RIG_TEETH_MESHES) and
// the lip parameters in the order of the values poseFace() reads (FACE_RIG_LIP_PARAMETERS) are
// declared once, in server/glasshead/constants.py; the definition carries them too, and a rig
// whose definition does not match them is refused.

const OPENING = 0;
const ROUNDING = 1;
const PROTRUSION = 2;
const RAISE = 3;
const TUCK = 4;

export { GAP_LIPS, GAP_NATURAL, lipGap } from './lipClosure.js';

/** mm. Largest distance between a mesh's rest vertex and the rig's probe of it. */
export const PROBE_TOLERANCE_MM = 1e-3;

/**
 * Build the real-time rig: per-mesh weights, field coefficients and scratch arrays, all allocated
 * here once.
 * @param {object} definition the face rig (GET /face/rig)
 * @param {Object<string, Float32Array|Float64Array>} rest rest positions of every mesh in
 *   FACE_RIG_MESHES, xyz per vertex, in the vertex order of the built GLBs
 * @returns {object} the rig, for poseFace()
 */
export function createFaceRig( definition, rest ) {

	if ( definition?.format_version !== FACE_RIG_FORMAT_VERSION ) {

		throw new Error( `face rig format_version ${ definition?.format_version } is not ${ FACE_RIG_FORMAT_VERSION }` );

	}

	const names = definition.parameters.map( ( p ) => p.name );
	if ( names.join() !== FACE_RIG_LIP_PARAMETERS.join() ) throw new Error( `face rig parameters are ${ names.join( ', ' ) }, expected ${ FACE_RIG_LIP_PARAMETERS.join( ', ' ) }` );
	const field = definition.field;
	const meshes = {};
	for ( const name of FACE_RIG_MESHES ) {

		const spec = definition.meshes[ name ];
		const positions = rest[ name ];
		if ( ! spec ) throw new Error( `face rig has no mesh "${ name }"` );
		if ( ! positions ) throw new Error( `no rest positions for "${ name }"` );
		const count = spec.vertex_count;
		if ( positions.length !== 3 * count ) throw new RangeError( `"${ name }" has ${ positions.length / 3 } vertices; the face rig was built for ${ count }` );
		checkProbes( name, spec.probes, positions );
		meshes[ name ] = prepareMesh( name, spec, Float64Array.from( positions ), field );

	}

	const rig = {
		definition,
		field,
		teeth: { upper: teethTable( definition.teeth.upper ), lower: teethTable( definition.teeth.lower ) },
		meshes,
		screw: new Float64Array( SCREW_SIZE ),
		frame: new Float64Array( FRAME_SIZE ),
		/** The closure vector C of the last pose. */
		closure: new Float64Array( 3 ),
		/** Lip gaps of the last pose, mm: before closure (GAP_NATURAL), after everything (GAP_LIPS). */
		gaps: new Float64Array( 3 ),
		/** Skin and lip points the teeth moved in the last pose. */
		counts: new Int32Array( 1 ),
	};
	primeFaceRig( rig );
	return rig;

}

/**
 * Run every path of the per-vertex code on a few points, then pose the face twice, off screen,
 * before anything is compiled: the optimising compiler then starts from complete type feedback.
 * Code that meets a new operation after compilation falls back to the interpreter, which boxes
 * numbers (garbage every frame) and can keep a hot loop there.
 */
function primeFaceRig( rig ) {

	primeTeeth( rig.teeth );
	const angle = 10 * Math.PI / 180;
	const turned = Float64Array.of( Math.cos( angle ), Math.sin( angle ), 0, 1, - Math.sin( angle ), Math.cos( angle ), 0, - 2, 0, 0, 1, 0 );
	const still = Float64Array.of( 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 );
	const values = lipValues( rig, { lip_opening: 0.5, lip_rounding: 2, lip_protrusion: 1, upper_lip_raise: 1, lower_lip_tuck: 1 } );
	for ( const pose of [ still, turned ] ) {

		frameNumbers( rig, values, pose );
		for ( const name of FACE_RIG_MESHES ) {

			const mesh = rig.meshes[ name ];
			const few = mesh.moving.slice( 0, 16 );
			shapeAndSkin( mesh.rest, mesh.weights, mesh.coeffs, few, mesh.work, rig.frame );
			clampToTeeth( few, mesh.work, rig.teeth, pose );

		}

	}

	const scratch = {};
	for ( const name of FACE_RIG_MESHES ) scratch[ name ] = new Float32Array( 3 * rig.meshes[ name ].count );
	poseFace( rig, values, turned, scratch );
	poseFace( rig, values, still, scratch );
	for ( const name of FACE_RIG_MESHES ) rig.meshes[ name ].work.set( rig.meshes[ name ].rest );

}

function checkProbes( name, probes, positions ) {

	if ( ! probes ) return;
	probes.index.forEach( ( v, k ) => {

		for ( let i = 0; i < 3; i ++ ) {

			if ( Math.abs( positions[ 3 * v + i ] - probes.position[ k ][ i ] ) > PROBE_TOLERANCE_MM ) {

				throw new Error( `"${ name }" vertex ${ v } is not where the face rig has it: the rig was built for other meshes (rebuild with glasshead build)` );

			}

		}

	} );

}

function prepareMesh( name, spec, rest, field ) {

	const count = spec.vertex_count;
	const weights = Float64Array.from( spec.jaw_weights );
	const { coeffs, moving } = fieldCoefficients( rest, weights, field );

	// Every mesh gets the same fields, in the same order (one hidden class for the hot loops).
	const lip = Boolean( spec.midline_edges );
	const crossings = lip ? spec.midline_edges.length : 0;
	const mesh = {
		name,
		count,
		rest,
		weights,
		coeffs,
		/** Vertices that can move (the others always keep their rest position). */
		moving,
		/** Posed positions, float64, xyz per vertex. */
		work: Float64Array.from( rest ),
		teeth: FACE_RIG_TEETH_MESHES.includes( name ),
		/** Lips only: midline edges (vertex pairs), the reference vertex, crossing scratch. */
		edges: Uint32Array.from( lip ? spec.midline_edges.flat() : [] ),
		reference: lip ? spec.reference_vertex : - 1,
		crossY: new Float64Array( crossings ),
		crossF: new Float64Array( crossings ),
	};
	return mesh;

}

/**
 * The vertical gap the closure aims at, mm: the kept gap g = opening x natural, less a press that
 * reaches `press` at opening 0 (closed lips press past level, so that their mid-sagittal sections
 * meet) and fades as g grows to `press` or the opening to 1 (closure_target in face_rig.py).
 */
export function closureTarget( opening, natural, press ) {

	const kept = opening * natural;
	return kept - press * ( 1 - opening ) * Math.max( 0, 1 - kept / press );

}

/**
 * Lip values in FACE_RIG_LIP_PARAMETERS order from an object of named values (neutral when absent),
 * refusing a value that is not a finite number within its range.
 * @param {object} rig from createFaceRig()
 * @param {Object<string, number>} params
 * @param {Float64Array} target length 5
 * @returns {Float64Array} target
 */
export function lipValues( rig, params, target = new Float64Array( FACE_RIG_LIP_PARAMETERS.length ) ) {

	rig.definition.parameters.forEach( ( spec, k ) => {

		const value = params[ spec.name ] ?? spec.neutral;
		if ( typeof value !== 'number' || ! Number.isFinite( value ) || value < spec.min || value > spec.max ) {

			throw new RangeError( `${ spec.name } = ${ value } is outside [${ spec.min }, ${ spec.max }] ${ spec.unit }` );

		}

		target[ k ] = value;

	} );
	return target;

}

/** Layout of rig.frame: the per-pose numbers the vertex loops read. */
const F_ROUNDING = 0;
const F_FORWARD = 1;
const F_PROTRUSION = 2;
const F_RAISE = 3;
const F_TUCK = 4;
const F_RAISE_DIR = 5; // 3 numbers
const F_TUCK_DIR = 8; // 3 numbers
const F_TURNING = 11; // 1 when the jaw turns, 0 for a pure slide
const F_HALF_COT = 12; // cot( angle / 2 ) / 2
const F_SCREW = 13; // the SCREW_SIZE numbers of jawScrew()
const FRAME_SIZE = F_SCREW + SCREW_SIZE;

/** The per-pose numbers of steps 1 and 2, into rig.frame. */
function frameNumbers( rig, values, pose ) {

	const frame = rig.frame;
	const field = rig.field;
	const screw = jawScrew( pose, rig.screw );
	frame[ F_ROUNDING ] = values[ ROUNDING ];
	frame[ F_FORWARD ] = values[ ROUNDING ] > 0 ? values[ ROUNDING ] : 0;
	frame[ F_PROTRUSION ] = values[ PROTRUSION ];
	frame[ F_RAISE ] = values[ RAISE ];
	frame[ F_TUCK ] = values[ TUCK ];
	for ( let i = 0; i < 3; i ++ ) {

		frame[ F_RAISE_DIR + i ] = field.raise_direction[ i ];
		frame[ F_TUCK_DIR + i ] = field.tuck_direction[ i ];

	}

	const turning = screw[ 3 ] > SCREW_MIN_ANGLE ? 1 : 0;
	frame[ F_TURNING ] = turning;
	frame[ F_HALF_COT ] = 0.5 / Math.tan( 0.5 * ( turning ? screw[ 3 ] : 1 ) );
	frame.set( screw, F_SCREW );

}

/**
 * Steps 1 and 2 for one mesh's moving vertices, into work. Everything arrives as typed arrays:
 * the compiled loop is entered with no property to look up, and has seen every operation
 * (without rotation the screw is a pure slide, a = w and b = 0, written as arithmetic on
 * F_TURNING rather than a branch first met after compilation).
 */
function shapeAndSkin( rest, weights, coeffs, moving, work, frame ) {

	// The pose's numbers once, into locals: the loop then reads only the per-vertex arrays.
	const rounding = frame[ F_ROUNDING ], forward = frame[ F_FORWARD ], protrusion = frame[ F_PROTRUSION ];
	const raiseBy = frame[ F_RAISE ], tuck = frame[ F_TUCK ];
	const rx = frame[ F_RAISE_DIR ], ry = frame[ F_RAISE_DIR + 1 ], rz = frame[ F_RAISE_DIR + 2 ];
	const tx = frame[ F_TUCK_DIR ], ty = frame[ F_TUCK_DIR + 1 ], tz = frame[ F_TUCK_DIR + 2 ];
	const ux = frame[ F_SCREW ], uy = frame[ F_SCREW + 1 ], uz = frame[ F_SCREW + 2 ];
	const angle = frame[ F_SCREW + 3 ], along = frame[ F_SCREW + 4 ];
	const px = frame[ F_SCREW + 5 ], py = frame[ F_SCREW + 6 ], pz = frame[ F_SCREW + 7 ];
	const qx = frame[ F_SCREW + 8 ], qy = frame[ F_SCREW + 9 ], qz = frame[ F_SCREW + 10 ];
	const turning = frame[ F_TURNING ];
	const halfCot = frame[ F_HALF_COT ];
	for ( let k = 0; k < moving.length; k ++ ) {

		const v = moving[ k ];
		const o = 3 * v;
		const c6 = COEFF_COUNT * v;
		const raise = coeffs[ c6 + COEFF_RAISE ] * raiseBy;
		const tuckBy = coeffs[ c6 + COEFF_TUCK ] * tuck;
		const x = rest[ o ] + ( raise * rx + tuckBy * tx ) + ( protrusion * coeffs[ c6 + COEFF_PROTRUSION ] + forward * coeffs[ c6 + COEFF_ROUND_X ] );
		const y = rest[ o + 1 ] + ( raise * ry + tuckBy * ty );
		const z = rest[ o + 2 ] + ( raise * rz + tuckBy * tz ) + rounding * coeffs[ c6 + COEFF_ROUND_Z ];
		const w = weights[ v ];
		const phi = w * angle;
		const c = Math.cos( phi );
		const s = Math.sin( phi );
		const a = turning * ( 0.5 * ( 1 - c ) + halfCot * s ) + ( 1 - turning ) * w;
		const b = turning * ( halfCot * ( 1 - c ) - 0.5 * s );
		const slide = w * along;
		const dot = ( ux * x + uy * y + uz * z ) * ( 1 - c );
		work[ o ] = x * c + ( uy * z - uz * y ) * s + dot * ux + a * px + b * qx + slide * ux;
		work[ o + 1 ] = y * c + ( uz * x - ux * z ) * s + dot * uy + a * py + b * qy + slide * uy;
		work[ o + 2 ] = z * c + ( ux * y - uy * x ) * s + dot * uz + a * pz + b * qz + slide * uz;

	}

}

/**
 * Pose the face: every mesh in FACE_RIG_MESHES, written into `out`.
 * @param {object} rig from createFaceRig()
 * @param {ArrayLike<number>} values the lip parameters in FACE_RIG_LIP_PARAMETERS order, in range
 * @param {ArrayLike<number>} pose the jaw pose, row-major 3 x 4 (jaw.js jawPose())
 * @param {Object<string, Float32Array|Float64Array>} out posed positions per mesh (xyz per vertex),
 *   holding the rest positions where vertices never move (restFaceRig() once)
 * @returns {object} the rig: its lip gap in rig.gaps[ GAP_LIPS ], closure and counts
 */
export function poseFace( rig, values, pose, out ) {

	const { field, meshes } = rig;
	frameNumbers( rig, values, pose );
	for ( let m = 0; m < FACE_RIG_MESHES.length; m ++ ) {

		const mesh = meshes[ FACE_RIG_MESHES[ m ] ];
		shapeAndSkin( mesh.rest, mesh.weights, mesh.coeffs, mesh.moving, mesh.work, rig.frame );

	}

	const up = meshes.upper_lip;
	const low = meshes.lower_lip;
	measureGap( rig, up.work, low.work, GAP_NATURAL );
	const natural = rig.gaps[ GAP_NATURAL ];
	const opening = values[ OPENING ];
	const target = closureTarget( opening, natural, field.lip_press_mm );
	const closure = rig.closure;
	closure.fill( 0 );
	if ( natural > 0 && target < natural ) {

		// Forward-backward: give back, by the same share, the change of the lips' relative depth.
		const iu = up.reference;
		const il = low.reference;
		const depthNow = up.work[ 3 * iu ] - low.work[ 3 * il ];
		const depthRest = up.rest[ 3 * iu ] - low.rest[ 3 * il ];
		const slope = low.coeffs[ COEFF_COUNT * il + COEFF_CLOSURE ] - up.coeffs[ COEFF_COUNT * iu + COEFF_CLOSURE ];
		if ( slope > 0 ) closure[ 0 ] = ( 1 - opening ) * ( depthNow - depthRest ) / slope;
		solveClosure( up, low, target, field.closure_iterations, closure );

	}

	let clamped = 0;
	for ( let m = 0; m < FACE_RIG_MESHES.length; m ++ ) {

		const name = FACE_RIG_MESHES[ m ];
		const mesh = meshes[ name ];
		const { coeffs, moving, work } = mesh;
		for ( let k = 0; k < moving.length; k ++ ) {

			const v = moving[ k ];
			const f = coeffs[ COEFF_COUNT * v + COEFF_CLOSURE ];
			work[ 3 * v ] += f * closure[ 0 ];
			work[ 3 * v + 1 ] += f * closure[ 1 ];
			work[ 3 * v + 2 ] += f * closure[ 2 ];

		}

		if ( mesh.teeth ) clamped += clampToTeeth( mesh.moving, mesh.work, rig.teeth, pose );
		const target32 = out[ name ];
		for ( let k = 0; k < moving.length; k ++ ) {

			const o = 3 * moving[ k ];
			target32[ o ] = work[ o ];
			target32[ o + 1 ] = work[ o + 1 ];
			target32[ o + 2 ] = work[ o + 2 ];

		}

	}

	rig.counts[ 0 ] = clamped;
	measureGap( rig, up.work, low.work, GAP_LIPS );
	return rig;

}

/**
 * Copy every mesh's rest positions into `out` (the vertices poseFace() never moves keep
 * them from then on).
 */
export function restFaceRig( rig, out ) {

	for ( const name of FACE_RIG_MESHES ) out[ name ].set( rig.meshes[ name ].rest );
	return out;

}
