// The learner's articulation estimated from the formants (web/src/core/listen/articulationEstimate.js):
// the vowel targets' parameters blended with inverse distance weights in the group's normalised
// formant space.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';

import { blendParams, estimateArticulation, groupFormantScale, normalisedFormants, vowelWeights } from '../../web/src/core/listen/articulationEstimate.js';

const vowel = ( f1, f2, sd1 = 60, sd2 = 150, n = 30 ) => ( { n, f1: { mean: f1, sd: sd1 }, f2: { mean: f2, sd: sd2 } } );
const VOWELS = {
	iy: vowel( 300, 2800 ),
	ih: vowel( 450, 2400 ),
	aa: vowel( 850, 1250 ),
	uw: vowel( 350, 1000 ),
};
const TARGETS = {
	iy: { tip_height: 2, dorsum_height: 10, jaw_opening: 1, lip_rounding: 0 },
	ih: { tip_height: 1, dorsum_height: 6, jaw_opening: 3, lip_rounding: 0 },
	aa: { tip_height: - 4, dorsum_height: - 8, jaw_opening: 12, lip_rounding: 0.1 },
	uw: { tip_height: - 2, dorsum_height: 4, jaw_opening: 2, lip_rounding: 0.9 },
};
const sum = ( weights ) => Object.values( weights ).reduce( ( a, b ) => a + b, 0 );
const near = ( a, b, tolerance = 1e-9 ) => assert.ok( Math.abs( a - b ) <= tolerance, `${ a } is not ${ b }` );

test( 'a measure at a vowel\'s norm mean gives that vowel\'s parameters exactly', () => {

	for ( const [ code, entry ] of Object.entries( VOWELS ) ) {

		const estimate = estimateArticulation( { f1: entry.f1.mean, f2: entry.f2.mean }, VOWELS, TARGETS );
		assert.equal( estimate.weights[ code ], 1, code );
		assert.deepEqual( estimate.params, TARGETS[ code ], code );

	}

} );

test( 'halfway between two vowels, with two blended, gives each half the weight and the mean of their parameters', () => {

	const f1 = ( VOWELS.iy.f1.mean + VOWELS.ih.f1.mean ) / 2;
	const f2 = ( VOWELS.iy.f2.mean + VOWELS.ih.f2.mean ) / 2;
	const estimate = estimateArticulation( { f1, f2 }, VOWELS, TARGETS, { nearest: 2 } );
	assert.deepEqual( Object.keys( estimate.weights ).sort(), [ 'ih', 'iy' ] );
	near( estimate.weights.iy, 0.5 );
	near( estimate.weights.ih, 0.5 );
	for ( const name of Object.keys( TARGETS.iy ) ) near( estimate.params[ name ], ( TARGETS.iy[ name ] + TARGETS.ih[ name ] ) / 2 );

} );

test( 'halfway between two vowels, with three blended, the two share the most weight equally and the third has less', () => {

	const f1 = ( VOWELS.iy.f1.mean + VOWELS.ih.f1.mean ) / 2;
	const f2 = ( VOWELS.iy.f2.mean + VOWELS.ih.f2.mean ) / 2;
	const { weights, params } = estimateArticulation( { f1, f2 }, VOWELS, TARGETS );
	assert.equal( Object.keys( weights ).length, 3 );
	near( weights.iy, weights.ih );
	const third = Object.keys( weights ).find( ( code ) => code !== 'iy' && code !== 'ih' );
	assert.ok( weights[ third ] < weights.iy, JSON.stringify( weights ) );
	// Every parameter lies within the range of the blended targets.
	for ( const name of Object.keys( params ) ) {

		const values = Object.keys( weights ).map( ( code ) => TARGETS[ code ][ name ] );
		assert.ok( params[ name ] >= Math.min( ...values ) - 1e-12 && params[ name ] <= Math.max( ...values ) + 1e-12, name );

	}

} );

test( 'the weights sum to 1 and the nearest vowel weighs most, wherever the measure lies (seeded)', () => {

	let seed = 20240611;
	const random = () => ( ( seed = ( seed * 1664525 + 1013904223 ) >>> 0 ) / 2 ** 32 );
	const scale = groupFormantScale( VOWELS );
	for ( let k = 0; k < 500; k ++ ) {

		const f1 = 200 + 900 * random();
		const f2 = 700 + 2600 * random();
		const weights = vowelWeights( f1, f2, VOWELS );
		near( sum( weights ), 1, 1e-12 );
		for ( const w of Object.values( weights ) ) assert.ok( w >= 0 && w <= 1, `seed case ${ k }: ${ w }` );
		const [ z1, z2 ] = normalisedFormants( f1, f2, scale );
		const distance = ( code ) => {

			const [ v1, v2 ] = normalisedFormants( VOWELS[ code ].f1.mean, VOWELS[ code ].f2.mean, scale );
			return Math.hypot( z1 - v1, z2 - v2 );

		};
		const nearest = Object.keys( VOWELS ).sort( ( a, b ) => distance( a ) - distance( b ) )[ 0 ];
		const heaviest = Object.entries( weights ).sort( ( a, b ) => b[ 1 ] - a[ 1 ] )[ 0 ][ 0 ];
		assert.equal( heaviest, nearest, `case ${ k }: F1 ${ f1 } F2 ${ f2 }` );

	}

} );

test( 'the estimate moves smoothly as the measure passes the point where the nearest three change', () => {

	// Along a line from /i/ to /ɑ/, the parameters never jump between two close steps.
	let last = null;
	for ( let s = 0; s <= 1; s += 0.001 ) {

		const f1 = VOWELS.iy.f1.mean + s * ( VOWELS.aa.f1.mean - VOWELS.iy.f1.mean );
		const f2 = VOWELS.iy.f2.mean + s * ( VOWELS.aa.f2.mean - VOWELS.iy.f2.mean );
		const { params } = estimateArticulation( { f1, f2 }, VOWELS, TARGETS );
		if ( last ) assert.ok( Math.abs( params.dorsum_height - last.dorsum_height ) < 0.5, `at ${ s.toFixed( 3 ) }: ${ last.dorsum_height } to ${ params.dorsum_height }` );
		last = params;

	}

} );

test( 'unknown parameters pass through: a base value no target gives is kept, one only a single vowel gives is that vowel\'s', () => {

	const targets = { ...TARGETS, iy: { ...TARGETS.iy, velum_opening: 0.25 } };
	const f1 = ( VOWELS.iy.f1.mean + VOWELS.ih.f1.mean ) / 2;
	const f2 = ( VOWELS.iy.f2.mean + VOWELS.ih.f2.mean ) / 2;
	const { params } = estimateArticulation( { f1, f2 }, VOWELS, targets, { base: { some_future_parameter: 7, tip_height: 99 } } );
	assert.equal( params.some_future_parameter, 7 );
	assert.equal( params.velum_opening, 0.25 );
	assert.notEqual( params.tip_height, 99, 'a parameter the targets give is blended, not taken from the base' );
	assert.deepEqual( blendParams( { iy: 1 }, { iy: { a: 1 } }, { b: 2 } ), { a: 1, b: 2 } );

} );

test( 'vowels without a target take no part, and there is no estimate without a measure or a target', () => {

	const { weights } = estimateArticulation( { f1: 300, f2: 2800 }, VOWELS, { aa: TARGETS.aa, uw: TARGETS.uw } );
	assert.deepEqual( Object.keys( weights ).sort(), [ 'aa', 'uw' ] );
	assert.equal( estimateArticulation( null, VOWELS, TARGETS ), null );
	assert.equal( estimateArticulation( { f1: 0, f2: 2000 }, VOWELS, TARGETS ), null );
	assert.equal( estimateArticulation( { f1: 300, f2: 2800 }, VOWELS, {} ), null );

} );

test( 'the group\'s scale pools the spread within each vowel and between their means', () => {

	const two = { a: vowel( 400, 1000, 0, 0, 2 ), b: vowel( 600, 2000, 0, 0, 2 ) };
	const scale = groupFormantScale( two );
	near( scale.f1.mean, 500 );
	// Four tokens at 400, 400, 600, 600: sample standard deviation sqrt( 4 * 100^2 / 3 ).
	near( scale.f1.sd, Math.sqrt( 40000 / 3 ) );
	const spread = groupFormantScale( { a: vowel( 500, 1500, 30, 90, 11 ) } );
	near( spread.f1.sd, 30 );
	near( spread.f2.sd, 90 );

} );

const NORMS = new URL( '../../assets/build/vowel-norms.json', import.meta.url );

test( 'on the built norms, each group\'s vowel means give their own vowel, and a child\'s /i/ of "heed" leans to /i/', { skip: ! existsSync( NORMS ) && 'assets/build is not built' }, () => {

	const norms = JSON.parse( readFileSync( NORMS, 'utf8' ) );
	for ( const vowels of Object.values( norms.groups ) ) {

		const targets = Object.fromEntries( Object.keys( vowels ).map( ( code, k ) => [ code, { index: k } ] ) );
		for ( const [ code, entry ] of Object.entries( vowels ) ) {

			const { weights } = estimateArticulation( { f1: entry.f1.mean, f2: entry.f2.mean }, vowels, targets );
			assert.equal( weights[ code ], 1, code );

		}

	}

	// Hillenbrand's boy 14, "heed": about F1 420 Hz, F2 3050 Hz.
	const { weights } = estimateArticulation( { f1: 420, f2: 3050 }, norms.groups.child, Object.fromEntries( Object.keys( norms.groups.child ).map( ( c ) => [ c, {} ] ) ) );
	const heaviest = Object.entries( weights ).sort( ( a, b ) => b[ 1 ] - a[ 1 ] )[ 0 ][ 0 ];
	assert.equal( heaviest, 'iy', JSON.stringify( weights ) );

} );
