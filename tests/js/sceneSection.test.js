// The section of a mesh by the plane z = c (web/src/core/section.js), which outlines the cutaway.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { planeSectionSegments } from '../../web/src/core/section.js';
import { near } from './support/near.js';

/** An axis-aligned box [lo, hi]^3 as 12 outward-wound triangles. */
function box( lo, hi ) {

	const positions = new Float32Array( 24 );
	for ( let i = 0; i < 8; i ++ ) {

		positions[ 3 * i ] = i & 1 ? hi : lo;
		positions[ 3 * i + 1 ] = i & 2 ? hi : lo;
		positions[ 3 * i + 2 ] = i & 4 ? hi : lo;

	}

	const index = Uint16Array.from( [
		0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, // z = lo, z = hi
		0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, // y = lo, y = hi
		0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5, // x = lo, x = hi
	] );
	return { positions, index };

}

/** A UV sphere of radius r about the origin. */
function sphere( r, rings, segments ) {

	const positions = [];
	for ( let i = 0; i <= rings; i ++ ) {

		const theta = Math.PI * i / rings;
		for ( let j = 0; j < segments; j ++ ) {

			const phi = 2 * Math.PI * j / segments;
			positions.push( r * Math.sin( theta ) * Math.cos( phi ), r * Math.sin( theta ) * Math.sin( phi ), r * Math.cos( theta ) );

		}

	}

	const index = [];
	for ( let i = 0; i < rings; i ++ ) {

		for ( let j = 0; j < segments; j ++ ) {

			const a = i * segments + j, b = i * segments + ( j + 1 ) % segments;
			index.push( a, a + segments, b, b, a + segments, b + segments );

		}

	}

	return { positions: Float64Array.from( positions ), index: Uint32Array.from( index ) };

}

function segmentsOf( target, count ) {

	const out = [];
	for ( let s = 0; s < count; s ++ ) out.push( Array.from( target.subarray( 6 * s, 6 * s + 6 ) ) );
	return out;

}

test( 'the section of a box through its middle is its square outline', () => {

	const { positions, index } = box( - 1, 1 );
	const target = new Float32Array( 6 * 12 );
	const count = planeSectionSegments( positions, index, 0.25, target );
	assert.equal( count, 8 ); // two triangles per side face cross the plane
	let perimeter = 0;
	for ( const [ x0, y0, z0, x1, y1, z1 ] of segmentsOf( target, count ) ) {

		near( z0, 0.25, 1e-7, 'on the plane (float32)' );
		near( z1, 0.25, 1e-7, 'on the plane (float32)' );
		for ( const v of [ x0, y0, x1, y1 ] ) assert.ok( Math.abs( v ) <= 1 );
		// Every end lies on the square's edge.
		assert.ok( Math.max( Math.abs( x0 ), Math.abs( y0 ) ) === 1 && Math.max( Math.abs( x1 ), Math.abs( y1 ) ) === 1 );
		perimeter += Math.hypot( x1 - x0, y1 - y0 );

	}

	assert.ok( Math.abs( perimeter - 8 ) < 1e-6, `perimeter ${ perimeter }` );

} );

test( 'a plane that misses the mesh gives no segments', () => {

	const { positions, index } = box( - 1, 1 );
	const target = new Float32Array( 6 * 12 );
	assert.equal( planeSectionSegments( positions, index, 1.5, target ), 0 );
	assert.equal( planeSectionSegments( positions, index, - 1.0001, target ), 0 );

} );

test( 'the section of a sphere lies on the circle where the plane cuts it', () => {

	const r = 50, c = 20;
	const { positions, index } = sphere( r, 24, 48 );
	const target = new Float32Array( 2 * index.length );
	const count = planeSectionSegments( positions, index, c, target );
	assert.ok( count >= 48, `only ${ count } segments` );
	const expected = Math.sqrt( r * r - c * c );
	for ( const [ x0, y0, , x1, y1 ] of segmentsOf( target, count ) ) {

		// The mesh is a polyhedron inside the sphere: the section points lie just inside the circle.
		for ( const radius of [ Math.hypot( x0, y0 ), Math.hypot( x1, y1 ) ] ) assert.ok( radius <= expected + 1e-4 && radius > expected * 0.97, `radius ${ radius }` );

	}

} );

test( 'non-indexed positions give the same section as the indexed mesh', () => {

	const { positions, index } = box( - 1, 1 );
	const flat = new Float32Array( 3 * index.length );
	index.forEach( ( v, i ) => flat.set( positions.subarray( 3 * v, 3 * v + 3 ), 3 * i ) );
	const a = new Float32Array( 72 ), b = new Float32Array( 72 );
	const count = planeSectionSegments( positions, index, 0.5, a );
	assert.equal( planeSectionSegments( flat, null, 0.5, b ), count );
	assert.deepEqual( a, b );

} );

test( 'a target too small for the section is refused, not overrun', () => {

	const { positions, index } = box( - 1, 1 );
	assert.throws( () => planeSectionSegments( positions, index, 0, new Float32Array( 6 * 3 ) ), /target holds 3 segments/ );
	assert.throws( () => planeSectionSegments( positions, index.subarray( 0, 4 ), 0, new Float32Array( 72 ) ), /multiple of 3/ );

} );
