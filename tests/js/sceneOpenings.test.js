// Openings of a surface and the patches that close them (web/src/core/openings.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { boundaryLoops, domePatch, loopFrame } from '../../web/src/core/openings.js';

/**
 * A square sheet in the plane y = 0 of (k+1) x (k+1) vertices, spacing 1, facing +y, with the
 * middle cell (or cells, `hole` wide) removed: a frame with a square hole.
 */
function sheetWithHole( k = 4, hole = 2 ) {

	const positions = [];
	for ( let i = 0; i <= k; i ++ ) for ( let j = 0; j <= k; j ++ ) positions.push( i, 0, j );
	const index = [];
	const v = ( i, j ) => i * ( k + 1 ) + j;
	const lo = ( k - hole ) / 2, hi = lo + hole;
	for ( let i = 0; i < k; i ++ ) {

		for ( let j = 0; j < k; j ++ ) {

			if ( i >= lo && i < hi && j >= lo && j < hi ) continue;
			// Wound so that the normal (b - a) x (c - a) is +y.
			index.push( v( i, j ), v( i, j + 1 ), v( i + 1, j ), v( i + 1, j ), v( i, j + 1 ), v( i + 1, j + 1 ) );

		}

	}

	return { positions: Float32Array.from( positions ), index: Uint32Array.from( index ) };

}

function triangleNormal( positions, index, t ) {

	const p = ( k ) => [ 0, 1, 2 ].map( ( c ) => positions[ 3 * index[ 3 * t + k ] + c ] );
	const [ a, b, c ] = [ p( 0 ), p( 1 ), p( 2 ) ];
	const u = b.map( ( x, i ) => x - a[ i ] ), w = c.map( ( x, i ) => x - a[ i ] );
	return [ u[ 1 ] * w[ 2 ] - u[ 2 ] * w[ 1 ], u[ 2 ] * w[ 0 ] - u[ 0 ] * w[ 2 ], u[ 0 ] * w[ 1 ] - u[ 1 ] * w[ 0 ] ];

}

test( 'a sheet with a hole has two boundary loops: the outer edge and the hole', () => {

	const { positions, index } = sheetWithHole();
	assert.ok( triangleNormal( positions, index, 0 )[ 1 ] > 0, 'the test sheet faces +y' );
	const loops = boundaryLoops( index );
	assert.equal( loops.length, 2 );
	const sizes = loops.map( ( loop ) => loop.length ).sort( ( a, b ) => a - b );
	assert.deepEqual( sizes, [ 8, 16 ] );
	const hole = loops.find( ( loop ) => loop.length === 8 );
	for ( const vertex of hole ) {

		const [ x, , z ] = [ positions[ 3 * vertex ], 0, positions[ 3 * vertex + 2 ] ];
		assert.ok( x >= 1 && x <= 3 && z >= 1 && z <= 3 && ( x === 1 || x === 3 || z === 1 || z === 3 ) );

	}

} );

test( 'a closed mesh has no boundary loops', () => {

	// A tetrahedron.
	const index = Uint32Array.of( 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2 );
	assert.deepEqual( boundaryLoops( index ), [] );
	assert.throws( () => boundaryLoops( Uint32Array.of( 0, 1 ) ), /multiple of 3/ );

} );

test( 'the frame of the hole sits at its centre and faces the way the sheet faces', () => {

	const { positions, index } = sheetWithHole();
	const hole = boundaryLoops( index ).find( ( loop ) => loop.length === 8 );
	const frame = loopFrame( positions, hole );
	frame.centre.forEach( ( c, i ) => assert.ok( Math.abs( c - [ 2, 0, 2 ][ i ] ) < 1e-9 ) );
	assert.ok( Math.abs( frame.normal[ 1 ] - 1 ) < 1e-9, `normal ${ frame.normal }` );
	assert.ok( Math.abs( frame.perimeter - 8 ) < 1e-9 );
	assert.equal( frame.minZ, 1 );
	assert.equal( frame.maxZ, 3 );

} );

test( 'a dome patch closes the hole with triangles wound like the sheet and rises along the normal', () => {

	const { positions, index } = sheetWithHole();
	const hole = boundaryLoops( index ).find( ( loop ) => loop.length === 8 );
	const frame = loopFrame( positions, hole );
	const patch = domePatch( positions, hole, frame, { rings: 3, bulge: 0.5 } );
	assert.equal( patch.positions.length / 3, 1 + 3 * 8 );
	assert.equal( patch.index.length / 3, 8 * ( 2 * 3 - 1 ) );
	// The centre is lifted by the full bulge, the outer ring lies on the hole's edge.
	assert.ok( Math.abs( patch.positions[ 1 ] - 0.5 ) < 1e-6 );
	assert.equal( patch.coords[ 2 ], 0 );
	for ( let i = 0; i < 8; i ++ ) {

		const slot = 1 + 2 * 8 + i;
		for ( let c = 0; c < 3; c ++ ) assert.ok( Math.abs( patch.positions[ 3 * slot + c ] - positions[ 3 * hole[ i ] + c ] ) < 1e-6 );
		assert.equal( patch.coords[ 3 * slot + 2 ], 1 );

	}

	for ( let t = 0; t < patch.index.length / 3; t ++ ) {

		assert.ok( triangleNormal( patch.positions, patch.index, t )[ 1 ] > 0, `patch triangle ${ t } faces away from the sheet's side` );

	}

	// Together, sheet and patch are a surface without a hole: every patch edge on the hole's rim
	// runs against the sheet's edge.
	const combined = Uint32Array.from( [ ...index, ...Array.from( patch.index, ( v ) => v + positions.length / 3 ) ] );
	const weld = new Map( Array.from( { length: 8 }, ( _, i ) => [ positions.length / 3 + 1 + 16 + i, hole[ i ] ] ) );
	const welded = combined.map( ( v ) => weld.get( v ) ?? v );
	assert.equal( boundaryLoops( welded ).length, 1, 'only the outer edge stays open' );

} );
