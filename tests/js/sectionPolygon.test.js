// The airway's mid-sagittal air polygon (web/src/core/sectionPolygon.js) on small exact sections.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { airwayPolygon, chainSegments, crossingsAt, insidePolygon } from '../../web/src/core/sectionPolygon.js';

/** Segments (x0 y0 z0 x1 y1 z1) along the polyline `points` (x y pairs), shuffled and some reversed. */
function segmentsOf( ...polylines ) {

	const list = [];
	for ( const { points, closed } of polylines ) {

		const n = points.length / 2;
		for ( let k = 0; k < ( closed ? n : n - 1 ); k ++ ) {

			const a = [ points[ 2 * k ], points[ 2 * k + 1 ], 0 ];
			const b = [ points[ 2 * ( ( k + 1 ) % n ) ], points[ 2 * ( ( k + 1 ) % n ) + 1 ], 0 ];
			list.push( k % 2 ? [ ...b, ...a ] : [ ...a, ...b ] );

		}

	}

	list.reverse();
	return Float32Array.from( list.flat() );

}

// A tube's section: the upper wall from the larynx (-50, -60) over the palate to the lip and up
// the face; the lower wall from (-40, -60) over the tongue to the lower lip and down the chin;
// a loop inside (the epiglottis).
const UPPER = { points: [ - 50, - 60, - 50, 20, 10, 25, 30, 6, 40, 20 ], closed: false };
const LOWER = { points: [ - 40, - 60, - 40, 10, 10, 12, 30, 2, 20, - 50 ], closed: false };
const LOOP = { points: [ - 46, - 40, - 44, - 40, - 44, - 36, - 46, - 36 ], closed: true };

test( 'section segments join into two open walls and a closed loop, whatever their order', () => {

	const segments = segmentsOf( UPPER, LOWER, LOOP );
	const chains = chainSegments( segments, segments.length / 6 );
	assert.equal( chains.length, 3 );
	assert.deepEqual( chains.map( ( c ) => [ c.points.length / 2, c.closed ] ).sort(), [ [ 4, true ], [ 5, false ], [ 5, false ] ] );

} );

test( 'the air runs from the larynx to the lip opening, leaves the face outside and the loop as a hole', () => {

	const segments = segmentsOf( UPPER, LOWER, LOOP );
	const air = airwayPolygon( chainSegments( segments, segments.length / 6 ) );
	assert.deepEqual( air.lips, [ 30, 6, 30, 2 ] );
	assert.equal( air.holes.length, 1 );
	assert.ok( insidePolygon( air.outline, 0, 15 ), 'between tongue and palate' );
	assert.ok( insidePolygon( air.outline, - 45, 0 ), 'in the pharynx' );
	assert.ok( ! insidePolygon( air.outline, 35, 10 ), 'in front of the lips' );
	assert.ok( ! insidePolygon( air.outline, 25, - 20 ), 'the chin' );
	const ys = new Float64Array( 4 );
	assert.equal( crossingsAt( air.upper, 0, ys ), 1 );
	assert.ok( Math.abs( ys[ 0 ] - ( 20 + 5 * 50 / 60 ) ) < 1e-5 );
	assert.equal( crossingsAt( air.lower, 0, ys ), 1 );
	assert.ok( Math.abs( ys[ 0 ] - 11.6 ) < 1e-5 );

} );

test( 'a section with fewer than two open walls is refused', () => {

	const segments = segmentsOf( UPPER );
	assert.throws( () => airwayPolygon( chainSegments( segments, segments.length / 6 ) ), /1 open wall/ );

} );
