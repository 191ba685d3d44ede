// Smooth shading across the seam of two meshes (web/src/core/weldNormals.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { weldNormals } from '../../web/src/core/weldNormals.js';

test( 'coincident vertices of two meshes get the same, averaged unit normal', () => {

	// Two triangles meeting along the edge (0,0,0)-(0,1,0) at a right angle.
	const a = { positions: Float32Array.of( 0, 0, 0, 0, 1, 0, 1, 0, 0 ), normals: Float32Array.of( 0, 0, 1, 0, 0, 1, 0, 0, 1 ) };
	const b = { positions: Float32Array.of( 0, 1, 0, 0, 0, 0, 0, 0, 1 ), normals: Float32Array.of( 1, 0, 0, 1, 0, 0, 1, 0, 0 ) };
	const changed = weldNormals( [ a, b ] );
	assert.equal( changed, 4 );
	const h = Math.SQRT1_2;
	for ( const normal of [ a.normals.subarray( 0, 3 ), a.normals.subarray( 3, 6 ), b.normals.subarray( 0, 3 ), b.normals.subarray( 3, 6 ) ] ) {

		assert.ok( Math.abs( normal[ 0 ] - h ) < 1e-6 && Math.abs( normal[ 1 ] ) < 1e-6 && Math.abs( normal[ 2 ] - h ) < 1e-6, `normal ${ normal }` );

	}

	// Vertices away from the seam keep their own normals.
	assert.deepEqual( Array.from( a.normals.subarray( 6 ) ), [ 0, 0, 1 ] );
	assert.deepEqual( Array.from( b.normals.subarray( 6 ) ), [ 1, 0, 0 ] );

} );

test( 'vertices that coincide within one mesh are left alone', () => {

	const a = { positions: Float32Array.of( 0, 0, 0, 0, 0, 0 ), normals: Float32Array.of( 1, 0, 0, 0, 1, 0 ) };
	assert.equal( weldNormals( [ a ] ), 0 );
	assert.deepEqual( Array.from( a.normals ), [ 1, 0, 0, 0, 1, 0 ] );

} );

test( 'points closer than the tolerance count as one; mismatched arrays are refused', () => {

	const a = { positions: Float32Array.of( 0, 0, 0 ), normals: Float32Array.of( 1, 0, 0 ) };
	const b = { positions: Float32Array.of( 0.0001, 0, 0 ), normals: Float32Array.of( 0, 1, 0 ) };
	assert.equal( weldNormals( [ a, b ], 0.01 ), 2 );
	assert.ok( Math.abs( a.normals[ 0 ] - b.normals[ 0 ] ) < 1e-7 );
	assert.throws( () => weldNormals( [ { positions: new Float32Array( 3 ), normals: new Float32Array( 6 ) } ] ), /normals must match/ );
	assert.throws( () => weldNormals( [ a ], 0 ), /tolerance/ );

} );
