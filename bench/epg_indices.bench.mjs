// Benchmark: EPG indices per frame in JavaScript over the 1,421 real frames of the emuR engassim
// set. Prints the median time per frame of the kernel (web/src/core/epgIndices.js) and of a
// naive baseline measured in the same run (an 8 x 8 array of arrays per frame and one pass per
// index, the way emuR's R code reads), and their ratio. Goal: kernel median under 0.05 ms.
//
//   node bench/epg_indices.bench.mjs            (GLASSHEAD_DATA_DIR overrides ../shared/data)
//   GLASSHEAD_BENCH_QUICK=1                      11 runs instead of 301
import { readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { performance } from 'node:perf_hooks';

import { EPG_CELLS } from '../web/src/core/constants.js';
import { INDEX_SLOTS, INDEX_STRIDE, epgIndicesAll, rowsToFrame } from '../web/src/core/epgIndices.js';
import { check, count } from './support/quick.mjs';
import { median } from './support/stats.mjs';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( HERE, '..', '..', 'shared', 'data' );
const RUNS = count( 301, 11 );
const WARMUP = count( 50, 3 );
const GOAL_MS = 0.05;

const segments = JSON.parse( readFileSync( join( DATA_DIR, 'epg', 'emur-engassim.json' ), 'utf8' ) ).segments;
const rows = segments.flatMap( ( s ) => s.frames.map( ( f ) => f.rows ) );
const n = rows.length;
const frames = new Uint8Array( n * EPG_CELLS );
rows.forEach( ( r, i ) => rowsToFrame( r, frames, i ) );
const target = new Float64Array( n * INDEX_STRIDE );

// The baseline: per frame, an array of 8 row arrays, then separate passes per index.
function naiveIndices( flat, i ) {

	const grid = [];
	for ( let r = 0; r < 8; r ++ ) grid.push( Array.from( flat.subarray( i * 64 + r * 8, i * 64 + r * 8 + 8 ) ) );
	const sum = ( a ) => a.reduce( ( x, y ) => x + y, 0 );
	const rowSums = grid.map( sum );
	const colSum = ( c ) => sum( grid.map( ( row ) => row[ c ] ) );
	const total = sum( rowSums );
	const zone = ( lo, hi ) => sum( rowSums.slice( lo, hi ) );
	const cogW = [ 7.5, 6.5, 5.5, 4.5, 3.5, 2.5, 1.5, 0.5 ];
	const aiW = [ 4921 / 6, 729 / 8, 81 / 8, 9 / 8, 1 / 8 ];
	const ciW = [ 1 / 14, 17 / 16, 289 / 16, 4913 / 16 ];
	const pairs = [ 0, 1, 2, 3 ].map( ( k ) => colSum( k ) + colSum( 7 - k ) );
	return {
		contacts: total, percent: 100 * total / 62, rows: rowSums,
		alveolar: zone( 0, 2 ), palatal: zone( 2, 5 ), velar: zone( 5, 8 ),
		cog: total ? sum( rowSums.map( ( s, r ) => s * cogW[ r ] ) ) / total : 0,
		anteriority: Math.log( 1 + sum( rowSums.slice( 0, 5 ).map( ( s, r ) => s * aiW[ r ] ) ) ) / Math.log( 5742 ),
		centrality: Math.log( 1 + sum( pairs.map( ( p, k ) => p * ciW[ k ] ) ) ) / Math.log( 5221 ),
		dorsopalatal: zone( 5, 8 ) / 24,
	};

}

function perFrameMedian( run ) {

	for ( let k = 0; k < WARMUP; k ++ ) run();
	const times = [];
	for ( let k = 0; k < RUNS; k ++ ) {

		const t0 = performance.now();
		run();
		times.push( ( performance.now() - t0 ) / n );

	}

	return median( times );

}

let sink = 0;
const kernelMs = perFrameMedian( () => {

	epgIndicesAll( frames, n, target );
	sink += target[ 16 ];

} );
const naive = new Array( n );
const naiveMs = perFrameMedian( () => {

	for ( let i = 0; i < n; i ++ ) naive[ i ] = naiveIndices( frames, i );
	sink += naive[ 0 ].cog;

} );

// Both must compute the same thing, or the comparison means nothing.
let firstDifference = '';
for ( let i = 0; i < n && ! firstDifference; i ++ ) for ( const name of [ 'cog', 'anteriority', 'centrality', 'dorsopalatal', 'percent' ] ) {

	const a = target[ i * INDEX_STRIDE + INDEX_SLOTS.indexOf( name ) ];
	if ( ! ( Math.abs( a - naive[ i ][ name ] ) <= 1e-9 ) ) firstDifference ||= `frame ${i} ${name}: kernel ${a}, baseline ${naive[ i ][ name ]}`;

}

const result = {
	benchmark: 'epg_indices', frames: n, runs: RUNS,
	kernel_median_ms_per_frame: Number( kernelMs.toPrecision( 3 ) ),
	naive_median_ms_per_frame: Number( naiveMs.toPrecision( 3 ) ),
	speedup: Number( ( naiveMs / kernelMs ).toFixed( 1 ) ),
	goal_ms: GOAL_MS, goal_met: kernelMs < GOAL_MS,
};
console.log( `EPG indices, ${n} real frames, median of ${RUNS} runs (${sink > 0 ? 'checked' : '?'})` );
console.log( `  kernel    ${( kernelMs * 1000 ).toFixed( 3 )} us per frame` );
console.log( `  naive     ${( naiveMs * 1000 ).toFixed( 3 )} us per frame` );
console.log( `  speed-up  ${result.speedup}x; goal < ${GOAL_MS} ms per frame: ${result.goal_met ? 'met' : 'NOT met'}` );
console.log( JSON.stringify( result ) );
check( `the kernel's indices are the baseline's on all ${ n } frames`, n > 0 && firstDifference === '', firstDifference || 'no frames' );
