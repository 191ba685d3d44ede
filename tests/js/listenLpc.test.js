// Formants: Burg's LPC (web/src/core/listen/lpc.js) on autoregressive processes of known
// coefficients, the polynomial root finder (roots.js) on polynomials built from known roots, and
// the whole chain, through the streaming analyser, on vowels synthesised through known resonators.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { analyseSamples, createAnalyser } from '../../web/src/core/listen/analyse.js';
import { burg, formantsFromRoots, lpcSpectrumDb } from '../../web/src/core/listen/lpc.js';
import { fixIntoUnitCircle, polynomialRoots } from '../../web/src/core/listen/roots.js';
import { noise, random, vowel } from './support/listenSignals.js';
import { near } from './support/near.js';

const FORMANTS = [ 700, 1200, 2600, 3500, 4500 ];
const BANDWIDTHS = [ 80, 100, 150, 200, 250 ];

/** Multiply out prod (z - r_k) over complex roots into real coefficients, highest power first. */
function polynomialFrom( rootsRe, rootsIm ) {

	let re = [ 1 ], im = [ 0 ];
	for ( let k = 0; k < rootsRe.length; k ++ ) {

		const nextRe = new Array( re.length + 1 ).fill( 0 ), nextIm = new Array( re.length + 1 ).fill( 0 );
		for ( let i = 0; i < re.length; i ++ ) {

			nextRe[ i ] += re[ i ];
			nextIm[ i ] += im[ i ];
			nextRe[ i + 1 ] -= re[ i ] * rootsRe[ k ] - im[ i ] * rootsIm[ k ];
			nextIm[ i + 1 ] -= re[ i ] * rootsIm[ k ] + im[ i ] * rootsRe[ k ];

		}

		re = nextRe;
		im = nextIm;

	}

	return Float64Array.from( re );

}

/** Each expected root matched to a distinct found one within tol. */
function sameRoots( foundRe, foundIm, wantRe, wantIm, tol, what ) {

	const used = new Set();
	for ( let k = 0; k < wantRe.length; k ++ ) {

		let best = - 1, distance = Infinity;
		for ( let j = 0; j < foundRe.length; j ++ ) {

			const d = Math.hypot( foundRe[ j ] - wantRe[ k ], foundIm[ j ] - wantIm[ k ] );
			if ( ! used.has( j ) && d < distance ) {

				distance = d;
				best = j;

			}

		}

		assert.ok( distance <= tol, `${ what }: root ${ wantRe[ k ] } + ${ wantIm[ k ] }i found only ${ distance } away` );
		used.add( best );

	}

}

test( 'the root finder recovers seeded random conjugate pairs and real roots inside the unit circle (order 10)', () => {

	const seed = 1995;
	const next = random( seed );
	for ( let trial = 0; trial < 200; trial ++ ) {

		const re = [], im = [];
		for ( let pair = 0; pair < 4; pair ++ ) {

			const r = 0.5 + 0.49 * next(), angle = Math.PI * next();
			re.push( r * Math.cos( angle ), r * Math.cos( angle ) );
			im.push( r * Math.sin( angle ), - r * Math.sin( angle ) );

		}

		re.push( 1.8 * next() - 0.9, 1.8 * next() - 0.9 );
		im.push( 0, 0 );
		const c = polynomialFrom( re, im );
		const foundRe = new Float64Array( 10 ), foundIm = new Float64Array( 10 );
		polynomialRoots( c, 10, foundRe, foundIm, new Uint8Array( 10 ) );
		sameRoots( foundRe, foundIm, re, im, 1e-6, `seed ${ seed } trial ${ trial }` );

	}

} );

test( 'the root finder separates two close poles (1e-3 apart), as of two formants that nearly merge', () => {

	const re = [ 0.9, 0.9, 0.9005, 0.9005, - 0.3, - 0.3 ], im = [ 0.3, - 0.3, 0.3009, - 0.3009, 0.8, - 0.8 ];
	const found = { re: new Float64Array( 6 ), im: new Float64Array( 6 ) };
	polynomialRoots( polynomialFrom( re, im ), 6, found.re, found.im, new Uint8Array( 6 ) );
	sameRoots( found.re, found.im, re, im, 1e-7, 'close pair' );

} );

test( 'roots outside the unit circle are reflected inside at the same angle', () => {

	const re = Float64Array.of( 2, 0.5 ), im = Float64Array.of( 0, 0.5 );
	fixIntoUnitCircle( re, im, 2 );
	assert.deepEqual( Array.from( re ), [ 0.5, 0.5 ] );
	assert.deepEqual( Array.from( im ), [ 0, 0.5 ] );

} );

test( 'formants from roots: above the real axis, inside the margins, sorted, bandwidth -ln|z| fs / pi', () => {

	const fs = 10000;
	const pole = ( hz, bw ) => [ Math.exp( - Math.PI * bw / fs ) * Math.cos( 2 * Math.PI * hz / fs ), Math.exp( - Math.PI * bw / fs ) * Math.sin( 2 * Math.PI * hz / fs ) ];
	const roots = [ pole( 2500, 120 ), pole( 500, 60 ), pole( 30, 10 ), pole( 4980, 100 ), pole( 1500, 90 ) ];
	const re = Float64Array.from( [ ...roots.map( ( r ) => r[ 0 ] ), roots[ 1 ][ 0 ] ] );
	const im = Float64Array.from( [ ...roots.map( ( r ) => r[ 1 ] ), - roots[ 1 ][ 1 ] ] );
	const frequencies = new Float64Array( 6 ), bandwidths = new Float64Array( 6 );
	const count = formantsFromRoots( re, im, 6, fs, 50, frequencies, bandwidths );
	assert.equal( count, 3, '30 Hz and 4980 Hz are outside the 50 Hz margins; the conjugate is not counted' );
	[ 500, 1500, 2500 ].forEach( ( hz, k ) => near( frequencies[ k ], hz, 1e-9, `F${ k + 1 }` ) );
	[ 60, 90, 120 ].forEach( ( bw, k ) => near( bandwidths[ k ], bw, 1e-9, `B${ k + 1 }` ) );

} );

test( 'Burg\'s method recovers the coefficients of a seeded AR(4) process within 0.02', () => {

	// x[n] = -a1 x[n-1] - ... - a4 x[n-4] + e[n], poles at 500 Hz and 1500 Hz (fs 8000).
	const fs = 8000;
	const poles = [ [ 500, 100 ], [ 1500, 200 ] ];
	const re = [], im = [];
	for ( const [ hz, bw ] of poles ) {

		const r = Math.exp( - Math.PI * bw / fs ), w = 2 * Math.PI * hz / fs;
		re.push( r * Math.cos( w ), r * Math.cos( w ) );
		im.push( r * Math.sin( w ), - r * Math.sin( w ) );

	}

	const a = polynomialFrom( re, im ); // [1, a1, a2, a3, a4]
	const e = noise( 20000, 4 );
	const x = new Float64Array( e.length );
	for ( let n = 0; n < x.length; n ++ ) {

		let v = e[ n ];
		for ( let k = 1; k <= 4; k ++ ) if ( n - k >= 0 ) v -= a[ k ] * x[ n - k ];
		x[ n ] = v;

	}

	const estimate = new Float64Array( 5 );
	const error = burg( x, 0, x.length, 4, estimate, new Float64Array( x.length ), new Float64Array( x.length ) );
	for ( let k = 0; k <= 4; k ++ ) near( estimate[ k ], a[ k ], 0.02, `a${ k }` );
	near( error, 0.01, 0.001, 'the prediction error power is the driving noise\'s (sd 0.1)' );

} );

test( 'Burg on a silent frame returns no error and the identity filter', () => {

	const a = new Float64Array( 11 ).fill( 7 );
	assert.equal( burg( new Float64Array( 100 ), 0, 100, 10, a, new Float64Array( 100 ), new Float64Array( 100 ) ), 0 );
	assert.deepEqual( Array.from( a ), [ 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 ] );

} );

/** The median of each formant (and bandwidth) over the hops well inside the signal. */
function medianFormants( hops, seconds ) {

	const inner = hops.filter( ( h ) => h.t >= 0.1 && h.t <= seconds - 0.1 );
	const median = ( values ) => values.slice().sort( ( x, y ) => x - y )[ values.length >> 1 ];
	return {
		formants: [ 0, 1, 2, 3 ].map( ( i ) => median( inner.map( ( h ) => h.formants[ i ] ) ) ),
		bandwidths: [ 0, 1, 2, 3 ].map( ( i ) => median( inner.map( ( h ) => h.bandwidths[ i ] ) ) ),
	};

}

test( 'a synthetic vowel (F1 700, F2 1200, F3 2600 Hz) gives F1-F3 within 5 % and bandwidths within a factor 2, F0 120 and 250 Hz', () => {

	const seconds = 0.5;
	// (rate, F0, group): 16 kHz as the recordings; 44.1 and 48 kHz as browsers' microphones.
	for ( const [ sampleRate, f0, group ] of [ [ 16000, 120, 'man' ], [ 16000, 250, 'woman' ], [ 44100, 120, 'woman' ], [ 48000, 120, 'woman' ] ] ) {

		const signal = vowel( { sampleRate, seconds, f0, formants: FORMANTS, bandwidths: BANDWIDTHS } );
		const { formants, bandwidths } = medianFormants( analyseSamples( signal, sampleRate, { group } ), seconds );
		const what = `${ f0 } Hz vowel at ${ sampleRate } Hz, ${ group }`;
		for ( let i = 0; i < 3; i ++ ) {

			near( formants[ i ], FORMANTS[ i ], 0.05 * FORMANTS[ i ], `${ what }: F${ i + 1 }` );
			assert.ok( bandwidths[ i ] > BANDWIDTHS[ i ] / 2 && bandwidths[ i ] < BANDWIDTHS[ i ] * 2, `${ what }: B${ i + 1 } ${ bandwidths[ i ] } against ${ BANDWIDTHS[ i ] }` );

		}

	}

} );

test( 'a vowel with a low F3 (as /r/) shows it in f3_minus_f2', () => {

	const sampleRate = 16000, seconds = 0.4;
	const signal = vowel( { sampleRate, seconds, f0: 200, formants: [ 500, 1300, 1700, 3300, 4300 ], bandwidths: [ 80, 100, 120, 200, 250 ] } );
	const hops = analyseSamples( signal, sampleRate, { group: 'woman' } ).filter( ( h ) => h.t >= 0.1 && h.t <= 0.3 );
	for ( const hop of hops ) near( hop.f3_minus_f2, 400, 60, `F3 - F2 at ${ hop.t } s` );

} );

test( 'the LPC spectrum peaks at the formants', () => {

	const sampleRate = 16000;
	const analyser = createAnalyser( { sampleRate, group: 'man' } );
	analyser.push( vowel( { sampleRate, seconds: 0.3, f0: 120, formants: FORMANTS, bandwidths: BANDWIDTHS } ) );
	const bins = 501; // 10 Hz apart, 0 to the ceiling (5000 Hz)
	const db = analyser.lpcSpectrum( new Float64Array( bins ) );
	const peaks = [];
	for ( let k = 1; k < bins - 1; k ++ ) if ( db[ k ] > db[ k - 1 ] && db[ k ] >= db[ k + 1 ] ) peaks.push( k * 10 );
	for ( const hz of FORMANTS.slice( 0, 4 ) ) assert.ok( peaks.some( ( p ) => Math.abs( p / hz - 1 ) < 0.05 ), `a peak near ${ hz } Hz among ${ peaks }` );
	assert.ok( db.every( Number.isFinite ) );
	// The same, from the kernel on a known filter: one pole pair at 1000 Hz peaks there.
	const r = 0.98, w = 2 * Math.PI * 1000 / 10000;
	const one = lpcSpectrumDb( Float64Array.of( 1, - 2 * r * Math.cos( w ), r * r ), 2, 1, 10000, new Float64Array( 501 ) );
	assert.equal( one.indexOf( Math.max( ...one ) ), 100 );

} );
