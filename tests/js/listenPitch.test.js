// Pitch: YIN (web/src/core/listen/pitch.js) and the tracker over its candidates (pitchTrack.js),
// alone and through the streaming analyser, on signals whose pitch is known by construction:
// sines, glottal pulse trains through formant resonators, silence and noise.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { analyseSamples } from '../../web/src/core/listen/analyse.js';
import { GROUPS } from '../../web/src/core/listen/params.js';
import { createYin, yinCandidates, yinPitch } from '../../web/src/core/listen/pitch.js';
import { addPitchFrame, createPitchTracker, decidePitch } from '../../web/src/core/listen/pitchTrack.js';
import { noise, onePole, sine, vowel } from './support/listenSignals.js';
import { near } from './support/near.js';

/** The formants of the test vowel (an /a/-like vowel), with formants up to the ceilings of men and women. */
const FORMANTS = [ 700, 1200, 2600, 3500, 4500 ];
const BANDWIDTHS = [ 80, 100, 150, 200, 250 ];

/** The hops well inside a signal (away from the zeros at its edges). */
const inner = ( hops, seconds ) => hops.filter( ( h ) => h.t >= 0.1 && h.t <= seconds - 0.1 );

test( 'YIN on one frame of a sine gives its frequency within 0.1 %', () => {

	for ( const [ sampleRate, hz, group ] of [ [ 11000, 200, 'woman' ], [ 10000, 97.3, 'man' ], [ 13000, 440, 'child' ] ] ) {

		const { pitchFloor, pitchCeiling } = GROUPS[ group ];
		const yin = createYin( { sampleRate, floor: pitchFloor, ceiling: pitchCeiling } );
		const result = yinPitch( yin, sine( yin.frameLength, sampleRate, hz ), 0, { f0: 0, aperiodicity: 1 } );
		near( result.f0, hz, 0.001 * hz, `${ hz } Hz sine at ${ sampleRate } Hz` );
		assert.ok( result.aperiodicity < 0.01, `a sine is periodic (aperiodicity ${ result.aperiodicity })` );

	}

} );

test( 'YIN\'s candidates are the period and its multiples within the range', () => {

	const sampleRate = 10000;
	const yin = createYin( { sampleRate, floor: 60, ceiling: 250 } );
	const frame = vowel( { sampleRate, seconds: 0.1, f0: 200, formants: FORMANTS.slice( 0, 4 ), bandwidths: BANDWIDTHS } );
	const count = yinCandidates( yin, frame, 300 );
	const found = Array.from( yin.candidateF0.subarray( 0, count ) );
	for ( const hz of [ 200, 100, 200 / 3 ] ) assert.ok( found.some( ( f ) => Math.abs( f / hz - 1 ) < 0.005 ), `a candidate near ${ hz.toFixed( 1 ) } Hz in ${ found }` );
	const aperiodicities = Array.from( yin.candidateAperiodicity.subarray( 0, count ) );
	assert.deepEqual( aperiodicities, aperiodicities.slice().sort( ( a, b ) => a - b ), 'deepest first' );

} );

test( 'silent frames have no candidates', () => {

	const yin = createYin( { sampleRate: 11000, floor: 120, ceiling: 400 } );
	assert.equal( yinCandidates( yin, new Float32Array( yin.frameLength ), 0 ), 0 );
	assert.equal( yinPitch( yin, new Float32Array( yin.frameLength ), 0, {} ).f0, 0 );

} );

test( 'a glottal pulse train through formant resonators gives its F0 within 1 % in every voiced hop (120 and 250 Hz)', () => {

	for ( const sampleRate of [ 16000, 48000 ] ) for ( const [ f0, group ] of [ [ 120, 'man' ], [ 250, 'woman' ], [ 120, 'woman' ], [ 250, 'child' ] ] ) {

		const seconds = 0.5;
		const hops = inner( analyseSamples( vowel( { sampleRate, seconds, f0, formants: FORMANTS, bandwidths: BANDWIDTHS } ), sampleRate, { group } ), seconds );
		assert.ok( hops.length >= 30 );
		for ( const hop of hops ) {

			assert.ok( hop.voiced, `${ f0 } Hz vowel, ${ group }, ${ sampleRate } Hz: hop at ${ hop.t } s unvoiced` );
			near( hop.f0, f0, 0.01 * f0, `${ f0 } Hz vowel, ${ group }, ${ sampleRate } Hz, hop at ${ hop.t } s` );

		}

	}

} );

test( 'a sine gives its pitch through the analyser', () => {

	const sampleRate = 44100;
	for ( const [ hz, group ] of [ [ 180, 'woman' ], [ 90, 'man' ], [ 330, 'child' ] ] ) {

		const hops = inner( analyseSamples( sine( sampleRate, sampleRate, hz, 0.3 ), sampleRate, { group } ), 1 );
		for ( const hop of hops ) near( hop.f0, hz, 0.005 * hz, `${ hz } Hz sine, hop at ${ hop.t } s` );

	}

} );

test( 'silence is unvoiced, with no intensity, formants or moments', () => {

	const hops = analyseSamples( new Float32Array( 8000 ), 16000, { group: 'woman' } );
	assert.equal( hops.length, 51 );
	for ( const hop of hops ) {

		assert.equal( hop.voiced, false );
		assert.equal( hop.f0, null );
		assert.equal( hop.intensity_db, null );
		assert.deepEqual( hop.formants, [ null, null, null, null ] );
		assert.equal( hop.centroid, null );
		assert.equal( hop.f3_minus_f2, null );

	}

} );

test( 'white noise is unvoiced at every rate and in every group (seeded)', () => {

	for ( const sampleRate of [ 16000, 44100, 48000 ] ) for ( const group of Object.keys( GROUPS ) ) {

		const seed = sampleRate + group.length;
		const hops = analyseSamples( noise( sampleRate, seed, 0.2 ), sampleRate, { group } );
		const voiced = hops.filter( ( h ) => h.voiced ).map( ( h ) => `${ h.t } s at ${ h.f0.toFixed( 1 ) } Hz` );
		assert.deepEqual( voiced, [], `white noise at ${ sampleRate } Hz, ${ group }, seed ${ seed }` );
		assert.ok( hops.every( ( h ) => h.intensity_db > 70 ), 'noise is loud: unvoiced for its aperiodicity, not its level' );

	}

} );

test( 'a voice below the voicing floor (about -64 dBFS) is unvoiced', () => {

	const sampleRate = 16000;
	const quiet = vowel( { sampleRate, seconds: 0.4, f0: 200, formants: FORMANTS, bandwidths: BANDWIDTHS, peak: 1e-4 } );
	assert.ok( analyseSamples( quiet, sampleRate, { group: 'woman' } ).every( ( h ) => ! h.voiced ) );
	const loud = vowel( { sampleRate, seconds: 0.4, f0: 200, formants: FORMANTS, bandwidths: BANDWIDTHS, peak: 0.1 } );
	assert.ok( inner( analyseSamples( loud, sampleRate, { group: 'woman' } ), 0.4 ).every( ( h ) => h.voiced ) );

} );

test( 'the tracker keeps the fundamental through frames where its undertone looks as periodic', () => {

	// Frames 0-9 see 200 Hz clearly (and its undertone 100 Hz a little less); in frames 4-6 the
	// undertone is slightly deeper, as in diplophonic or creaky stretches. Frame by frame the
	// deepest dip would jump an octave down and back; the path does not.
	const tracker = createPitchTracker( { candidates: 2, lookahead: 5, floor: 60 } );
	const decided = [];
	for ( let k = 0; k < 10; k ++ ) {

		const undertoneDeeper = k >= 4 && k <= 6;
		addPitchFrame( tracker, [ 200, 100 ], [ 0.05, undertoneDeeper ? 0.02 : 0.1 ], 2, true );
		if ( k >= 5 ) decided.push( decidePitch( tracker, k - 5 ) );

	}

	for ( let k = 5; k < 10; k ++ ) decided.push( decidePitch( tracker, k ) );
	assert.deepEqual( decided, new Array( 10 ).fill( 200 ) );

} );

test( 'the tracker follows a real octave change that lasts, and leaves unvoiced frames unvoiced', () => {

	const tracker = createPitchTracker( { candidates: 2, lookahead: 3, floor: 60 } );
	const frames = [
		...new Array( 6 ).fill( [ [ 220, 110 ], [ 0.03, 0.05 ] ] ),
		...new Array( 3 ).fill( [ [], [] ] ), // noise: no dip deep enough
		...new Array( 6 ).fill( [ [ 110, 220 ], [ 0.03, 0.5 ] ] ),
	];
	frames.forEach( ( [ f0s, aps ] ) => addPitchFrame( tracker, f0s, aps, f0s.length, true ) );
	const path = [];
	for ( let k = 12; k < 15; k ++ ) path.push( decidePitch( tracker, k ) );
	assert.deepEqual( path, [ 110, 110, 110 ] );
	assert.throws( () => decidePitch( tracker, 0 ), /not held/ );

} );

test( 'low-passed noise (rumble) is rarely voiced: in under 3 % of hops', () => {

	const sampleRate = 16000;
	const rumble = onePole( noise( 3 * sampleRate, 11, 0.5 ), sampleRate, 150 );
	const hops = analyseSamples( rumble, sampleRate, { group: 'man' } );
	assert.ok( hops.filter( ( h ) => h.voiced ).length <= 0.03 * hops.length );

} );
