// B-spline basis functions (The NURBS Book A2.1, A2.2) against the shared vectors written by
// Python and against the Cox-de Boor recursion evaluated directly.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { random as seededRandom } from '../../bench/support/stats.mjs';
import { basisFuns, basisTable, findSpan, periodicKnots } from '../../web/src/core/bspline.js';

import { near, nearArray, readVectors, tolerance } from './support/vectors.js';

const VECTORS = readVectors( 'tongue-bspline.json' );
/** Basis weights against the Python reference (the file states the reason). */
const BASIS = tolerance( VECTORS, 'basis' );

// Cox-de Boor, straight from the definition (slow; degree-0 spans half-open, the last closed).
function coxDeBoor( knots, i, degree, u ) {

	if ( degree === 0 ) {

		const last = knots[ knots.length - 1 ];
		if ( u === last ) return knots[ i ] < u && knots[ i + 1 ] === u ? 1 : 0;
		return knots[ i ] <= u && u < knots[ i + 1 ] ? 1 : 0;

	}

	let value = 0;
	const a = knots[ i + degree ] - knots[ i ];
	const b = knots[ i + degree + 1 ] - knots[ i + 1 ];
	if ( a > 0 ) value += ( u - knots[ i ] ) / a * coxDeBoor( knots, i, degree - 1, u );
	if ( b > 0 ) value += ( knots[ i + degree + 1 ] - u ) / b * coxDeBoor( knots, i + 1, degree - 1, u );
	return value;

}

test( 'the vector file has cases with unique descriptions', () => {

	const descriptions = VECTORS.cases.map( ( c ) => c.description );
	assert.ok( descriptions.length >= 6 );
	assert.equal( new Set( descriptions ).size, descriptions.length );

} );

for ( const vector of VECTORS.cases ) {

	test( `basis tables match Python: ${vector.description}`, () => {

		const { knots, degree, params } = vector.input;
		const { first, values } = basisTable( knots, degree, params );
		assert.deepEqual( Array.from( first ), vector.expected.first ); // spans: integers
		const expected = vector.expected.values.flat();
		for ( let k = 0; k < expected.length; k ++ ) near( values[ k ], expected[ k ], BASIS, `value ${k}` );

	} );

}

test( 'basis functions agree with the Cox-de Boor recursion on seeded random clamped knots', () => {

	const seed = 7;
	const random = seededRandom( seed );
	const left = new Float64Array( 6 );
	const right = new Float64Array( 6 );
	const target = new Float64Array( 6 );
	for ( let trial = 0; trial < 50; trial ++ ) {

		const degree = 1 + Math.floor( random() * 4 );
		const inner = Array.from( { length: 1 + Math.floor( random() * 6 ) }, () => 0.02 + 0.96 * random() ).sort( ( a, b ) => a - b );
		const knots = [ ...new Array( degree + 1 ).fill( 0 ), ...inner, ...new Array( degree + 1 ).fill( 1 ) ];
		for ( let s = 0; s < 10; s ++ ) {

			const u = s === 0 ? 1 : random();
			const span = findSpan( knots, degree, u );
			basisFuns( knots, degree, span, u, target, 0, left, right );
			for ( let i = 0; i <= degree; i ++ ) {

				const reference = coxDeBoor( knots, span - degree + i, degree, u );
				assert.ok( Math.abs( target[ i ] - reference ) < 1e-12, `seed ${seed}, trial ${trial}, u ${u}: N${span - degree + i} ${target[ i ]} vs ${reference}` );

			}

		}

	}

} );

test( 'uniform cubic basis at a knot of a closed curve is 1/6, 4/6, 1/6, 0', () => {

	const knots = periodicKnots( 8, 3 );
	const { first, values } = basisTable( knots, 3, [ 0.25 ] );
	assert.equal( first[ 0 ], 2 );
	const expected = [ 1 / 6, 4 / 6, 1 / 6, 0 ];
	expected.forEach( ( e, k ) => assert.ok( Math.abs( values[ k ] - e ) < 1e-15 ) );

} );

test( 'basis functions sum to one and are never negative', () => {

	const knots = [ - 90, - 90, - 90, - 90, - 66, - 46, - 32, - 22, - 12, 0, 12, 22, 32, 46, 66, 90, 90, 90, 90 ];
	const params = Array.from( { length: 181 }, ( _, k ) => - 90 + k );
	const { values } = basisTable( knots, 3, params );
	for ( let k = 0; k < params.length; k ++ ) {

		let sum = 0;
		for ( let i = 0; i < 4; i ++ ) {

			assert.ok( values[ 4 * k + i ] >= 0 );
			sum += values[ 4 * k + i ];

		}

		assert.ok( Math.abs( sum - 1 ) < 1e-14, `at ${params[ k ]}: sum ${sum}` );

	}

} );

test( 'a clamped curve starts on its first control point and ends on its last', () => {

	const knots = [ 0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1 ];
	const { first, values } = basisTable( knots, 3, [ 0, 1 ] );
	assert.deepEqual( Array.from( first ), [ 0, 2 ] );
	nearArray( values, [ 1, 0, 0, 0, 0, 0, 0, 1 ], 1e-15, 'basis at the clamped ends' );

} );

test( 'bad knot vectors are refused with a message', () => {

	assert.throws( () => basisTable( [ 0, 1, 0.5, 1 ], 1, [ 0.2 ] ), /non-decreasing/ );
	assert.throws( () => basisTable( [ 0, 1 ], 1, [ 0.2 ] ), /too few/ );
	assert.throws( () => periodicKnots( 3, 3 ), /more than 3 points/ );

} );
