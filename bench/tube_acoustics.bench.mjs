// Benchmark: the formants of a 40-section tube in JavaScript (web/src/core/tubeAcoustics.js), on
// tubes of the shared vectors' shapes and of VocalTractLab's vowel sizes. Prints the median time
// per tube of the kernel (complex numbers as pairs of doubles, no allocation) and of a plain
// baseline measured in the same run (complex numbers as objects, a 2 x 2 matrix of them per
// section, the way the model is written down), their ratio, and checks that both find the same
// formants. Goal: kernel median under 2 ms per tube (the area function of a pose, next, is to
// take under 1 ms, for a live display at 20 frames a second).
//
//   node bench/tube_acoustics.bench.mjs
//   GLASSHEAD_BENCH_QUICK=1                      5 runs instead of 101
import { performance } from 'node:perf_hooks';

import { TUBE_AIR, TUBE_FORMANT_BAND_HZ, TUBE_GRID_STEP_HZ, TUBE_WALL } from '../web/src/core/constants.js';
import { tubeFormants } from '../web/src/core/tubeAcoustics.js';
import { check, count } from './support/quick.mjs';
import { median } from './support/stats.mjs';

const RUNS = count( 101, 5 );
const WARMUP = count( 20, 2 );
const GOAL_MS = 2;
const SECTIONS = 40;

/** Seeded tubes of 40 sections, 14 to 19 cm long, areas 0.3 to 8 cm², smooth along the tract. */
function tubes( n, seed = 7 ) {

	let state = seed;
	const random = () => ( ( state = ( state * 1103515245 + 12345 ) % 2147483648 ) / 2147483648 );
	return Array.from( { length: n }, () => {

		const length = 140 + 50 * random();
		const a = [ random(), random(), random() ];
		return {
			lengths: new Array( SECTIONS ).fill( length / SECTIONS ),
			areas: Array.from( { length: SECTIONS }, ( _, k ) => 30 + 770 * ( 0.5 + 0.5 * Math.sin( 2 * Math.PI * ( a[ 0 ] + k / SECTIONS * ( 0.5 + a[ 1 ] ) ) ) ) * ( 0.4 + 0.6 * a[ 2 ] ) ),
		};

	} );

}

// The baseline: the same model, complex numbers as { re, im } objects.
const cx = ( re, im = 0 ) => ( { re, im } );
const add = ( a, b ) => cx( a.re + b.re, a.im + b.im );
const mul = ( a, b ) => cx( a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re );
const div = ( a, b ) => {

	const n = b.re * b.re + b.im * b.im;
	return cx( ( a.re * b.re + a.im * b.im ) / n, ( a.im * b.re - a.re * b.im ) / n );

};
const sqrt = ( a ) => {

	const r = Math.hypot( a.re, a.im );
	return cx( Math.sqrt( ( r + a.re ) / 2 ), Math.sign( a.im || 1 ) * Math.sqrt( Math.max( ( r - a.re ) / 2, 0 ) ) );

};
const cosh = ( a ) => cx( Math.cosh( a.re ) * Math.cos( a.im ), Math.sinh( a.re ) * Math.sin( a.im ) );
const sinh = ( a ) => cx( Math.sinh( a.re ) * Math.cos( a.im ), Math.cosh( a.re ) * Math.sin( a.im ) );
const matmul = ( p, q ) => [ [ add( mul( p[ 0 ][ 0 ], q[ 0 ][ 0 ] ), mul( p[ 0 ][ 1 ], q[ 1 ][ 0 ] ) ), add( mul( p[ 0 ][ 0 ], q[ 0 ][ 1 ] ), mul( p[ 0 ][ 1 ], q[ 1 ][ 1 ] ) ) ],
	[ add( mul( p[ 1 ][ 0 ], q[ 0 ][ 0 ] ), mul( p[ 1 ][ 1 ], q[ 1 ][ 0 ] ) ), add( mul( p[ 1 ][ 0 ], q[ 0 ][ 1 ] ), mul( p[ 1 ][ 1 ], q[ 1 ][ 1 ] ) ) ] ];

function plainTransfer( lengths, areas, f ) {

	const { density: rho, sound_speed: c } = TUBE_AIR;
	const w = 2 * Math.PI * f;
	let k = [ [ cx( 1 ), cx( 0 ) ], [ cx( 0 ), cx( 1 ) ] ];
	lengths.forEach( ( length, i ) => {

		const area = areas[ i ] * 1e-6, l = length * 1e-3, s = 2 * Math.sqrt( Math.PI * area );
		const viscous = s / ( area * area ) * Math.sqrt( w * rho * TUBE_AIR.viscosity / 2 );
		const thermal = s * ( TUBE_AIR.heat_ratio - 1 ) / ( rho * c * c ) * Math.sqrt( TUBE_AIR.heat_conductivity * w / ( 2 * TUBE_AIR.specific_heat * rho ) );
		const z = cx( viscous, w * rho / area + viscous );
		const walls = div( cx( s ), cx( TUBE_WALL.resistance, w * TUBE_WALL.mass - TUBE_WALL.stiffness / w ) );
		const y = add( cx( thermal, w * area / ( rho * c * c ) + thermal ), walls );
		const g = mul( sqrt( mul( z, y ) ), cx( l ) ), z0 = sqrt( div( z, y ) );
		k = matmul( k, [ [ cosh( g ), mul( z0, sinh( g ) ) ], [ div( sinh( g ), z0 ), cosh( g ) ] ] );

	} );
	const area = areas[ areas.length - 1 ] * 1e-6;
	const r = 128 * rho * c / ( 9 * Math.PI * Math.PI * area ), x = w * 8 * rho / ( 3 * Math.PI * Math.sqrt( Math.PI * area ) );
	const load = div( mul( cx( r ), cx( 0, x ) ), cx( r, x ) );
	return div( cx( 1 ), add( mul( k[ 1 ][ 0 ], load ), k[ 1 ][ 1 ] ) );

}

function plainFormants( lengths, areas ) {

	const grid = [];
	for ( let f = TUBE_FORMANT_BAND_HZ[ 0 ]; f <= TUBE_FORMANT_BAND_HZ[ 1 ] + TUBE_GRID_STEP_HZ / 2; f += TUBE_GRID_STEP_HZ ) grid.push( f );
	const db = grid.map( ( f ) => {

		const h = plainTransfer( lengths, areas, f );
		return 20 * Math.log10( Math.hypot( h.re, h.im ) + 1e-300 );

	} );
	const found = [];
	for ( let i = 1; i < grid.length - 1 && found.length < 4; i ++ ) {

		if ( ! ( db[ i ] > db[ i - 1 ] && db[ i ] >= db[ i + 1 ] ) ) continue;
		const curvature = db[ i - 1 ] - 2 * db[ i ] + db[ i + 1 ];
		found.push( grid[ i ] + ( curvature < 0 ? 0.5 * ( db[ i - 1 ] - db[ i + 1 ] ) / curvature : 0 ) * TUBE_GRID_STEP_HZ );

	}

	return found;

}

function perTubeMedian( shapes, run ) {

	for ( let k = 0; k < WARMUP; k ++ ) run( shapes[ k % shapes.length ] );
	const times = [];
	for ( let k = 0; k < RUNS; k ++ ) {

		const t0 = performance.now();
		run( shapes[ k % shapes.length ] );
		times.push( performance.now() - t0 );

	}

	return median( times );

}

const shapes = tubes( 20 );
let sink = 0;
const out = { frequencies: new Float64Array( 4 ), bandwidths: new Float64Array( 4 ) };
const kernelMs = perTubeMedian( shapes, ( t ) => ( sink += tubeFormants( t.lengths, t.areas, {}, out ).frequencies[ 0 ] ) );
const plainMs = perTubeMedian( shapes, ( t ) => ( sink += plainFormants( t.lengths, t.areas )[ 0 ] ) );

let worst = 0;
for ( const t of shapes ) {

	const ours = tubeFormants( t.lengths, t.areas ).frequencies;
	plainFormants( t.lengths, t.areas ).forEach( ( f, k ) => ( worst = Math.max( worst, Math.abs( f - ours[ k ] ) ) ) );

}

const result = {
	benchmark: 'tube_acoustics', sections: SECTIONS, tubes: shapes.length, runs: RUNS,
	kernel_median_ms_per_tube: Number( kernelMs.toPrecision( 3 ) ),
	plain_median_ms_per_tube: Number( plainMs.toPrecision( 3 ) ),
	speedup: Number( ( plainMs / kernelMs ).toFixed( 1 ) ),
	goal_ms: GOAL_MS, goal_met: kernelMs < GOAL_MS, worst_formant_difference_hz: Number( worst.toPrecision( 3 ) ),
};
console.log( `Tube formants, ${SECTIONS} sections, median of ${RUNS} runs (${Number.isFinite( sink ) ? 'checked' : '?'})` );
console.log( `  kernel    ${kernelMs.toFixed( 3 )} ms per tube` );
console.log( `  plain     ${plainMs.toFixed( 3 )} ms per tube` );
console.log( `  speed-up  ${result.speedup}x; goal < ${GOAL_MS} ms per tube: ${result.goal_met ? 'met' : 'NOT met'}` );
console.log( JSON.stringify( result ) );
check( 'the kernel finds the baseline\'s formants on every tube (within 1e-6 Hz)', worst <= 1e-6, `${ worst } Hz` );
