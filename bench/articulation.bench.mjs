// Benchmark: one frame of the articulation pipeline (web/src/scene/Articulation.js) in Node, on the
// built head loaded as the app loads it (tests/js/support/builtHead.js: every scene mesh through
// GLTFLoader and scene/gltfGeometry.js, the tongue rig, the collision tables), for seeded random
// poses (every tongue parameter and the jaw uniform over its range): tongue surface, collision
// correction, normals, jaw matrix, the lips' gap and the scene's tongue geometry. The face rig and
// the velum are left out (the lower lip rides on the jaw): bench/frame.bench.mjs times the whole
// frame with them. Measured in this run, over the same poses:
//   ours      Articulation.update(): preallocated arrays written in place;
//   rebuild   the same frame handed to three.js the usual way for a deformed mesh: a new
//             BufferGeometry per frame and BufferGeometry.computeVertexNormals().
// Checked: both give the same corrected vertices and the same normals.
//
//   node bench/articulation.bench.mjs [samples]      (GLASSHEAD_BENCH_QUICK=1: 3 samples)
import { BufferAttribute, BufferGeometry } from 'three';

import { correctVertices } from '../web/src/core/collision.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { builtFile } from './support/assets.mjs';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const SAMPLES = Number( process.argv[ 2 ] ?? count( 40, 3 ) );
const FRAMES = 50; // frames per timed sample, each with new parameters
const SEED = 1998;
/** Largest difference allowed between ours and three.js's normals (float32 sums in another order). */
const NORMAL_TOLERANCE = 1e-4;

builtFile( 'manifest.json' ); // exits with a message when there is no build
const { articulation } = await loadBuiltHead();
articulation.setFaceRig( null );
articulation.velum = null;
articulation.setTract( null );
const { rig, state } = articulation;
const tables = articulation.tables;
if ( ! tables ) throw new Error( `the built head has no collision tables: ${ articulation.tablesError }` );

const next = random( SEED );
const poses = Array.from( { length: SAMPLES * FRAMES }, () => Float32Array.from( state.minimum, ( lo, k ) => ( k < rig.parameterCount ? lo + ( state.maximum[ k ] - lo ) * next() : state.values[ k ] ) ) );

function ours( k ) {

	state.values.set( poses[ k ] );
	state.touch();
	articulation.update();

}

const surface = rig.createSurface();
const stats = new Int32Array( 3 );
function rebuild( k ) {

	rig.evaluate( poses[ k ], surface );
	const positions = Float32Array.from( surface.positions );
	correctVertices( positions, rig.vertexCount, tables, null, stats );
	const geometry = new BufferGeometry();
	geometry.setAttribute( 'position', new BufferAttribute( positions, 3 ) );
	geometry.setIndex( new BufferAttribute( rig.index, 1 ) );
	geometry.computeVertexNormals();
	geometry.computeBoundingSphere();
	return geometry;

}

function time( run ) {

	for ( let k = 0; k < FRAMES * 4; k ++ ) run( k % poses.length ); // warm up
	const samples = [];
	for ( let s = 0; s < SAMPLES; s ++ ) {

		const start = performance.now();
		for ( let f = 0; f < FRAMES; f ++ ) run( s * FRAMES + f );
		samples.push( ( performance.now() - start ) / FRAMES );

	}

	return median( samples );

}

const oursMs = time( ours );
const rebuildMs = time( rebuild );
// Both ways give the same tongue: the same corrected vertices, normals within float32 rounding.
let corrected = 0, positionsDiffer = 0, normalGap = 0;
for ( let k = 0; k < poses.length; k ++ ) {

	ours( k );
	corrected += articulation.stats[ 2 ] > 0 ? 1 : 0;
	const geometry = rebuild( k );
	const position = geometry.attributes.position.array, normal = geometry.attributes.normal.array;
	for ( let i = 0; i < position.length; i ++ ) {

		positionsDiffer += position[ i ] !== articulation.positions[ i ] ? 1 : 0;
		normalGap = Math.max( normalGap, Math.abs( normal[ i ] - articulation.normals[ i ] ) );

	}

}

console.log( `articulation frame, ${ rig.vertexCount } tongue vertices, ${ poses.length } random poses (seed ${ SEED }), ${ corrected } touching the palate` );
console.log( `  ours     median ${ oursMs.toFixed( 3 ) } ms per frame` );
console.log( `  rebuild  median ${ rebuildMs.toFixed( 3 ) } ms per frame   (ours faster by ${ ( rebuildMs / oursMs ).toFixed( 1 ) }x)` );
check( 'ours and rebuild give the same tongue', positionsDiffer === 0 && normalGap <= NORMAL_TOLERANCE && corrected > 0, `${ positionsDiffer } coordinates differ, normals up to ${ normalGap.toExponential( 1 ) } apart, ${ corrected } poses touching` );
