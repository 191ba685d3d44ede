// The spectral kernels of web/src/core/listen/: the real FFT against a naive DFT over seeded
// random frames, the spectral moments on distributions whose moments are known in closed form
// and on filtered noise, and the resampler's pass band, stop band and chunking.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createRealFft } from '../../web/src/core/listen/fft.js';
import { SampleStream } from '../../web/src/core/listen/frames.js';
import {
	MOMENT_CENTROID, MOMENT_KURTOSIS, MOMENT_PEAK, MOMENT_POWER, MOMENT_SKEW, MOMENT_SLOTS, MOMENT_SPREAD,
	analyseMoments, createMomentsAnalysis, spectralMoments,
} from '../../web/src/core/listen/moments.js';
import { createResampler, resampleStream } from '../../web/src/core/listen/resample.js';
import { noise, onePole, random, sine } from './support/listenSignals.js';
import { near } from './support/near.js';

/** The DFT by its definition, O(n^2), in float64. */
function naiveDft( x ) {

	const n = x.length, re = new Float64Array( n / 2 + 1 ), im = new Float64Array( n / 2 + 1 );
	for ( let k = 0; k <= n / 2; k ++ ) for ( let j = 0; j < n; j ++ ) {

		re[ k ] += x[ j ] * Math.cos( 2 * Math.PI * k * j / n );
		im[ k ] -= x[ j ] * Math.sin( 2 * Math.PI * k * j / n );

	}

	return { re, im };

}

test( 'the real FFT equals the naive DFT on seeded random frames of 4 to 1024 points, and inverts', () => {

	const seed = 20240611;
	const next = random( seed );
	for ( let size = 4; size <= 1024; size *= 2 ) {

		const fft = createRealFft( size );
		const x = Float64Array.from( { length: size }, () => next() - 0.5 );
		const re = new Float64Array( fft.bins ), im = new Float64Array( fft.bins );
		fft.forward( x, re, im );
		const ref = naiveDft( x );
		const tol = 1e-12 * size;
		for ( let k = 0; k < fft.bins; k ++ ) {

			near( re[ k ], ref.re[ k ], tol, `size ${ size } seed ${ seed } bin ${ k } (re)` );
			near( im[ k ], ref.im[ k ], tol, `size ${ size } seed ${ seed } bin ${ k } (im)` );

		}

		const back = new Float64Array( size );
		fft.inverse( re, im, back );
		for ( let j = 0; j < size; j ++ ) near( back[ j ], x[ j ], 1e-14 * size, `size ${ size } sample ${ j } after the round trip` );

	}

} );

test( 'FFT sizes that are not powers of two are refused', () => {

	for ( const size of [ 0, 2, 6, 100, 1.5 ] ) assert.throws( () => createRealFft( size ), RangeError );

} );

test( 'moments of a flat spectrum: the band centre, its uniform spread, no skew, kurtosis -1.2 (n -> inf)', () => {

	const n = 101, binHz = 10;
	const power = new Float64Array( n ).fill( 2 );
	const m = spectralMoments( power, binHz, 0, n - 1, new Float64Array( MOMENT_SLOTS ) );
	near( m[ MOMENT_CENTROID ], 500, 1e-9, 'centroid' );
	near( m[ MOMENT_SPREAD ], binHz * Math.sqrt( ( n * n - 1 ) / 12 ), 1e-9, 'spread' );
	near( m[ MOMENT_SKEW ], 0, 1e-12, 'skew' );
	// Discrete uniform: excess kurtosis -6 (n^2 + 1) / (5 (n^2 - 1)).
	near( m[ MOMENT_KURTOSIS ], - 6 * ( n * n + 1 ) / ( 5 * ( n * n - 1 ) ), 1e-9, 'kurtosis' );
	near( m[ MOMENT_POWER ], 2 * n, 1e-9, 'power' );

} );

test( 'moments of two spikes: the weighted mean, the spread between them, the skew toward the weaker', () => {

	const power = new Float64Array( 64 );
	power[ 10 ] = 3;
	power[ 30 ] = 1;
	const m = spectralMoments( power, 100, 0, 63, new Float64Array( MOMENT_SLOTS ) );
	// Bernoulli p = 1/4 on {1000, 3000}: mean 1500, sd 2000 sqrt(p q), skew (1 - 2p) / sqrt(p q).
	near( m[ MOMENT_CENTROID ], 1500, 1e-9, 'centroid' );
	near( m[ MOMENT_SPREAD ], 2000 * Math.sqrt( 3 / 16 ), 1e-9, 'spread' );
	near( m[ MOMENT_SKEW ], 0.5 / Math.sqrt( 3 / 16 ), 1e-9, 'skew' );
	near( m[ MOMENT_PEAK ], 1000, 1e-9, 'peak' );
	const band = spectralMoments( power, 100, 20, 63, new Float64Array( MOMENT_SLOTS ) );
	near( band[ MOMENT_CENTROID ], 3000, 1e-9, 'centroid within a band that leaves the stronger spike out' );

} );

test( 'no power in the band gives no moments (NaN), not zeros', () => {

	const m = spectralMoments( new Float64Array( 16 ), 100, 0, 15, new Float64Array( MOMENT_SLOTS ) );
	assert.equal( m[ MOMENT_POWER ], 0 );
	assert.ok( Number.isNaN( m[ MOMENT_CENTROID ] ) && Number.isNaN( m[ MOMENT_PEAK ] ) );

} );

test( 'a sine\'s spectral peak is its frequency, to a tenth of a bin', () => {

	const sampleRate = 16000;
	const analysis = createMomentsAnalysis( { sampleRate, windowS: 0.02 } );
	for ( const hz of [ 440, 1234.5, 5000 ] ) {

		const m = analyseMoments( analysis, sine( analysis.frameLength, sampleRate, hz ), 0 );
		near( m[ MOMENT_PEAK ], hz, 0.1 * analysis.binHz, `peak of a ${ hz } Hz sine` );

	}

} );

test( 'high-passed noise has a higher centroid, less skew and its peak higher than low-passed noise (/s/ against /ʃ/)', () => {

	for ( const sampleRate of [ 16000, 44100 ] ) {

		const analysis = createMomentsAnalysis( { sampleRate, windowS: 0.02 } );
		const white = noise( analysis.frameLength, 7 );
		const high = analyseMoments( analysis, onePole( white, sampleRate, 4000, true ), 0 ).slice();
		const low = analyseMoments( analysis, onePole( white, sampleRate, 1000 ), 0 ).slice();
		assert.ok( high[ MOMENT_CENTROID ] > low[ MOMENT_CENTROID ] + 1000, `${ sampleRate } Hz: centroid high ${ high[ MOMENT_CENTROID ] } low ${ low[ MOMENT_CENTROID ] }` );
		assert.ok( high[ MOMENT_SKEW ] < low[ MOMENT_SKEW ], `${ sampleRate } Hz: skew high ${ high[ MOMENT_SKEW ] } low ${ low[ MOMENT_SKEW ] }` );
		// The white noise's own centroid: the middle of 0 .. Nyquist, within a tenth.
		const flat = analyseMoments( analysis, white, 0 );
		near( flat[ MOMENT_CENTROID ], sampleRate / 4, sampleRate / 40, `${ sampleRate } Hz: white noise centroid` );

	}

} );

test( 'the moments\' band must lie within 0 to Nyquist', () => {

	assert.throws( () => createMomentsAnalysis( { sampleRate: 16000, windowS: 0.02, band: [ 1000, 9000 ] } ), /must lie within 0-8000 Hz/ );
	assert.throws( () => createMomentsAnalysis( { sampleRate: 16000, windowS: 0.02, band: [ 3000, 2000 ] } ), RangeError );

} );

/** Resample a whole signal in one go, with zeros after it so that every output sample is made. */
function resampleAll( signal, from, to, chunk = signal.length ) {

	const resampler = createResampler( from, to );
	const input = new SampleStream( resampler.halfTaps + 1 );
	const output = new SampleStream( 0 );
	for ( let i = 0; i < signal.length; i += chunk ) {

		input.append( signal, i, Math.min( signal.length, i + chunk ) );
		resampleStream( resampler, input, output );

	}

	input.appendZeros( 2 * resampler.halfTaps );
	resampleStream( resampler, input, output );
	return output.data.slice( 0, Math.floor( signal.length * to / from ) );

}

test( 'resampling keeps a sine below the new Nyquist frequency (gain 1 within 0.1 %) at its frequency', () => {

	for ( const [ from, to, hz ] of [ [ 16000, 11000, 1000 ], [ 48000, 13000, 4000 ], [ 44100, 10000, 300 ], [ 8000, 11000, 2500 ] ] ) {

		const out = resampleAll( sine( from, from, hz ), from, to );
		for ( let m = to >> 2; m < ( 3 * to ) >> 2; m += 7 ) {

			near( out[ m ], 0.5 * Math.sin( 2 * Math.PI * hz * m / to ), 0.0005, `${ from } -> ${ to } Hz, ${ hz } Hz sine, sample ${ m }` );

		}

	}

} );

test( 'resampling removes what lies above the new Nyquist frequency (at least 50 dB down)', () => {

	const from = 16000, to = 11000;
	const out = resampleAll( sine( from, from, 6500 ), from, to );
	let power = 0;
	for ( let m = to >> 2; m < ( 3 * to ) >> 2; m ++ ) power += out[ m ] * out[ m ];
	const rms = Math.sqrt( power / ( to >> 1 ) );
	assert.ok( 20 * Math.log10( rms / ( 0.5 / Math.SQRT2 ) ) < - 50, `a 6500 Hz sine comes out at ${ ( 20 * Math.log10( rms / ( 0.5 / Math.SQRT2 ) ) ).toFixed( 1 ) } dB` );

} );

test( 'resampling in chunks of 128 samples gives the same samples as in one go', () => {

	const signal = noise( 20000, 3 );
	assert.deepEqual( resampleAll( signal, 44100, 11000, 128 ), resampleAll( signal, 44100, 11000 ) );

} );
