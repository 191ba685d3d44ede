// The mid-sagittal section as polylines (web/src/core/midSection.js) on small exact meshes, against
// the per-triangle section of core/section.js on seeded random meshes, and without allocation.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { createSectionPart, cutSection, isPlanarPose, posePoints } from '../../web/src/core/midSection.js';
import { planeSectionSegments } from '../../web/src/core/section.js';
import { random } from '../../bench/support/stats.mjs';
import { fewestGarbageCollections } from './support/garbage.js';

/** The points of chain c as [ [ x, y ], ... ]. */
function chainPoints( part, c ) {

	const out = [];
	for ( let k = part.starts[ c ]; k < part.starts[ c + 1 ]; k ++ ) out.push( [ part.points[ 2 * k ], part.points[ 2 * k + 1 ] ] );
	return out;

}

/** Shoelace area of a closed chain. */
function area( points ) {

	let sum = 0;
	for ( let i = 0; i < points.length; i ++ ) {

		const [ x0, y0 ] = points[ i ], [ x1, y1 ] = points[ ( i + 1 ) % points.length ];
		sum += x0 * y1 - x1 * y0;

	}

	return Math.abs( sum ) / 2;

}

const sortPoints = ( points ) => points.map( ( p ) => p.map( ( v ) => Math.round( v * 1e9 ) / 1e9 ) ).sort( ( a, b ) => a[ 0 ] - b[ 0 ] || a[ 1 ] - b[ 1 ] );

test( 'a tetrahedron with one vertex below the plane cuts into one closed triangle at its edges\' midpoints', () => {

	const positions = Float32Array.of( 0, 0, - 1, 2, 0, 1, 0, 2, 1, 0, 0, 1 );
	const index = Uint32Array.of( 0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3 );
	const part = createSectionPart( index, 4 );
	assert.equal( cutSection( part, positions ), 3 );
	assert.equal( part.segmentCount, 3 );
	assert.equal( part.chainCount, 1 );
	assert.equal( part.closed[ 0 ], 1 );
	assert.deepEqual( sortPoints( chainPoints( part, 0 ) ), [ [ 0, 0 ], [ 0, 1 ], [ 1, 0 ] ] );

} );

/** A box [ 0, 4 ] x [ 0, 2 ] x [ -1, 1 ]: 8 corners, 12 triangles. */
function box() {

	const positions = new Float32Array( 24 );
	for ( let v = 0; v < 8; v ++ ) positions.set( [ v & 1 ? 4 : 0, v & 2 ? 2 : 0, v & 4 ? 1 : - 1 ], 3 * v );
	const quads = [ [ 0, 1, 3, 2 ], [ 4, 6, 7, 5 ], [ 0, 4, 5, 1 ], [ 2, 3, 7, 6 ], [ 0, 2, 6, 4 ], [ 1, 5, 7, 3 ] ];
	const index = Uint32Array.from( quads.flatMap( ( [ a, b, c, d ] ) => [ a, b, c, a, c, d ] ) );
	return { positions, index };

}

test( 'a box cut through its middle is one closed loop on its rectangle, of the rectangle\'s area', () => {

	const { positions, index } = box();
	const part = createSectionPart( index, 8 );
	cutSection( part, positions );
	assert.equal( part.chainCount, 1 );
	assert.equal( part.closed[ 0 ], 1 );
	const points = chainPoints( part, 0 );
	assert.equal( points.length, 8, 'four corners and the four side diagonals\' midpoints' );
	for ( const [ x, y ] of points ) assert.ok( x === 0 || x === 4 || y === 0 || y === 2, `(${ x }, ${ y }) is on the rectangle` );
	assert.equal( area( points ), 8 );

} );

test( 'a box above the plane has no section; moved down it has one again, in the same buffers', () => {

	const { positions, index } = box();
	const part = createSectionPart( index, 8 );
	for ( let v = 0; v < 8; v ++ ) positions[ 3 * v + 2 ] += 5;
	assert.equal( cutSection( part, positions ), 0 );
	assert.equal( part.chainCount, 0 );
	for ( let v = 0; v < 8; v ++ ) positions[ 3 * v + 2 ] -= 5;
	assert.equal( cutSection( part, positions ), 8 );

} );

test( 'an open strip crossing the plane gives one open polyline, in order from one end to the other', () => {

	// A strip along x from 0 to 4, z from -1 to 1, y = x * x.
	const positions = [];
	for ( let i = 0; i <= 4; i ++ ) positions.push( i, i * i, - 1, i, i * i, 1 );
	const index = [];
	for ( let i = 0; i < 4; i ++ ) index.push( 2 * i, 2 * i + 2, 2 * i + 1, 2 * i + 1, 2 * i + 2, 2 * i + 3 );
	const part = createSectionPart( Uint32Array.from( index ), 10 );
	cutSection( part, Float32Array.from( positions ) );
	assert.equal( part.chainCount, 1 );
	assert.equal( part.closed[ 0 ], 0 );
	const xs = chainPoints( part, 0 ).map( ( [ x ] ) => x );
	const ascending = xs[ 0 ] < xs[ xs.length - 1 ] ? xs : [ ...xs ].reverse();
	assert.deepEqual( ascending, [ 0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4 ] );

} );

test( 'a planar pose maps the cut points; a pose that tilts the plane is refused', () => {

	const { positions, index } = box();
	const part = createSectionPart( index, 8 );
	// A quarter turn about z and a shift of (10, 20).
	const pose = Float64Array.of( 0, - 1, 0, 10, 1, 0, 0, 20, 0, 0, 1, 0 );
	assert.ok( isPlanarPose( pose ) );
	cutSection( part, positions, pose );
	const points = chainPoints( part, 0 );
	for ( let k = 0; k < points.length; k ++ ) {

		const lx = part.local[ 2 * k ], ly = part.local[ 2 * k + 1 ];
		assert.deepEqual( points[ k ], [ 10 - ly, 20 + lx ] );

	}

	const tilted = Float64Array.of( 1, 0, 0, 0, 0, 0, - 1, 0, 0, 1, 0, 0 );
	assert.equal( isPlanarPose( tilted ), false );
	assert.throws( () => posePoints( part, tilted ), /out of the mid-sagittal plane/ );

} );

/** A jittered UV sphere (closed, indexed), centre near the plane. */
function sphere( next, rings = 12, segments = 16 ) {

	const positions = [ 0, 0, 10 ];
	for ( let r = 1; r < rings; r ++ ) {

		for ( let s = 0; s < segments; s ++ ) {

			const theta = Math.PI * r / rings, phi = 2 * Math.PI * s / segments;
			const radius = 8 + 2 * next();
			positions.push( radius * Math.sin( theta ) * Math.cos( phi ), radius * Math.sin( theta ) * Math.sin( phi ) + 3 * next(), radius * Math.cos( theta ) + 0.5 + next() );

		}

	}

	positions.push( 0, 0, - 10 );
	const last = positions.length / 3 - 1;
	const ring = ( r, s ) => 1 + ( r - 1 ) * segments + ( s % segments );
	const index = [];
	for ( let s = 0; s < segments; s ++ ) index.push( 0, ring( 1, s ), ring( 1, s + 1 ) );
	for ( let r = 1; r < rings - 1; r ++ ) for ( let s = 0; s < segments; s ++ ) index.push( ring( r, s ), ring( r + 1, s ), ring( r + 1, s + 1 ), ring( r, s ), ring( r + 1, s + 1 ), ring( r, s + 1 ) );
	for ( let s = 0; s < segments; s ++ ) index.push( last, ring( rings - 1, s + 1 ), ring( rings - 1, s ) );
	return { positions: Float32Array.from( positions ), index: Uint32Array.from( index ), vertexCount: last + 1 };

}

test( 'on seeded random spheres the chains hold exactly the segments of the per-triangle section, as one closed loop', () => {

	const seed = 20261123;
	const next = random( seed );
	for ( let trial = 0; trial < 20; trial ++ ) {

		const { positions, index, vertexCount } = sphere( next );
		const part = createSectionPart( index, vertexCount );
		cutSection( part, positions );
		const segments = new Float32Array( index.length * 2 );
		const count = planeSectionSegments( positions, index, 0, segments );
		assert.equal( part.segmentCount, count, `seed ${ seed }, trial ${ trial }` );
		assert.equal( part.chainCount, 1, `seed ${ seed }, trial ${ trial }: one loop` );
		assert.equal( part.closed[ 0 ], 1 );
		assert.equal( part.pointCount, count );
		// Each chain edge is one of the reference segments (within float32 rounding).
		const reference = [];
		for ( let s = 0; s < count; s ++ ) reference.push( [ segments[ 6 * s ], segments[ 6 * s + 1 ], segments[ 6 * s + 3 ], segments[ 6 * s + 4 ] ] );
		const points = chainPoints( part, 0 );
		for ( let k = 0; k < points.length; k ++ ) {

			const [ ax, ay ] = points[ k ], [ bx, by ] = points[ ( k + 1 ) % points.length ];
			const found = reference.some( ( [ x0, y0, x1, y1 ] ) => ( Math.hypot( x0 - ax, y0 - ay ) < 1e-4 && Math.hypot( x1 - bx, y1 - by ) < 1e-4 ) || ( Math.hypot( x0 - bx, y0 - by ) < 1e-4 && Math.hypot( x1 - ax, y1 - ay ) < 1e-4 ) );
			assert.ok( found, `seed ${ seed }, trial ${ trial }: edge ${ k } is a section segment` );

		}

	}

} );

test( 'a part recut frame after frame gives what a fresh part gives, whether or not vertices change side', () => {

	const next = random( 11 );
	const { positions, index, vertexCount } = sphere( next );
	const part = createSectionPart( index, vertexCount );
	const fields = ( p ) => [ p.segmentCount, p.pointCount, p.chainCount, Array.from( p.points.subarray( 0, 2 * p.pointCount ) ), Array.from( p.starts.subarray( 0, p.chainCount + 1 ) ), Array.from( p.closed.subarray( 0, p.chainCount ) ) ];
	for ( let frame = 0; frame < 30; frame ++ ) {

		// Even frames move vertices in x y only (no side changes); odd ones shift z as well.
		for ( let v = 0; v < vertexCount; v ++ ) {

			positions[ 3 * v ] += next() - 0.5;
			if ( frame % 2 === 1 ) positions[ 3 * v + 2 ] += 0.6 * ( next() - 0.5 );

		}

		cutSection( part, positions );
		const fresh = createSectionPart( index, vertexCount );
		cutSection( fresh, positions );
		assert.deepEqual( fields( part ), fields( fresh ), `frame ${ frame }` );

	}

} );

test( 'recutting a moving mesh allocates nothing', async () => {

	const { positions, index, vertexCount } = sphere( random( 7 ), 24, 32 );
	const part = createSectionPart( index, vertexCount );
	const pose = Float64Array.of( 1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 0 );
	const collections = await fewestGarbageCollections( () => {

		for ( let frame = 0; frame < 20000; frame ++ ) {

			positions[ 2 ] = 10 + ( frame % 3 );
			cutSection( part, positions, pose );

		}

	} );
	assert.equal( collections, 0 );

} );
