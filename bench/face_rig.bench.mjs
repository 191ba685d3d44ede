// Benchmark: the real-time face rig (web/src/core/faceRig.js) in Node, on the built head loaded as
// the app loads it (tests/js/support/builtHead.js: the face skin, the lips and the head shell
// through GLTFLoader and scene/gltfGeometry.js, the face rig definition, and the scene's
// FacePose), for seeded random lip parameters and jaw openings over their ranges, a quarter of
// them closing the lips. Measured in this run, over the same sets:
//   ours     poseFace: shape fields, screw skinning, closure solve, incisor correction,
//            skipping the vertices that never move;
//   frame    what a changed frame costs the scene: FacePose.pose (ours, then the normals around
//            the moving vertices, their bounding spheres and the seam welded again);
//   baseline every vertex of the four meshes moved by the jaw's matrix blended by its weight
//            (linear blend skinning, no lip fields, closure or teeth): the floor of any skinning.
// Checked: every vertex the rig skips has no jaw weight and no field coefficient (so it never
// moves), every posed vertex is finite, and the lips asked to close (lip_opening 0) close.
// Goal: a frame under 1 ms median.
//
//   node bench/face_rig.bench.mjs [samples]      (GLASSHEAD_BENCH_QUICK=1: 3 samples, less warm-up)
import { GAP_LIPS, lipValues, poseFace, restFaceRig } from '../web/src/core/faceRig.js';
import { COEFF_COUNT } from '../web/src/core/faceField.js';
import { FACE_RIG_MESHES } from '../web/src/core/constants.js';
import { jawPose, POSE_LENGTH } from '../web/src/core/jaw.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { builtFile } from './support/assets.mjs';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const SAMPLES = Number( process.argv[ 2 ] ?? count( 40, 3 ) );
const CALLS = 50; // poses per timed sample
const WARM_CALLS = count( 20, 2 ) * CALLS; // let the JIT settle
const SEED = 1998;
const GOAL_MS = 1;
/** mm: the closure is solved by a few fixed-point iterations; lips asked to close end this near. */
const CLOSED_GAP_MM = 0.05;

/** Median milliseconds per call of run( k ), over SAMPLES samples of CALLS calls each. */
function time( run ) {

	for ( let k = 0; k < WARM_CALLS; k ++ ) run( k );
	const samples = [];
	for ( let s = 0; s < SAMPLES; s ++ ) {

		const start = performance.now();
		for ( let k = 0; k < CALLS; k ++ ) run( s * CALLS + k );
		samples.push( ( performance.now() - start ) / CALLS );

	}

	return median( samples );

}

builtFile( 'face-rig.json' ); // exits with a message when there is no build
const { articulation } = await loadBuiltHead();
const face = articulation.faceRig;
if ( ! face ) throw new Error( `the built head has no face rig: ${ articulation.faceRigError }` );
const rig = face.rig;
const out = face.out;
const rest = Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, Float32Array.from( rig.meshes[ name ].rest ) ] ) );
const vertexCount = FACE_RIG_MESHES.reduce( ( total, name ) => total + rest[ name ].length / 3, 0 );

// Seeded sets: lip values (the rig's order) and the state's values with them (FacePose reads
// those), and a jaw pose from the jaw parameter's range.
const state = articulation.state;
const jaw = articulation.rig.jaw;
const jawIndex = articulation.jawIndex;
const next = random( SEED );
const SETS = 256;
const values = [], states = [], poses = [], closing = [];
for ( let k = 0; k < SETS; k ++ ) {

	const params = Object.fromEntries( rig.definition.parameters.map( ( p ) => [ p.name, p.min + next() * ( p.max - p.min ) ] ) );
	if ( next() < 0.25 ) params.lip_opening = 0;
	closing.push( params.lip_opening === 0 );
	values.push( lipValues( rig, params ) );
	const full = Float32Array.from( state.values );
	for ( const [ name, value ] of Object.entries( params ) ) full[ state.indexOf( name ) ] = value;
	const opening = state.minimum[ jawIndex ] + next() * ( state.maximum[ jawIndex ] - state.minimum[ jawIndex ] );
	full[ jawIndex ] = opening;
	states.push( full );
	poses.push( jawPose( opening, jaw, new Float64Array( POSE_LENGTH ) ) );

}

const weights = Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, rig.meshes[ name ].weights ] ) );
function baseline( pose ) {

	for ( const name of FACE_RIG_MESHES ) {

		const p = rest[ name ];
		const q = out[ name ];
		const w = weights[ name ];
		for ( let v = 0; v < w.length; v ++ ) {

			const o = 3 * v;
			const x = p[ o ];
			const y = p[ o + 1 ];
			const z = p[ o + 2 ];
			const s = w[ v ];
			q[ o ] = x + s * ( pose[ 0 ] * x + pose[ 1 ] * y + pose[ 2 ] * z + pose[ 3 ] - x );
			q[ o + 1 ] = y + s * ( pose[ 4 ] * x + pose[ 5 ] * y + pose[ 6 ] * z + pose[ 7 ] - y );
			q[ o + 2 ] = z + s * ( pose[ 8 ] * x + pose[ 9 ] * y + pose[ 10 ] * z + pose[ 11 ] - z );

		}

	}

}

// The checks, before timing: the skipped vertices cannot move; the poses are finite and close
// the lips when asked.
let movable = 0;
for ( const name of FACE_RIG_MESHES ) {

	const mesh = rig.meshes[ name ];
	const moving = new Uint8Array( mesh.weights.length );
	for ( const v of mesh.moving ) moving[ v ] = 1;
	for ( let v = 0; v < moving.length; v ++ ) {

		if ( moving[ v ] ) continue;
		let any = mesh.weights[ v ] !== 0;
		for ( let c = 0; c < COEFF_COUNT; c ++ ) any ||= mesh.coeffs[ COEFF_COUNT * v + c ] !== 0;
		movable += any ? 1 : 0;

	}

}

let nonFinite = 0, widestClosed = 0, closed = 0;
for ( let k = 0; k < SETS; k ++ ) {

	poseFace( rig, values[ k ], poses[ k ], out );
	for ( const name of FACE_RIG_MESHES ) for ( const x of out[ name ] ) nonFinite += Number.isFinite( x ) ? 0 : 1;
	if ( closing[ k ] ) {

		closed ++;
		widestClosed = Math.max( widestClosed, rig.gaps[ GAP_LIPS ] );

	}

}

restFaceRig( rig, out );

const ours = time( ( k ) => poseFace( rig, values[ k % SETS ], poses[ k % SETS ], out ) );
const frame = time( ( k ) => face.pose( states[ k % SETS ], poses[ k % SETS ] ) );
restFaceRig( rig, out );
const floor = time( ( k ) => baseline( poses[ k % SETS ] ) );
restFaceRig( rig, out );
const moving = FACE_RIG_MESHES.reduce( ( total, name ) => total + rig.meshes[ name ].moving.length, 0 );

console.log( `face rig on the built head: ${ vertexCount } vertices (${ moving } can move), ${ SETS } seeded sets (seed ${ SEED }), median of ${ SAMPLES } x ${ CALLS } poses` );
console.log( `  ours      ${ ours.toFixed( 3 ) } ms per pose` );
console.log( `  frame     ${ frame.toFixed( 3 ) } ms per pose in the scene, with normals (goal < ${ GOAL_MS } ms: ${ frame < GOAL_MS ? 'met' : 'missed' })` );
console.log( `  baseline  ${ floor.toFixed( 3 ) } ms per pose (linear blend skinning of every vertex)` );
console.log( `  ratio ours / baseline ${ ( ours / floor ).toFixed( 2 ) }` );
console.log( `  lips asked to close: ${ closed } sets, widest gap left ${ widestClosed.toFixed( 4 ) } mm` );
check( 'every vertex the rig skips has no weight and no field', movable === 0, `${ movable } skipped vertices could move` );
check( 'every posed vertex is finite', nonFinite === 0, `${ nonFinite } coordinates are not` );
check( 'the lips asked to close close', closed > 0 && widestClosed <= CLOSED_GAP_MM, `widest gap ${ widestClosed.toFixed( 4 ) } mm over ${ closed } sets` );
