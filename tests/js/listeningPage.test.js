// The listening page's pure parts: the chart's scales and norm ellipses, the verdict on a
// measurement, the /ʃ/–/s/ meter, the input's level checks, the summary of an attempt and the
// messages for every kind of bad input.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import {
	chartPoint, ellipse, IN_TARGET, inputProblem, nearestVowel, normDistance, sibilantPosition,
	SIBILANT_ENDS_HZ, sibilantBand, summariseAttempt, zoneOf, measurableTarget, attemptZone, attemptMeasures, attemptWords, itemTarget, F3_TARGET_HZ, roomProblem, NOISY_CONTRAST_DB, NOISY_FLOOR_BELOW_FULL_SCALE_DB,
} from '../../web/src/ui/listen/listenScales.js';
import { listenMessage, MESSAGES, pictureShapes } from '../../web/src/ui/listen/listenMessages.js';
import { microphoneErrorKind } from '../../web/src/ui/listen/audioInput.js';
import { spectrogram } from '../../web/src/ui/listen/spectrogram.js';
import { AttemptRecorder, KEPT_SECONDS } from '../../web/src/ui/listen/AttemptRecorder.js';
import { vowel } from './support/listenSignals.js';
import { attemptDone, MAX_ATTEMPT_S, QUIET_END_S } from '../../web/src/ui/practice/PracticeListener.js';

const norm = ( f1, f2, sd1 = 0.1, sd2 = 0.08, rho = 0.3 ) => ( {
	mean: [ Math.log( f1 ), Math.log( f2 ) ],
	cov: [ [ sd1 * sd1, rho * sd1 * sd2 ], [ rho * sd1 * sd2, sd2 * sd2 ] ],
} );
const VOWELS = {
	iy: { ipa: 'i', arpabet: 'IY', log_f1_f2: norm( 300, 2800 ) },
	aa: { ipa: 'ɑ', arpabet: 'AA', log_f1_f2: norm( 850, 1250 ) },
	uw: { ipa: 'u', arpabet: 'UW', log_f1_f2: norm( 350, 1000 ) },
};

test( 'the chart puts front vowels left, open vowels low, inside its box', () => {

	const box = { width: 400, height: 300, pad: 20 };
	const i = chartPoint( 300, 2800, box );
	const a = chartPoint( 850, 1250, box );
	const u = chartPoint( 350, 1000, box );
	assert.ok( i.x < a.x && a.x < u.x, 'F2 falls from left to right' );
	assert.ok( i.y < a.y && u.y < a.y, 'F1 grows downwards' );
	for ( const p of [ i, a, u ] ) assert.ok( p.x >= 20 && p.x <= 380 && p.y >= 20 && p.y <= 280 );

} );

test( 'every point of a norm ellipse lies at its scale in Mahalanobis distance', () => {

	for ( const [ sd1, sd2, rho ] of [ [ 0.1, 0.08, 0.3 ], [ 0.05, 0.2, - 0.7 ], [ 0.1, 0.1, 0 ] ] ) {

		const n = norm( 500, 1500, sd1, sd2, rho );
		for ( const [ f1, f2 ] of ellipse( n, 2, 32 ) ) assert.ok( Math.abs( normDistance( f1, f2, n ) - 2 ) < 1e-9, `${ sd1 } ${ sd2 } ${ rho }` );

	}

} );

test( 'a measurement is given its nearest vowel and a zone: in, near or off', () => {

	assert.deepEqual( { ...nearestVowel( 310, 2750, VOWELS ), distance: undefined }, { vowel: 'iy', zone: 'in', distance: undefined } );
	assert.equal( nearestVowel( 820, 1300, VOWELS ).vowel, 'aa' );
	assert.equal( zoneOf( IN_TARGET ), 'in' );
	assert.equal( zoneOf( 3 ), 'near' );
	assert.equal( zoneOf( 3.6 ), 'off' );
	assert.equal( nearestVowel( 600, 2000, { iy: VOWELS.iy } ).zone, 'off' );
	assert.equal( nearestVowel( null, 2000, VOWELS ), null );

} );

test( 'the meter puts /ʃ/ left and /s/ right for every group, clamped to its ends', () => {

	for ( const [ group, ends ] of Object.entries( SIBILANT_ENDS_HZ ) ) {

		assert.equal( sibilantPosition( ends.sh, group ), 0 );
		assert.equal( sibilantPosition( ends.s, group ), 1 );
		assert.equal( sibilantPosition( 20000, group ), 1 );
		assert.equal( sibilantPosition( 100, group ), 0 );
		assert.ok( sibilantPosition( ( ends.sh + ends.s ) / 2, group ) > 0.4 );

	}

	assert.deepEqual( sibilantBand( 48000 ), [ 1000, 8000 ] );
	assert.deepEqual( sibilantBand( 8000 ), [ 1000, 4000 ] );

} );

test( 'the input is silent, clipping or fine by its samples', () => {

	assert.equal( inputProblem( new Float32Array( 1024 ) ), 'silent' );
	assert.equal( inputProblem( new Float32Array( 0 ) ), 'silent' );
	const tone = Float32Array.from( { length: 1024 }, ( _, i ) => 0.3 * Math.sin( i / 5 ) );
	assert.equal( inputProblem( tone ), null );
	const clipped = Float32Array.from( tone, ( x ) => Math.max( - 1, Math.min( 1, x * 10 ) ) );
	assert.equal( inputProblem( clipped ), 'clipping' );

} );

test( 'an attempt is summarised from the middle of its longest voiced run and its loud hiss', () => {

	const hops = [];
	let t = 0;
	const add = ( n, hop ) => {

		for ( let k = 0; k < n; k ++ ) hops.push( { t: ( t ++ ) / 100, ...hop( k ) } );

	};

	add( 10, () => ( { voiced: false, intensity_db: 30, centroid: 1000, formants: [ null, null, null, null ] } ) ); // room
	add( 20, () => ( { voiced: false, intensity_db: 70, centroid: 6000, formants: [ null, null, null, null ] } ) ); // /s/
	add( 5, () => ( { voiced: true, intensity_db: 75, f0: 200, formants: [ 500, 1500, 2500, 3500 ], f3_minus_f2: 1000 } ) ); // a short voiced bit
	add( 3, () => ( { voiced: false, intensity_db: 40, centroid: 2000, formants: [ null, null, null, null ] } ) );
	add( 40, ( k ) => ( { voiced: true, intensity_db: 80, f0: 250, formants: [ k < 8 || k > 32 ? 700 : 300, 2800, 3300, 4000 ], f3_minus_f2: 500 } ) ); // the vowel, with transitions
	const { vowel, fricative } = summariseAttempt( hops );
	assert.deepEqual( [ vowel.f0, vowel.f1, vowel.f2, vowel.f3, vowel.f3_minus_f2 ], [ 250, 300, 2800, 3300, 500 ] );
	assert.ok( Math.abs( vowel.duration_s - 0.39 ) < 1e-9 );
	assert.equal( fricative.centroid, 6000 );
	assert.deepEqual( summariseAttempt( [] ), { vowel: null, fricative: null } );

} );

test( 'every kind of bad input has words and a picture; an unknown kind reads as unusable', () => {

	for ( const kind of [ 'unsupported', 'refused', 'no-microphone', 'busy', 'not-audio', 'silent', 'clipping', 'whisper', 'noisy', 'asking' ] ) {

		const message = listenMessage( kind );
		assert.equal( message.kind, kind );
		assert.ok( message.text.length > 20 && /[.!]$/.test( message.text ), kind );
		assert.ok( pictureShapes( message.picture ).length > 0, kind );

	}

	assert.equal( listenMessage( 'what' ).kind, 'unsupported' );
	assert.equal( new Set( Object.values( MESSAGES ).map( ( m ) => m.text ) ).size, Object.keys( MESSAGES ).length );
	assert.equal( microphoneErrorKind( 'NotAllowedError' ), 'refused' );
	assert.equal( microphoneErrorKind( 'NotFoundError' ), 'no-microphone' );
	assert.equal( microphoneErrorKind( 'NotReadableError' ), 'busy' );

} );

test( 'a lesson item is measured against a vowel of the norms or /s/ and /ʃ/, else not judged', () => {

	assert.deepEqual( measurableTarget( { kind: 'phoneme', text: 'i' }, VOWELS ), { kind: 'vowel', code: 'iy' } );
	assert.deepEqual( measurableTarget( { kind: 'phoneme', text: 'AA' }, VOWELS ), { kind: 'vowel', code: 'aa' } );
	assert.deepEqual( measurableTarget( { kind: 'phoneme', text: 'ʃ' }, VOWELS ), { kind: 'sibilant', sound: 'sh' } );
	assert.deepEqual( measurableTarget( { kind: 'phoneme', text: 's' }, VOWELS ), { kind: 'sibilant', sound: 's' } );
	assert.equal( measurableTarget( { kind: 'phoneme', text: 't' }, VOWELS ), null );
	assert.equal( measurableTarget( { kind: 'word', text: 'sea' }, VOWELS ), null );

} );

test( 'a try is judged against its target: the vowel by its norm, the hiss by the meter', () => {

	const vowel = ( f1, f2 ) => ( { vowel: { f0: 250, f1, f2, f3: 3300, duration_s: 0.25 }, fricative: null } );
	assert.equal( attemptZone( vowel( 300, 2800 ), { kind: 'vowel', code: 'iy' }, VOWELS ), 'in' );
	assert.equal( attemptZone( vowel( 850, 1250 ), { kind: 'vowel', code: 'iy' }, VOWELS ), 'off' );
	assert.equal( attemptZone( { vowel: null, fricative: null }, { kind: 'vowel', code: 'iy' }, VOWELS ), null );
	const hiss = ( centroid ) => ( { vowel: null, fricative: { centroid, duration_s: 0.2 } } );
	const { sh, s } = SIBILANT_ENDS_HZ.child;
	assert.equal( attemptZone( hiss( s ), { kind: 'sibilant', sound: 's' } ), 'in' );
	assert.equal( attemptZone( hiss( s ), { kind: 'sibilant', sound: 'sh' } ), 'off' );
	assert.equal( attemptZone( hiss( sh ), { kind: 'sibilant', sound: 'sh' } ), 'in' );
	assert.equal( attemptZone( hiss( ( sh + s ) / 2 ), { kind: 'sibilant', sound: 's' } ), 'near' );
	assert.equal( attemptZone( vowel( 300, 2800 ), null ), null );

} );

test( 'the record keeps the try\'s numbers, rounded, and its verdict, and nothing unmeasured', () => {

	const summary = { vowel: { f0: 251.26, f1: 410.04, f2: 3050.55, f3: null, f3_minus_f2: null, duration_s: 0.2612 }, fricative: null };
	assert.deepEqual( attemptMeasures( summary, 'in', { kind: 'vowel', code: 'iy' } ),
		{ f0: 251.3, f1: 410, f2: 3050.6, duration_s: 0.261, verdict: 'in', target_vowel: 'iy' } );
	assert.deepEqual( attemptMeasures( { vowel: null, fricative: { centroid: 5612.44, duration_s: 0.2 } }, null, null ),
		{ centroid: 5612.4, duration_s: 0.2 } );

} );

test( 'a spoken try ends once the child has spoken and fallen quiet, or at its longest', () => {

	const hops = ( levels ) => levels.map( ( db, k ) => ( { t: k / 100, intensity_db: db } ) );
	const quietHops = Math.round( QUIET_END_S * 100 );
	assert.equal( attemptDone( [] ), false );
	assert.equal( attemptDone( hops( Array( 50 ).fill( 30 ) ) ), false, 'nothing said yet' );
	assert.equal( attemptDone( hops( [ ...Array( 10 ).fill( 30 ), ...Array( 20 ).fill( 70 ) ] ) ), false, 'still speaking' );
	assert.equal( attemptDone( hops( [ ...Array( 10 ).fill( 30 ), ...Array( 20 ).fill( 70 ), ...Array( quietHops + 1 ).fill( 30 ) ] ) ), true );
	assert.equal( attemptDone( hops( Array( MAX_ATTEMPT_S * 100 + 1 ).fill( 30 ) ) ), true, 'the longest try' );

} );

test( 'the spectrogram puts a tone\'s energy in its own row, and the panel says the measures in words', () => {

	const rate = 16000;
	const tone = Float32Array.from( { length: rate / 2 }, ( _, i ) => 0.5 * Math.sin( 2 * Math.PI * 2000 * i / rate ) );
	const rows = 64;
	const { db, top } = spectrogram( tone, rate, { columns: 10, rows, maxHz: 8000 } );
	for ( let c = 0; c < 10; c ++ ) {

		const column = Array.from( db.subarray( c * rows, ( c + 1 ) * rows ) );
		const loudest = column.indexOf( Math.max( ...column ) );
		assert.ok( Math.abs( ( loudest + 0.5 ) / rows * 8000 - 2000 ) <= 8000 / rows, `column ${ c }: row ${ loudest }` );

	}

	assert.ok( Number.isFinite( top ) );
	assert.equal( spectrogram( new Float32Array( 10 ), rate ).top, - Infinity );
	assert.equal( attemptWords( { vowel: { f0: 251.4, f1: 410, f2: 3050, f3: 3600, f3_minus_f2: 550, duration_s: 0.26 }, fricative: null } ),
		'vowel: F0 251 Hz, F1 410 Hz, F2 3050 Hz, F3 3600 Hz, F3 − F2 550 Hz, 0.26 s' );
	assert.equal( attemptWords( { vowel: null, fricative: null } ), 'Nothing measured: no voice and no hiss.' );

} );

test( 'an item\'s own listen settings set its target zone: the edge in sd, the meter share, the F3', () => {

	const vowel = ( f1, f2, f3 = 3300 ) => ( { vowel: { f0: 250, f1, f2, f3, duration_s: 0.25 }, fricative: null } );
	const strict = itemTarget( { target: { kind: 'word', text: 'beat' }, listen: { measure: 'vowel', vowel: 'iy', within_sd: 1 } }, VOWELS );
	assert.deepEqual( strict, { kind: 'vowel', code: 'iy', withinSd: 1 } );
	// 1.5 sd from the norm: in at the default edge, only near at an edge of 1.
	const f1 = Math.exp( VOWELS.iy.log_f1_f2.mean[ 0 ] + 1.5 * 0.1 );
	assert.equal( attemptZone( vowel( f1, 2800 ), itemTarget( { target: { kind: 'phoneme', text: 'i' } }, VOWELS ), VOWELS ), 'in' );
	assert.equal( attemptZone( vowel( f1, 2800 ), strict, VOWELS ), 'near' );
	const r = itemTarget( { target: { kind: 'phoneme', text: 'r' }, listen: { measure: 'rhotic' } }, VOWELS );
	assert.deepEqual( r, { kind: 'rhotic', f3BelowHz: F3_TARGET_HZ.child } );
	assert.equal( attemptZone( vowel( 500, 1400, 2000 ), r ), 'in' );
	assert.equal( attemptZone( vowel( 500, 1400, 2800 ), r ), 'near' );
	assert.equal( attemptZone( vowel( 500, 1400, 3300 ), r ), 'off' );
	const sh = itemTarget( { target: { kind: 'word', text: 'ship' }, listen: { measure: 'sibilant', sound: 'sh', from_share: 0.8 } } );
	const { sh: shEnd, s: sEnd } = SIBILANT_ENDS_HZ.child;
	const hiss = ( share ) => ( { vowel: null, fricative: { centroid: shEnd + share * ( sEnd - shEnd ), duration_s: 0.2 } } );
	assert.equal( attemptZone( hiss( 0.1 ), sh ), 'in' );
	assert.equal( attemptZone( hiss( 0.3 ), sh ), 'near' );
	assert.equal( attemptZone( hiss( 0.6 ), sh ), 'off' );

} );

test( 'a room whose quiet is loud is said to be noisy, once there is enough to tell', () => {

	const full = 94;
	const hops = ( floor, over ) => Array.from( { length: 200 }, ( _, k ) => ( { intensity_db: k % 3 ? floor + over : floor } ) );
	const loudRoom = full - NOISY_FLOOR_BELOW_FULL_SCALE_DB + 5;
	assert.equal( roomProblem( hops( full - 60, 30 ), full ), null, 'a quiet room' );
	assert.equal( roomProblem( hops( loudRoom, NOISY_CONTRAST_DB - 8 ), full ), 'noisy' );
	assert.equal( roomProblem( hops( loudRoom, NOISY_CONTRAST_DB + 2 ), full ), null, 'loud speech with short gaps stands clear of them' );
	assert.equal( roomProblem( hops( full - 20, 5 ).slice( 0, 50 ), full ), null, 'too little to tell' );

} );

test( 'an attempt keeps the microphone\'s last seconds and its hops, and a recording gives the same hops', () => {

	const sampleRate = 16000;
	const signal = Float32Array.from( vowel( { sampleRate, seconds: 1, f0: 220, formants: [ 700, 1200, 2600, 3500, 4500 ], bandwidths: [ 80, 100, 150, 200, 250 ] } ) );
	const live = new AttemptRecorder( { sampleRate, group: 'woman' } );
	for ( let i = 0; i < signal.length; i += 128 ) live.push( signal.subarray( i, i + 128 ) );
	const whole = new AttemptRecorder( { sampleRate, group: 'woman' } );
	const all = whole.analyseAll( signal );
	assert.ok( live.hops.length > 80 && all.length >= live.hops.length, `${ live.hops.length } hops live, ${ all.length } of the recording` );
	assert.deepEqual( live.hops.map( ( hop ) => hop.formants ), all.slice( 0, live.hops.length ).map( ( hop ) => hop.formants ) );
	assert.deepEqual( Array.from( live.samples() ), Array.from( signal ) );
	assert.ok( live.spectrumFormants && Math.abs( live.spectrumFormants[ 0 ] - 700 ) < 70, `F1 ${ live.spectrumFormants?.[ 0 ] }` );
	const long = new AttemptRecorder( { sampleRate, group: 'woman' } );
	for ( let k = 0; k < KEPT_SECONDS + 2; k ++ ) long.push( signal );
	assert.ok( long.samples().length <= KEPT_SECONDS * sampleRate && long.samples().length > ( KEPT_SECONDS - 1 ) * sampleRate );

} );
