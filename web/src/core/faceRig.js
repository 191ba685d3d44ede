// Face deformation: the skin and lips following the jaw, and the lip parameters. Twin of
// server/glasshead/geometry/face_rig.py and face_teeth.py; tests/vectors/face-rig.json keeps the
// two in agreement. The rig definition (GET /face/rig, built by glasshead.pipeline.face_rig) holds
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
//      faces' normals (upper faces on the maxilla, lower ones carried by the jaw).
// Vertices whose weight and field coefficients are all 0 never move and are skipped.

import { FACE_RIG_FORMAT_VERSION } from './constants.js';

/** Meshes the rig deforms, in the definition's order. */
export const FACE_MESHES = Object.freeze( [ 'face_skin', 'upper_lip', 'lower_lip', 'head_shell' ] );
/** Meshes kept in front of the incisors (the head shell never comes near them). */
export const TEETH_MESHES = Object.freeze( [ 'face_skin', 'upper_lip', 'lower_lip' ] );
/** Lip parameter names in table order: the order of the values applyFaceRig() reads. */
export const LIP_PARAMETER_NAMES = Object.freeze( [ 'lip_opening', 'lip_rounding', 'lip_protrusion', 'upper_lip_raise', 'lower_lip_tuck' ] );

const OPENING = 0;
const ROUNDING = 1;
const PROTRUSION = 2;
const RAISE = 3;
const TUCK = 4;

/** Per-vertex field coefficients, COEFF_COUNT per vertex (as in face_rig.py). */
const COEFF_PROTRUSION = 0;
const COEFF_ROUND_X = 1;
const COEFF_ROUND_Z = 2;
const COEFF_RAISE = 3;
const COEFF_TUCK = 4;
const COEFF_CLOSURE = 5;
export const COEFF_COUNT = 6;

/** Slots of rig.gaps: the lips' gap before closure, after the pose, and scratch for lipGap(). */
export const GAP_NATURAL = 0;
export const GAP_LIPS = 1;
const GAP_SCRATCH = 2;

/** Below this rotation (radians) the jaw motion is a pure translation. */
const SCREW_MIN_ANGLE = 1e-9;
/** mm. Largest distance between a mesh's rest vertex and the rig's probe of it. */
export const PROBE_TOLERANCE_MM = 1e-3;

/** The quintic smoothstep 6t^5 - 15t^4 + 10t^3 of t clamped to [0, 1]. */
function smoothstep5( t ) {

	const c = t < 0 ? 0 : ( t > 1 ? 1 : t );
	return c * c * c * ( c * ( 6 * c - 15 ) + 10 );

}

/** Compact bump with a flat top (face_rig.smooth_bump). */
function bumpAt( bump, x, y, z ) {

	const dx = ( x - bump.centre[ 0 ] ) / bump.radii[ 0 ];
	const dy = ( y - bump.centre[ 1 ] ) / bump.radii[ 1 ];
	const dz = ( z - bump.centre[ 2 ] ) / bump.radii[ 2 ];
	const r = Math.sqrt( dx * dx + dy * dy + dz * dz );
	return smoothstep5( ( 1 - r ) / ( 1 - bump.plateau ) );

}

/**
 * Build the real-time rig: per-mesh weights, field coefficients and scratch arrays, all allocated
 * here once.
 * @param {object} definition the face rig (GET /face/rig)
 * @param {Object<string, Float32Array|Float64Array>} rest rest positions of every mesh in
 *   FACE_MESHES, xyz per vertex, in the vertex order of the built GLBs
 * @returns {object} the rig, for applyFaceRig()
 */
export function createFaceRig( definition, rest ) {

	if ( definition?.format_version !== FACE_RIG_FORMAT_VERSION ) {

		throw new Error( `face rig format_version ${ definition?.format_version } is not ${ FACE_RIG_FORMAT_VERSION }` );

	}

	const names = definition.parameters.map( ( p ) => p.name );
	if ( names.join() !== LIP_PARAMETER_NAMES.join() ) throw new Error( `face rig parameters are ${ names.join( ', ' ) }, expected ${ LIP_PARAMETER_NAMES.join( ', ' ) }` );
	const field = definition.field;
	const meshes = {};
	for ( const name of FACE_MESHES ) {

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
		screw: new Float64Array( 11 ),
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

	const p = new Float64Array( 3 );
	for ( const table of [ rig.teeth.lower, rig.teeth.upper ] ) {

		const { x, n } = table;
		const middle = Math.floor( n[ T_ROWS ] / 2 ) * n[ T_COLS ] + Math.floor( n[ T_COLS ] / 2 );
		const y = n[ T_Y0 ] + Math.floor( n[ T_ROWS ] / 2 ) * n[ T_STEP_Y ];
		const z = n[ T_Z0 ] + Math.floor( n[ T_COLS ] / 2 ) * n[ T_STEP_Z ];
		for ( const depth of [ - 1, 0.5, n[ T_DEPTH ] + 1, 0.5, - 1 ] ) {

			p[ 0 ] = x[ middle ] - depth; p[ 1 ] = y; p[ 2 ] = z;
			pushOut( x, n, p );

		}

	}

	const angle = 10 * Math.PI / 180;
	const turned = Float64Array.of( Math.cos( angle ), Math.sin( angle ), 0, 1, - Math.sin( angle ), Math.cos( angle ), 0, - 2, 0, 0, 1, 0 );
	const still = Float64Array.of( 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 );
	const values = lipValues( rig, { lip_opening: 0.5, lip_rounding: 2, lip_protrusion: 1, upper_lip_raise: 1, lower_lip_tuck: 1 } );
	for ( const pose of [ still, turned ] ) {

		frameNumbers( rig, values, pose );
		for ( const name of FACE_MESHES ) {

			const mesh = rig.meshes[ name ];
			const few = mesh.moving.slice( 0, 16 );
			shapeAndSkin( mesh.rest, mesh.weights, mesh.coeffs, few, mesh.work, rig.frame );
			clampToTeeth( few, mesh.work, rig.teeth, pose );

		}

	}

	const scratch = {};
	for ( const name of FACE_MESHES ) scratch[ name ] = new Float32Array( 3 * rig.meshes[ name ].count );
	applyFaceRig( rig, values, turned, scratch );
	applyFaceRig( rig, values, still, scratch );
	for ( const name of FACE_MESHES ) rig.meshes[ name ].work.set( rig.meshes[ name ].rest );

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
	const coeffs = new Float64Array( COEFF_COUNT * count );
	const { mouth: mouthBump, raise: raiseBump, tuck: tuckBump } = field.bumps;
	const halfWidth = field.mouth_half_width;
	const moving = [];
	for ( let v = 0; v < count; v ++ ) {

		const x = rest[ 3 * v ];
		const y = rest[ 3 * v + 1 ];
		const z = rest[ 3 * v + 2 ];
		const w = weights[ v ];
		const mouth = bumpAt( mouthBump, x, y, z );
		const zn = z / halfWidth;
		const medial = zn * Math.exp( 0.5 * ( 1 - zn * zn ) );
		const o = COEFF_COUNT * v;
		coeffs[ o + COEFF_PROTRUSION ] = mouth;
		coeffs[ o + COEFF_ROUND_X ] = mouth * ( field.rounding_forward * Math.exp( - zn * zn ) + field.rounding_along_arch * Math.abs( medial ) );
		coeffs[ o + COEFF_ROUND_Z ] = - mouth * medial;
		coeffs[ o + COEFF_RAISE ] = bumpAt( raiseBump, x, y, z ) * ( 1 - w );
		coeffs[ o + COEFF_TUCK ] = bumpAt( tuckBump, x, y, z ) * w;
		coeffs[ o + COEFF_CLOSURE ] = mouth * ( w - field.closure_upper_share );
		let still = w === 0;
		for ( let k = 0; k < COEFF_COUNT && still; k ++ ) still = coeffs[ o + k ] === 0;
		if ( ! still ) moving.push( v );

	}

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
		moving: Uint32Array.from( moving ),
		/** Posed positions, float64, xyz per vertex. */
		work: Float64Array.from( rest ),
		teeth: TEETH_MESHES.includes( name ),
		/** Lips only: midline edges (vertex pairs), the reference vertex, crossing scratch. */
		edges: Uint32Array.from( lip ? spec.midline_edges.flat() : [] ),
		reference: lip ? spec.reference_vertex : - 1,
		crossY: new Float64Array( crossings ),
		crossF: new Float64Array( crossings ),
	};
	return mesh;

}

/**
 * Lip values in LIP_PARAMETER_NAMES order from an object of named values (neutral when absent),
 * refusing a value that is not a finite number within its range.
 * @param {object} rig from createFaceRig()
 * @param {Object<string, number>} params
 * @param {Float64Array} target length 5
 * @returns {Float64Array} target
 */
export function lipValues( rig, params, target = new Float64Array( LIP_PARAMETER_NAMES.length ) ) {

	rig.definition.parameters.forEach( ( spec, k ) => {

		const value = params[ spec.name ] ?? spec.neutral;
		if ( typeof value !== 'number' || ! Number.isFinite( value ) || value < spec.min || value > spec.max ) {

			throw new RangeError( `${ spec.name } = ${ value } is outside [${ spec.min }, ${ spec.max }] ${ spec.unit }` );

		}

		target[ k ] = value;

	} );
	return target;

}

/**
 * Screw decomposition of a jaw pose (face_rig.jaw_screw): axis u, angle, slide along u, the
 * translation's part perpendicular to u, t_perp, and u x t_perp.
 * @param {ArrayLike<number>} pose row-major 3 x 4 [ R | t ] (jaw.js jawPose())
 * @param {Float64Array} target length 11
 */
export function jawScrew( pose, target ) {

	const sx = pose[ 9 ] - pose[ 6 ];
	const sy = pose[ 2 ] - pose[ 8 ];
	const sz = pose[ 4 ] - pose[ 1 ];
	const length = Math.sqrt( sx * sx + sy * sy + sz * sz );
	const sinAngle = 0.5 * length;
	const cosAngle = 0.5 * ( pose[ 0 ] + pose[ 5 ] + pose[ 10 ] - 1 );
	let angle = Math.atan2( sinAngle, cosAngle );
	let ux = 0;
	let uy = 0;
	let uz = 1;
	if ( angle < SCREW_MIN_ANGLE ) {

		angle = 0;

	} else {

		ux = sx / length; uy = sy / length; uz = sz / length;

	}

	const tx = pose[ 3 ];
	const ty = pose[ 7 ];
	const tz = pose[ 11 ];
	const slide = ux * tx + uy * ty + uz * tz;
	const px = tx - slide * ux;
	const py = ty - slide * uy;
	const pz = tz - slide * uz;
	target[ 0 ] = ux; target[ 1 ] = uy; target[ 2 ] = uz; target[ 3 ] = angle; target[ 4 ] = slide;
	target[ 5 ] = px; target[ 6 ] = py; target[ 7 ] = pz;
	target[ 8 ] = uy * pz - uz * py; target[ 9 ] = uz * px - ux * pz; target[ 10 ] = ux * py - uy * px;
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
const F_SCREW = 13; // the 11 numbers of jawScrew()
const FRAME_SIZE = F_SCREW + 11;

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
 * Steps 1 and 2 for one mesh's moving vertices, into work. Everything arrives as typed arrays
 * read inside the loop: the compiled loop is entered with no property to look up, and has seen
 * every operation (without rotation the screw is a pure slide, a = w and b = 0, written as
 * arithmetic on F_TURNING rather than a branch first met after compilation).
 */
function shapeAndSkin( rest, weights, coeffs, moving, work, frame ) {

	for ( let k = 0; k < moving.length; k ++ ) {

		const v = moving[ k ];
		const o = 3 * v;
		const c6 = COEFF_COUNT * v;
		const raise = coeffs[ c6 + COEFF_RAISE ] * frame[ F_RAISE ];
		const tuckBy = coeffs[ c6 + COEFF_TUCK ] * frame[ F_TUCK ];
		const x = rest[ o ] + ( raise * frame[ F_RAISE_DIR ] + tuckBy * frame[ F_TUCK_DIR ] ) + ( frame[ F_PROTRUSION ] * coeffs[ c6 + COEFF_PROTRUSION ] + frame[ F_FORWARD ] * coeffs[ c6 + COEFF_ROUND_X ] );
		const y = rest[ o + 1 ] + ( raise * frame[ F_RAISE_DIR + 1 ] + tuckBy * frame[ F_TUCK_DIR + 1 ] );
		const z = rest[ o + 2 ] + ( raise * frame[ F_RAISE_DIR + 2 ] + tuckBy * frame[ F_TUCK_DIR + 2 ] ) + frame[ F_ROUNDING ] * coeffs[ c6 + COEFF_ROUND_Z ];
		const ux = frame[ F_SCREW ];
		const uy = frame[ F_SCREW + 1 ];
		const uz = frame[ F_SCREW + 2 ];
		const turning = frame[ F_TURNING ];
		const halfCot = frame[ F_HALF_COT ];
		const w = weights[ v ];
		const phi = w * frame[ F_SCREW + 3 ];
		const c = Math.cos( phi );
		const s = Math.sin( phi );
		const a = turning * ( 0.5 * ( 1 - c ) + halfCot * s ) + ( 1 - turning ) * w;
		const b = turning * ( halfCot * ( 1 - c ) - 0.5 * s );
		const slide = w * frame[ F_SCREW + 4 ];
		const dot = ( ux * x + uy * y + uz * z ) * ( 1 - c );
		work[ o ] = x * c + ( uy * z - uz * y ) * s + dot * ux + a * frame[ F_SCREW + 5 ] + b * frame[ F_SCREW + 8 ] + slide * ux;
		work[ o + 1 ] = y * c + ( uz * x - ux * z ) * s + dot * uy + a * frame[ F_SCREW + 6 ] + b * frame[ F_SCREW + 9 ] + slide * uy;
		work[ o + 2 ] = z * c + ( ux * y - uy * x ) * s + dot * uz + a * frame[ F_SCREW + 7 ] + b * frame[ F_SCREW + 10 ] + slide * uz;

	}

}

// Hot paths pass numbers through typed arrays, never as arguments or return values of calls that
// may not be inlined: a boxed double per call would make garbage every frame.

/**
 * The midline crossings of a lip: for each edge with ends on both sides of z = 0, the height
 * where it crosses (mesh.crossY) and the closure factor there (mesh.crossF).
 */
function crossings( mesh, positions ) {

	const { edges, coeffs, crossY, crossF } = mesh;
	for ( let k = 0; k < crossY.length; k ++ ) {

		const a = edges[ 2 * k ];
		const b = edges[ 2 * k + 1 ];
		const za = positions[ 3 * a + 2 ];
		const t = za / ( za - positions[ 3 * b + 2 ] );
		crossY[ k ] = positions[ 3 * a + 1 ] + t * ( positions[ 3 * b + 1 ] - positions[ 3 * a + 1 ] );
		crossF[ k ] = ( 1 - t ) * coeffs[ COEFF_COUNT * a + COEFF_CLOSURE ] + t * coeffs[ COEFF_COUNT * b + COEFF_CLOSURE ];

	}

}

/**
 * The lips' mid-sagittal gap, mm: the lowest crossing of the upper lip above the highest of the
 * lower lip; 0 when they touch or overlap.
 * @param {object} rig from createFaceRig()
 * @param {ArrayLike<number>} upper posed upper-lip positions (xyz per vertex)
 * @param {ArrayLike<number>} lower posed lower-lip positions
 */
export function lipGap( rig, upper, lower ) {

	measureGap( rig, upper, lower, GAP_SCRATCH );
	return rig.gaps[ GAP_SCRATCH ];

}

/** lipGap() into rig.gaps[ slot ]. */
function measureGap( rig, upper, lower, slot ) {

	const up = rig.meshes.upper_lip;
	const low = rig.meshes.lower_lip;
	crossings( up, upper );
	crossings( low, lower );
	let upperLowest = Infinity;
	for ( let k = 0; k < up.crossY.length; k ++ ) if ( up.crossY[ k ] < upperLowest ) upperLowest = up.crossY[ k ];
	let lowerHighest = - Infinity;
	for ( let k = 0; k < low.crossY.length; k ++ ) if ( low.crossY[ k ] > lowerHighest ) lowerHighest = low.crossY[ k ];
	rig.gaps[ slot ] = Math.max( 0, upperLowest - lowerHighest );

}

/**
 * Vertical closure c (mm) bringing the gap to `target` (face_rig.solve_closure), from the
 * crossings of the last lipGap(): a crossing's height becomes y + factor * c, the gap is piecewise
 * linear and decreasing in c, and each step is a Newton step on the current extreme pair.
 */
function solveClosure( up, low, target, iterations, closure ) {

	const { crossY: uy, crossF: uf } = up;
	const { crossY: ly, crossF: lf } = low;
	let c = 0;
	for ( let step = 0; step < iterations; step ++ ) {

		let iu = 0;
		for ( let k = 1; k < uy.length; k ++ ) if ( uy[ k ] + uf[ k ] * c < uy[ iu ] + uf[ iu ] * c ) iu = k;
		let il = 0;
		for ( let k = 1; k < ly.length; k ++ ) if ( ly[ k ] + lf[ k ] * c > ly[ il ] + lf[ il ] * c ) il = k;
		const gap = ( uy[ iu ] + uf[ iu ] * c ) - ( ly[ il ] + lf[ il ] * c );
		const slope = lf[ il ] - uf[ iu ];
		if ( slope <= 0 || Math.abs( gap - target ) < 1e-9 ) break;
		c += ( gap - target ) / slope;

	}

	closure[ 1 ] = c;

}

/**
 * Pose the face: every mesh in FACE_MESHES, written into `out`.
 * @param {object} rig from createFaceRig()
 * @param {ArrayLike<number>} values the lip parameters in LIP_PARAMETER_NAMES order, in range
 * @param {ArrayLike<number>} pose the jaw pose, row-major 3 x 4 (jaw.js jawPose())
 * @param {Object<string, Float32Array|Float64Array>} out posed positions per mesh (xyz per vertex),
 *   holding the rest positions where vertices never move (restFaceRig() once)
 * @returns {object} the rig: its lip gap in rig.gaps[ GAP_LIPS ], closure and counts
 */
export function applyFaceRig( rig, values, pose, out ) {

	const { field, meshes } = rig;
	frameNumbers( rig, values, pose );
	for ( let m = 0; m < FACE_MESHES.length; m ++ ) {

		const mesh = meshes[ FACE_MESHES[ m ] ];
		shapeAndSkin( mesh.rest, mesh.weights, mesh.coeffs, mesh.moving, mesh.work, rig.frame );

	}

	const up = meshes.upper_lip;
	const low = meshes.lower_lip;
	measureGap( rig, up.work, low.work, GAP_NATURAL );
	const natural = rig.gaps[ GAP_NATURAL ];
	const opening = values[ OPENING ];
	const target = opening * natural;
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
	for ( let m = 0; m < FACE_MESHES.length; m ++ ) {

		const name = FACE_MESHES[ m ];
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
 * Copy every mesh's rest positions into `out` (the vertices applyFaceRig() never moves keep
 * them from then on).
 */
export function restFaceRig( rig, out ) {

	for ( const name of FACE_MESHES ) out[ name ].set( rig.meshes[ name ].rest );
	return out;

}

// --- Teeth (face_teeth.py) ------------------------------------------------------------------------

/** Layout of a table's numbers (table.n, Float64Array), read by the per-vertex code. */
const T_Y0 = 0;
const T_Z0 = 1;
const T_STEP_Y = 2;
const T_STEP_Z = 3;
const T_ROWS = 4;
const T_COLS = 5;
const T_RECESSION = 6;
const T_DEPTH = 7;
const T_STEPS = 8;
const T_X_MAX = 9;

/** A table of the definition as typed arrays: values x and numbers n (T_* layout). */
function teethTable( table ) {

	const x = Float64Array.from( table.x );
	// The face never lies in front of its largest table value: a cheap exact early-out.
	const n = Float64Array.of( table.y0, table.z0, table.step_y, table.step_z, table.rows, table.cols, table.recession, table.depth ?? 0, table.steps ?? 0, Math.max( ...x ) );
	return { x, n };

}

const scratchBound = new Float64Array( 3 );
const scratchQuery = new Float64Array( 3 );

/**
 * The labial face x = F( y, z ) of a row of incisors (a table of the definition), bilinear in
 * its table, receding by recession * ( distance outside, mm )^2 beyond it; F, dF/dy and dF/dz
 * into target.
 */
export function teethBound( table, y, z, target ) {

	const { x, n } = teethTable( table );
	scratchQuery[ 1 ] = y;
	scratchQuery[ 2 ] = z;
	return teethBoundAt( x, n, scratchQuery, target );

}

/** teethBound() at the point p ( y = p[ 1 ], z = p[ 2 ] ) for table values x and numbers n. */
function teethBoundAt( x, n, p, target ) {

	const rows = n[ T_ROWS ];
	const cols = n[ T_COLS ];
	const stepY = n[ T_STEP_Y ];
	const stepZ = n[ T_STEP_Z ];
	const recession = n[ T_RECESSION ];
	const fy = ( p[ 1 ] - n[ T_Y0 ] ) / stepY;
	const fz = ( p[ 2 ] - n[ T_Z0 ] ) / stepZ;
	const cy = fy < 0 ? 0 : ( fy > rows - 1 ? rows - 1 : fy );
	const cz = fz < 0 ? 0 : ( fz > cols - 1 ? cols - 1 : fz );
	const iy = Math.min( Math.floor( cy ), rows - 2 );
	const iz = Math.min( Math.floor( cz ), cols - 2 );
	const ty = cy - iy;
	const tz = cz - iz;
	const v00 = x[ iy * cols + iz ];
	const v01 = x[ iy * cols + iz + 1 ];
	const v10 = x[ ( iy + 1 ) * cols + iz ];
	const v11 = x[ ( iy + 1 ) * cols + iz + 1 ];
	const low = ( 1 - tz ) * v00 + tz * v01;
	const high = ( 1 - tz ) * v10 + tz * v11;
	const outY = ( fy - cy ) * stepY;
	const outZ = ( fz - cz ) * stepZ;
	target[ 0 ] = ( 1 - ty ) * low + ty * high - recession * ( outY * outY + outZ * outZ );
	const left = ( 1 - ty ) * v00 + ty * v10;
	const right = ( 1 - ty ) * v01 + ty * v11;
	target[ 1 ] = ( outY === 0 ? ( high - low ) / stepY : 0 ) - 2 * recession * outY;
	target[ 2 ] = ( outZ === 0 ? ( right - left ) / stepZ : 0 ) - 2 * recession * outZ;
	return target;

}

/**
 * Push one point (in the table's frame, in p[ 0..2 ]) out of a face (values x, numbers n);
 * returns 1 if it moved, else 0. Everything is read from typed arrays and the moves are written
 * as arithmetic rather than branches (a step that does not move adds 0): the compiled code has
 * seen every operation before its first frame.
 */
function pushOut( x, n, p ) {

	let moved = 0;
	for ( let step = 0; step < n[ T_STEPS ]; step ++ ) {

		// F <= xMax - recession * ( distance outside the table )^2: most points are in front.
		const fy = ( p[ 1 ] - n[ T_Y0 ] ) / n[ T_STEP_Y ];
		const fz = ( p[ 2 ] - n[ T_Z0 ] ) / n[ T_STEP_Z ];
		const outY = ( fy < 0 ? fy : ( fy > n[ T_ROWS ] - 1 ? fy - n[ T_ROWS ] + 1 : 0 ) ) * n[ T_STEP_Y ];
		const outZ = ( fz < 0 ? fz : ( fz > n[ T_COLS ] - 1 ? fz - n[ T_COLS ] + 1 : 0 ) ) * n[ T_STEP_Z ];
		if ( p[ 0 ] >= n[ T_X_MAX ] - n[ T_RECESSION ] * ( outY * outY + outZ * outZ ) ) break;
		teethBoundAt( x, n, p, scratchBound );
		const behind = scratchBound[ 0 ] - p[ 0 ];
		const hit = behind > 0 && behind < n[ T_DEPTH ] ? 1 : 0;
		const dy = scratchBound[ 1 ];
		const dz = scratchBound[ 2 ];
		const s = hit * behind / ( 1 + dy * dy + dz * dz );
		p[ 0 ] += s;
		p[ 1 ] -= s * dy;
		p[ 2 ] -= s * dz;
		moved |= hit;

	}

	return moved;

}

const scratchPoint = new Float64Array( 3 );

/** Step 4 for one mesh: the lower row in the rest mandible's frame, then the upper row. */
function clampToTeeth( moving, work, teeth, pose ) {

	const p = scratchPoint;
	const lowerX = teeth.lower.x;
	const lowerN = teeth.lower.n;
	const upperX = teeth.upper.x;
	const upperN = teeth.upper.n;
	let count = 0;
	for ( let k = 0; k < moving.length; k ++ ) {

		const o = 3 * moving[ k ];
		// Rest mandible frame: R^T ( x - t ).
		const dx = work[ o ] - pose[ 3 ];
		const dy = work[ o + 1 ] - pose[ 7 ];
		const dz = work[ o + 2 ] - pose[ 11 ];
		p[ 0 ] = pose[ 0 ] * dx + pose[ 4 ] * dy + pose[ 8 ] * dz;
		p[ 1 ] = pose[ 1 ] * dx + pose[ 5 ] * dy + pose[ 9 ] * dz;
		p[ 2 ] = pose[ 2 ] * dx + pose[ 6 ] * dy + pose[ 10 ] * dz;
		const lower = pushOut( lowerX, lowerN, p );
		// Back to the posed frame only when moved (lower = 1): a point left alone keeps its
		// exact coordinates, not their round trip.
		work[ o ] += lower * ( pose[ 0 ] * p[ 0 ] + pose[ 1 ] * p[ 1 ] + pose[ 2 ] * p[ 2 ] + pose[ 3 ] - work[ o ] );
		work[ o + 1 ] += lower * ( pose[ 4 ] * p[ 0 ] + pose[ 5 ] * p[ 1 ] + pose[ 6 ] * p[ 2 ] + pose[ 7 ] - work[ o + 1 ] );
		work[ o + 2 ] += lower * ( pose[ 8 ] * p[ 0 ] + pose[ 9 ] * p[ 1 ] + pose[ 10 ] * p[ 2 ] + pose[ 11 ] - work[ o + 2 ] );
		p[ 0 ] = work[ o ]; p[ 1 ] = work[ o + 1 ]; p[ 2 ] = work[ o + 2 ];
		const upper = pushOut( upperX, upperN, p );
		work[ o ] = p[ 0 ]; work[ o + 1 ] = p[ 1 ]; work[ o + 2 ] = p[ 2 ];
		count += lower + upper;

	}

	return count;

}
