// The listening page's pure parts: the chart's scales and norm ellipses, the verdict on a
// measurement, the /ʃ/–/s/ meter, the input's level checks, the summary of an attempt and the
// messages for every kind of bad input.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import {
	chartPoint, ellipse, IN_TARGET, inputProblem, nearestVowel, normDistance, sibilantPosition,
	SIBILANT_ENDS_HZ, sibilantBand, summariseAttempt, zoneOf,
} from '../../web/src/ui/listen/listenScales.js';
import { listenMessage, MESSAGES, pictureShapes } from '../../web/src/ui/listen/listenMessages.js';
import { microphoneErrorKind } from '../../web/src/ui/listen/audioInput.js';

const norm = ( f1, f2, sd1 = 0.1, sd2 = 0.08, rho = 0.3 ) => ( {
	mean: [ Math.log( f1 ), Math.log( f2 ) ],
	cov: [ [ sd1 * sd1, rho * sd1 * sd2 ], [ rho * sd1 * sd2, sd2 * sd2 ] ],
} );
const VOWELS = {
	iy: { ipa: 'i', log_f1_f2: norm( 300, 2800 ) },
	aa: { ipa: 'ɑ', log_f1_f2: norm( 850, 1250 ) },
	uw: { ipa: 'u', log_f1_f2: norm( 350, 1000 ) },
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

	for ( const kind of [ 'unsupported', 'refused', 'no-microphone', 'busy', 'not-audio', 'silent', 'clipping', 'whisper' ] ) {

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
