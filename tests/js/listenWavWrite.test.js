// The WAV writer and the recording of an attempt (web/src/core/listen/wavWrite.js, with
// resample.js's resampleSamples): the header field by field, a round trip through the WAV reader,
// clipping at both ends, tones kept (frequency and level) or stopped (what would fold back below
// 8 kHz) on the way to 16 kHz, and a real child's vowel measured the same after it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { analyseSamples } from '../../web/src/core/listen/analyse.js';
import { resampleSamples } from '../../web/src/core/listen/resample.js';
import { parseWav } from '../../web/src/core/listen/wav.js';
import { encodeWav16, pcm16, RECORDING_RATE, recordingWav, WAV_HEADER_BYTES } from '../../web/src/core/listen/wavWrite.js';
import { noise, sine } from './support/listenSignals.js';
import { near, nearArray } from './support/near.js';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( HERE, '..', '..', '..', 'shared', 'data' );
/** Boy 14 of Hillenbrand et al. (1995) saying "heed", 16 kHz. */
const HEED = join( DATA_DIR, 'speech', 'hillenbrand1995-dev', 'audio', 'b14iy.wav' );

const text = ( bytes, at ) => String.fromCharCode( ...bytes.subarray( at, at + 4 ) );

/**
 * The amplitude of the `hz` component of `x` (at `rate`), by correlation over its middle 60 %
 * (away from the silence the resampler assumes past each end): the brute-force reference.
 */
function amplitudeAt( x, hz, rate ) {

	let re = 0, im = 0;
	const from = Math.floor( 0.2 * x.length ), to = Math.floor( 0.8 * x.length );
	for ( let i = from; i < to; i ++ ) {

		re += x[ i ] * Math.cos( 2 * Math.PI * hz * i / rate );
		im += x[ i ] * Math.sin( 2 * Math.PI * hz * i / rate );

	}

	return 2 * Math.hypot( re, im ) / ( to - from );

}

/** The strongest frequency of `x` between `lo` and `hi` Hz, searched in 1 Hz steps. */
function strongestHz( x, rate, lo, hi ) {

	let best = lo, level = - 1;
	for ( let hz = lo; hz <= hi; hz ++ ) {

		const a = amplitudeAt( x, hz, rate );
		if ( a > level ) [ best, level ] = [ hz, a ];

	}

	return best;

}

const db = ( ratio ) => 20 * Math.log10( ratio );

test( 'a 16-bit mono WAV has the 44-byte header of the plain PCM format, field by field', () => {

	const bytes = encodeWav16( new Float32Array( [ 0, 0.5, - 0.5 ] ), 16000 );
	const view = new DataView( bytes.buffer );
	assert.equal( WAV_HEADER_BYTES, 44 );
	assert.equal( bytes.length, 44 + 3 * 2 );
	assert.equal( text( bytes, 0 ), 'RIFF' );
	assert.equal( view.getUint32( 4, true ), bytes.length - 8, 'RIFF size: all that follows it' );
	assert.equal( text( bytes, 8 ), 'WAVE' );
	assert.equal( text( bytes, 12 ), 'fmt ' );
	assert.equal( view.getUint32( 16, true ), 16, 'format chunk size' );
	assert.equal( view.getUint16( 20, true ), 1, 'PCM' );
	assert.equal( view.getUint16( 22, true ), 1, 'one channel' );
	assert.equal( view.getUint32( 24, true ), 16000, 'sample rate' );
	assert.equal( view.getUint32( 28, true ), 32000, 'bytes per second' );
	assert.equal( view.getUint16( 32, true ), 2, 'block align' );
	assert.equal( view.getUint16( 34, true ), 16, 'bits per sample' );
	assert.equal( text( bytes, 36 ), 'data' );
	assert.equal( view.getUint32( 40, true ), 6, 'data size' );
	assert.deepEqual( [ 0, 1, 2 ].map( ( k ) => view.getInt16( 44 + 2 * k, true ) ), [ 0, 16384, - 16384 ] );
	assert.equal( encodeWav16( new Float32Array( 0 ), 8000 ).length, 44, 'no samples: the header alone' );
	assert.throws( () => encodeWav16( new Float32Array( 1 ), 44100.5 ), RangeError );

} );

test( 'samples read back through the WAV reader within half a quantisation step', () => {

	const samples = noise( 4000, 7, 0.15 ); // all within [-1, 1)
	const wav = parseWav( encodeWav16( samples, 22050 ) );
	assert.deepEqual( [ wav.sampleRate, wav.channels, wav.bitsPerSample, wav.format ], [ 22050, 1, 16, 'pcm' ] );
	nearArray( wav.samples, samples, 0.5 / 32768, 'samples, within half a step' );
	const grid = Float32Array.from( [ - 32768, - 1, 0, 1, 12345, 32767 ], ( n ) => n / 32768 );
	assert.deepEqual( parseWav( encodeWav16( grid, 8000 ) ).samples, grid, 'values on the 16-bit grid come back exactly' );

} );

test( 'samples beyond [-1, 1] are clipped to the ends of the range, never wrapped round', () => {

	assert.deepEqual( [ 1, 1.5, 1e9, Infinity, - 1, - 1.0001, - Infinity, NaN, 0.99999, - 0.99999 ].map( pcm16 ),
		[ 32767, 32767, 32767, 32767, - 32768, - 32768, - 32768, 0, 32767, - 32768 ] );
	const loud = sine( 1600, 16000, 440, 2 ); // a tone at twice full scale
	const read = parseWav( encodeWav16( loud, 16000 ) ).samples;
	const clipped = Array.from( loud, ( v ) => Math.max( - 1, Math.min( 32767 / 32768, v ) ) );
	nearArray( read, clipped, 0.5 / 32768, 'the loud tone, flat-topped at full scale' );

} );

test( 'a tone keeps its frequency and level on the way from 48 or 44.1 kHz to 16 kHz', () => {

	for ( const rate of [ 48000, 44100 ] ) for ( const hz of [ 220, 1000, 3100, 6800 ] ) {

		const wav = parseWav( recordingWav( sine( rate, rate, hz, 0.5 ), rate ) );
		assert.equal( wav.sampleRate, RECORDING_RATE );
		assert.equal( wav.samples.length, RECORDING_RATE, `one second from ${ rate } Hz` );
		assert.equal( strongestHz( wav.samples, RECORDING_RATE, hz - 40, hz + 40 ), hz, `${ hz } Hz from ${ rate } Hz` );
		near( db( amplitudeAt( wav.samples, hz, RECORDING_RATE ) / 0.5 ), 0, 0.05, `level of ${ hz } Hz from ${ rate } Hz, dB` );

	}

} );

test( 'what lies above 8 kHz is stopped, not folded back below it', () => {

	// Kept as it came, 8.5 kHz would be heard at 7.5 kHz and 12 kHz at 4 kHz.
	for ( const rate of [ 48000, 44100 ] ) for ( const hz of [ 8100, 8500, 12000, 15000 ] ) {

		const out = resampleSamples( sine( rate, rate, hz, 0.5 ), rate, RECORDING_RATE, { rolloff: 0.94 } );
		const folded = RECORDING_RATE - hz;
		assert.ok( db( amplitudeAt( out, folded, RECORDING_RATE ) / 0.5 ) < - 65, `${ hz } Hz from ${ rate } Hz folded to ${ folded } Hz at ${ db( amplitudeAt( out, folded, RECORDING_RATE ) / 0.5 ).toFixed( 1 ) } dB` );

	}

	// At the formant analysis's cut-off (the new Nyquist frequency) it would not be.
	const unguarded = resampleSamples( sine( 48000, 48000, 8100, 0.5 ), 48000, RECORDING_RATE );
	assert.ok( db( amplitudeAt( unguarded, 7900, RECORDING_RATE ) / 0.5 ) > - 30, 'the guard band is what stops it' );

} );

test( 'resampling keeps every sample that falls within the input, and equal rates copy', () => {

	for ( const [ from, n, expected ] of [ [ 48000, 4800, 1600 ], [ 48000, 4801, 1601 ], [ 44100, 441, 160 ], [ 44100, 442, 161 ], [ 8000, 100, 200 ] ] ) {

		assert.equal( resampleSamples( new Float32Array( n ), from, 16000 ).length, expected, `${ n } samples at ${ from } Hz` );

	}

	const same = new Float32Array( [ 0.1, - 0.2 ] );
	const copy = resampleSamples( same, 16000, 16000 );
	assert.deepEqual( copy, same );
	assert.notEqual( copy, same );
	const first = parseWav( recordingWav( sine( 48000, 48000, 1000 ), 48000, { maxSeconds: 0.25 } ) );
	assert.equal( first.samples.length, 4000, 'a quarter of a second kept' );

} );

test( 'a real child\'s "heed", as a 48 kHz microphone would give it, measures the same after the recording', () => {

	assert.ok( existsSync( HEED ), `recording missing: ${ HEED }; put the shared data at ../shared/data or set GLASSHEAD_DATA_DIR` );
	const original = parseWav( readFileSync( HEED ) );
	const microphone = resampleSamples( original.samples, original.sampleRate, 48000 );
	const kept = parseWav( recordingWav( microphone, 48000 ) );
	assert.equal( kept.samples.length, original.samples.length );
	// The same sound to within 2 % of its RMS (the band from 7.3 to 8 kHz is what is lost).
	let error = 0, power = 0;
	for ( let i = 0; i < kept.samples.length; i ++ ) {

		error += ( kept.samples[ i ] - original.samples[ i ] ) ** 2;
		power += original.samples[ i ] ** 2;

	}

	assert.ok( Math.sqrt( error / power ) < 0.02, `relative RMS difference ${ Math.sqrt( error / power ).toFixed( 4 ) }` );
	// Its steady state (the authors' judges: 257 and 320 ms) measures the same F0, F1 and F2.
	const hop = ( samples ) => analyseSamples( samples, RECORDING_RATE, { group: 'child' } )[ 29 ];
	const before = hop( original.samples ), after = hop( kept.samples );
	near( after.f0, before.f0, 0.01 * before.f0, 'F0' );
	for ( const k of [ 0, 1 ] ) near( after.formants[ k ], before.formants[ k ], 0.01 * before.formants[ k ], `F${ k + 1 }` );

} );
