// Benchmark: the real-time tongue evaluator (web/src/core/tongue.js) in Node: the full surface
// with normals, for seeded random parameter sets (every parameter uniform over its range, the
// jaw included). Measured in this run, over the same sets:
//   ours    TongueRig.evaluate into a preallocated surface (tables built once, no allocation);
//   cold    the same work with a new TongueRig and surface per call (basis tables, blends and
//           outputs allocated every time: what a per-frame evaluation without setup costs);
//   python  the numpy reference evaluator, surface with normals (bench/tongue_py.py).
// Checked: ours and cold give the same surface and normals, bit for bit, for every set.
// Goal: ours under 0.2 ms median with 2,000 vertices or more.
//
//   node bench/tongue.bench.mjs [samples]      (GLASSHEAD_BENCH_QUICK=1: 3 samples)
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { TongueRig } from '../web/src/core/tongue.js';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const REPO = resolve( HERE, '..' );
const SAMPLES = Number( process.argv[ 2 ] ?? count( 60, 3 ) );
const CALLS = 100; // evaluations per timed sample
const COLD_CALLS = 10;
const SEED = 1998;
const GOAL_MS = 0.2;
const GOAL_VERTICES = 2000;

function loadDefinition() {

	const built = join( REPO, 'assets', 'build', 'tongue-rig.json' );
	if ( existsSync( built ) ) return [ JSON.parse( readFileSync( built, 'utf8' ) ), relative( REPO, built ) ];
	const vectors = join( REPO, 'tests', 'vectors', 'tongue-surface.json' );
	return [ JSON.parse( readFileSync( vectors, 'utf8' ) ).fixtures.rig, `${relative( REPO, vectors )} (rig)` ];

}

/** Median milliseconds per call of run( k ), over `samples` samples of `calls` calls each. */
function time( run, samples, calls ) {

	for ( let k = 0; k < calls; k ++ ) run( k ); // warm-up
	const perCall = [];
	for ( let s = 0; s < samples; s ++ ) {

		const start = performance.now();
		for ( let k = 0; k < calls; k ++ ) run( s * calls + k );
		perCall.push( ( performance.now() - start ) / calls );

	}

	return median( perCall );

}

const [ definition, source ] = loadDefinition();
const rig = new TongueRig( definition );
const next = random( SEED );
const sets = Array.from( { length: 64 }, () => Float64Array.from( rig.minimum, ( low, k ) => low + next() * ( rig.maximum[ k ] - low ) ) );
const surface = rig.createSurface();

const ours = time( ( k ) => rig.evaluate( sets[ k % sets.length ], surface ), SAMPLES, CALLS );
const cold = time( ( k ) => {

	const fresh = new TongueRig( definition );
	fresh.evaluate( sets[ k % sets.length ], fresh.createSurface() );

}, count( Math.max( 5, SAMPLES >> 2 ), 2 ), COLD_CALLS );

const python = spawnSync( join( REPO, '.venv', 'bin', 'python' ), [ join( HERE, 'tongue_py.py' ), '--json' ], { cwd: REPO, encoding: 'utf8' } );
const pythonMs = python.status === 0 ? JSON.parse( python.stdout.trim().split( '\n' ).pop() ).median_ms : NaN;

// The preallocated evaluator keeps no state between calls: a fresh rig gives the same numbers.
let differ = 0;
for ( const values of sets ) {

	rig.evaluate( values, surface );
	const fresh = new TongueRig( definition );
	const other = fresh.createSurface();
	fresh.evaluate( values, other );
	for ( let i = 0; i < surface.positions.length; i ++ ) differ += surface.positions[ i ] !== other.positions[ i ] || surface.normals[ i ] !== other.normals[ i ] ? 1 : 0;

}

const ok = ours < GOAL_MS && rig.vertexCount >= GOAL_VERTICES;
console.log( `rig: ${source}` );
console.log( `tongue surface with normals, ${rig.vertexCount} vertices, ${rig.triangleCount} triangles, ${sets.length} random sets (seed ${SEED})` );
console.log( `  ours   (JS, preallocated)  median ${ours.toFixed( 4 )} ms` );
console.log( `  cold   (JS, setup per call) median ${cold.toFixed( 4 )} ms   ${( cold / ours ).toFixed( 1 )} x ours` );
if ( Number.isFinite( pythonMs ) ) console.log( `  python (numpy reference)   median ${pythonMs.toFixed( 4 )} ms   ${( pythonMs / ours ).toFixed( 1 )} x ours` );
else console.log( `  python: not measured (${( python.stderr || python.error?.message || 'no output' ).trim().split( '\n' ).pop()})` );
console.log( `goal: under ${GOAL_MS} ms with ${GOAL_VERTICES}+ vertices: ${ok ? 'met' : 'NOT met'}` );
check( 'ours and cold give the same surface', differ === 0, `${ differ } coordinates differ` );
