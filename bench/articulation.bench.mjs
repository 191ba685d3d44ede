// Benchmark: one frame of the articulation pipeline (web/src/scene/Articulation.js) in Node, for
// seeded random poses (every tongue parameter and the jaw uniform over its range): tongue surface,
// collision correction against the built tables, normals, volume, jaw matrix, lip gap and the
// scene's tongue geometry. Measured in this run, over the same poses:
//   ours      Articulation.update(): preallocated arrays written in place, normals recomputed
//             only when a vertex was corrected;
//   rebuild   the same frame handed to three.js the usual way for a deformed mesh: a new
//             BufferGeometry per frame and BufferGeometry.computeVertexNormals().
//
//   node bench/articulation.bench.mjs [samples]
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { BoxGeometry, BufferAttribute, BufferGeometry } from 'three';

import { Head } from '../web/src/scene/Head.js';
import { Articulation, parameterDefinitions } from '../web/src/scene/Articulation.js';
import { TongueRig } from '../web/src/core/tongue.js';
import { correctVertices } from '../web/src/core/collision.js';
import { ParamState } from '../web/src/core/paramState.js';
import { decodeCollisionTables } from '../web/src/core/tables.js';
import { median, random } from './support/stats.mjs';

const REPO = resolve( dirname( fileURLToPath( import.meta.url ) ), '..' );
const SAMPLES = Number( process.argv[ 2 ] ?? 40 );
const FRAMES = 50; // frames per timed sample, each with new parameters
const SEED = 1998;

function built( name ) {

	const path = join( REPO, 'assets', 'build', name );
	if ( ! existsSync( path ) ) {

		console.error( `${ path } is missing: run \`glasshead build\` first` );
		process.exit( 1 );

	}

	return readFileSync( path );

}

const definition = JSON.parse( built( 'tongue-rig.json' ).toString( 'utf8' ) );
const tables = decodeCollisionTables( built( 'collision-tables.bin' ) );
const rig = new TongueRig( definition );
const state = new ParamState( parameterDefinitions( definition ) );
const head = new Head();
head.addPart( { name: 'tongue_rest', role: 'tongue' }, new BoxGeometry( 40, 20, 30 ) );
head.addPart( { name: 'mandible', role: 'mandible' }, new BoxGeometry( 60, 20, 60 ) );
head.finishLoading();
const articulation = new Articulation( rig, state, { tables } ).attach( head );

const next = random( SEED );
const poses = Array.from( { length: SAMPLES * FRAMES }, () => Float32Array.from( rig.parameters, ( p ) => p.min + ( p.max - p.min ) * next() ) );

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
let corrected = 0;
for ( let k = 0; k < poses.length; k ++ ) {

	ours( k );
	corrected += articulation.stats[ 2 ] > 0 ? 1 : 0;

}

console.log( `articulation frame, ${ rig.vertexCount } tongue vertices, ${ poses.length } random poses (seed ${ SEED }), ${ corrected } touching the palate` );
console.log( `  ours     median ${ oursMs.toFixed( 3 ) } ms per frame` );
console.log( `  rebuild  median ${ rebuildMs.toFixed( 3 ) } ms per frame   (ours faster by ${ ( rebuildMs / oursMs ).toFixed( 1 ) }x)` );
