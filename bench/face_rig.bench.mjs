// Benchmark: the real-time face rig (web/src/core/faceRig.js) in Node, on the rig and rest meshes
// of the shared vectors (the built face skin, lips and head shell: about 7,700 vertices), for
// seeded random lip parameters and jaw openings, a quarter of them closing the lips. Measured in
// this run, over the same sets:
//   ours     poseFace: shape fields, screw skinning, closure solve, incisor correction,
//            skipping the vertices that never move;
//   frame    ours plus vertex normals of the four meshes (what a changed frame costs the scene);
//   baseline every vertex of the four meshes moved by the jaw's matrix blended by its weight
//            (linear blend skinning, no lip fields, closure or teeth): the floor of any skinning.
// Goal: a frame under 1 ms median.
//
//   node bench/face_rig.bench.mjs [samples]
import { readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { createFaceRig, lipValues, poseFace, restFaceRig } from '../web/src/core/faceRig.js';
import { FACE_RIG_MESHES } from '../web/src/core/constants.js';
import { jawPose, POSE_LENGTH } from '../web/src/core/jaw.js';
import { vertexNormals } from '../web/src/core/meshVolume.js';
import { median, random } from './support/stats.mjs';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const REPO = resolve( HERE, '..' );
const SAMPLES = Number( process.argv[ 2 ] ?? 40 );
const CALLS = 50; // poses per timed sample
const SEED = 1998;
const GOAL_MS = 1;

/** Median milliseconds per call of run( k ), over SAMPLES samples of CALLS calls each. */
function time( run ) {

	for ( let k = 0; k < 20 * CALLS; k ++ ) run( k ); // let the JIT settle
	const samples = [];
	for ( let s = 0; s < SAMPLES; s ++ ) {

		const start = performance.now();
		for ( let k = 0; k < CALLS; k ++ ) run( s * CALLS + k );
		samples.push( ( performance.now() - start ) / CALLS );

	}

	return median( samples );

}

const vectors = JSON.parse( readFileSync( join( REPO, 'tests', 'vectors', 'face-rig.json' ), 'utf8' ) ).fixtures;
const rest = Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, Float32Array.from( vectors.rest[ name ] ) ] ) );
const rig = createFaceRig( vectors.rig, rest );
const out = restFaceRig( rig, Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, new Float32Array( rest[ name ].length ) ] ) ) );
const vertexCount = FACE_RIG_MESHES.reduce( ( total, name ) => total + rest[ name ].length / 3, 0 );

// Triangles for the normals: the vectors carry positions only, so a fan over each mesh's vertex
// list stands in, with the meshes' real triangle counts (about twice the vertices).
const normals = FACE_RIG_MESHES.map( ( name ) => {

	const count = rest[ name ].length / 3;
	const index = new Uint32Array( 3 * ( 2 * count - 4 ) );
	for ( let t = 0; t < index.length / 3; t ++ ) {

		index[ 3 * t ] = 0; index[ 3 * t + 1 ] = 1 + ( t % ( count - 2 ) ); index[ 3 * t + 2 ] = 2 + ( t % ( count - 2 ) );

	}

	return { name, index, sums: new Float64Array( 3 * count ), target: new Float32Array( 3 * count ) };

} );

const next = random( SEED );
const SETS = 256;
const values = [];
const poses = [];
for ( let k = 0; k < SETS; k ++ ) {

	const params = Object.fromEntries( vectors.rig.parameters.map( ( p ) => [ p.name, p.min + next() * ( p.max - p.min ) ] ) );
	if ( next() < 0.25 ) params.lip_opening = 0;
	values.push( lipValues( rig, params ) );
	poses.push( jawPose( 25 * next(), vectors.jaw, new Float64Array( POSE_LENGTH ) ) );

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

const ours = time( ( k ) => poseFace( rig, values[ k % SETS ], poses[ k % SETS ], out ) );
const frame = time( ( k ) => {

	poseFace( rig, values[ k % SETS ], poses[ k % SETS ], out );
	for ( const n of normals ) vertexNormals( out[ n.name ], n.index, n.sums, n.target );

} );
restFaceRig( rig, out );
const floor = time( ( k ) => baseline( poses[ k % SETS ] ) );
const moving = FACE_RIG_MESHES.reduce( ( total, name ) => total + rig.meshes[ name ].moving.length, 0 );

console.log( `face rig: ${ vertexCount } vertices (${ moving } can move), ${ SETS } seeded sets (seed ${ SEED }), median of ${ SAMPLES } x ${ CALLS } poses` );
console.log( `  ours      ${ ours.toFixed( 3 ) } ms per pose` );
console.log( `  frame     ${ frame.toFixed( 3 ) } ms per pose with normals (goal < ${ GOAL_MS } ms: ${ frame < GOAL_MS ? 'met' : 'missed' })` );
console.log( `  baseline  ${ floor.toFixed( 3 ) } ms per pose (linear blend skinning of every vertex)` );
console.log( `  ratio ours / baseline ${ ( ours / floor ).toFixed( 2 ) }` );
