// First crossings of rays from one origin with a triangle mesh (web/src/core/rayFirstHit.js):
// small exact cases, seeded random meshes and rays against a brute-force loop over every
// triangle, the fitted tongue of the shared vectors, and no allocation per call.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { createRayFan, crossing, FAN_CELLS, faceOf, rayFirstHits } from '../../web/src/core/rayFirstHit.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { random as seededRandom } from '../../bench/support/stats.mjs';
import { fewestGarbageCollections, garbageCollections } from './support/garbage.js';
import { near } from './support/near.js';

const RIG = JSON.parse( readFileSync( join( dirname( fileURLToPath( import.meta.url ) ), '..', 'vectors', 'tongue-surface.json' ), 'utf8' ) ).fixtures.rig;

/** The first crossing of every ray, by testing every triangle: the reference. */
function bruteForce( fan, positions, triangles ) {

	const [ ox, oy, oz ] = fan.origin;
	const result = new Float64Array( fan.count ).fill( Infinity );
	for ( let k = 0; k < fan.count; k ++ ) {

		const [ dx, dy, dz ] = fan.directions.subarray( 3 * k, 3 * k + 3 );
		for ( let t = 0; t < triangles.length / 3; t ++ ) {

			const [ a, b, c ] = [ 0, 1, 2 ].map( ( i ) => 3 * triangles[ 3 * t + i ] );
			const e = ( v, i ) => positions[ v + i ] - positions[ a + i ];
			const hit = crossing( dx, dy, dz, ox - positions[ a ], oy - positions[ a + 1 ], oz - positions[ a + 2 ], e( b, 0 ), e( b, 1 ), e( b, 2 ), e( c, 0 ), e( c, 1 ), e( c, 2 ) );
			if ( hit > 0 && hit < result[ k ] ) result[ k ] = hit;

		}

	}

	return result;

}

/**
 * Equal to the brute force, ray by ray. Exactly: both run the same operations on the same
 * numbers in the same engine, so any difference is a pair the culling wrongly skipped.
 */
function assertSameHits( fan, positions, triangles, what ) {

	const target = new Float64Array( fan.count );
	const hits = rayFirstHits( fan, positions, triangles, triangles.length / 3, target );
	const reference = bruteForce( fan, positions, triangles );
	for ( let k = 0; k < fan.count; k ++ ) assert.equal( target[ k ], reference[ k ], `${ what }: ray ${ k }` );
	assert.equal( hits, reference.filter( Number.isFinite ).length );
	return { target, hits };

}

/** A UV sphere of radius about `radius` (each vertex scaled by 1 +- `wobble`) round `center`, with its poles. */
function sphere( center, radius, wobble, random, rings = 12, segments = 24 ) {

	const positions = [];
	const triangles = [];
	positions.push( center[ 0 ], center[ 1 ] + radius, center[ 2 ] );
	for ( let i = 1; i < rings; i ++ ) {

		const theta = Math.PI * i / rings;
		for ( let j = 0; j < segments; j ++ ) {

			const phi = 2 * Math.PI * j / segments;
			const r = radius * ( 1 + wobble * ( 2 * random() - 1 ) );
			// On j = 0 and j = segments / 2, z is exactly 0: rays in the plane z = 0 meet edges there.
			const z = j % ( segments / 2 ) === 0 ? 0 : r * Math.sin( theta ) * Math.sin( phi );
			positions.push( center[ 0 ] + r * Math.sin( theta ) * Math.cos( phi ), center[ 1 ] + r * Math.cos( theta ), center[ 2 ] + z );

		}

	}

	positions.push( center[ 0 ], center[ 1 ] - radius, center[ 2 ] );
	const ring = ( i, j ) => 1 + ( i - 1 ) * segments + ( j % segments );
	const last = 1 + ( rings - 1 ) * segments;
	for ( let j = 0; j < segments; j ++ ) {

		triangles.push( 0, ring( 1, j + 1 ), ring( 1, j ) );
		for ( let i = 1; i < rings - 1; i ++ ) triangles.push( ring( i, j ), ring( i, j + 1 ), ring( i + 1, j ), ring( i + 1, j ), ring( i, j + 1 ), ring( i + 1, j + 1 ) );
		triangles.push( last, ring( rings - 1, j ), ring( rings - 1, j + 1 ) );

	}

	return { positions: Float32Array.from( positions ), triangles: Uint32Array.from( triangles ) };

}

test( 'a ray through a triangle crosses it where the plane is; a ray away from it crosses nothing', () => {

	const positions = Float32Array.of( 10, - 5, - 5, 10, 5, - 5, 10, 0, 5 );
	const triangles = Uint32Array.of( 0, 1, 2 );
	// Toward the triangle (through x = 5: t = 2), away from it, and beside it.
	const fan = createRayFan( [ 0, 0, 0 ], [ 5, 0, 0, - 5, 0, 0, 5, 20, 0 ] );
	const target = new Float64Array( 3 );
	const hits = rayFirstHits( fan, positions, triangles, 1, target );
	near( target[ 0 ], 2, 1e-12, 't of the ray through the triangle' );
	assert.equal( target[ 1 ], Infinity, 'a ray pointing away misses' );
	assert.equal( target[ 2 ], Infinity, 'a ray passing beside misses' );
	assert.equal( hits, 1 );

} );

test( 'the first crossing is the nearest one in front of the origin, not one behind it', () => {

	// Two parallel triangles at x = 4 and x = 8, one at x = -3 behind the origin.
	const positions = Float32Array.of( 4, - 9, - 9, 4, 9, - 9, 4, 0, 9, 8, - 9, - 9, 8, 9, - 9, 8, 0, 9, - 3, - 9, - 9, - 3, 9, - 9, - 3, 0, 9 );
	const triangles = Uint32Array.of( 3, 4, 5, 0, 1, 2, 6, 7, 8 );
	const fan = createRayFan( [ 0, 0, 0 ], [ 2, 0, 0, - 1, 0, 0 ] );
	const target = new Float64Array( 2 );
	rayFirstHits( fan, positions, triangles, 3, target );
	near( target[ 0 ], 2, 1e-12, 'the plane x = 4 at t = 2' );
	near( target[ 1 ], 3, 1e-12, 'the plane x = -3 at t = 3 along -x' );

} );

test( 'directions fall on the cube face of their largest component; a point at the origin crosses nothing', () => {

	assert.deepEqual( [ faceOf( 2, 1, 0 ), faceOf( - 2, 1, 0 ), faceOf( 0, 3, 1 ), faceOf( 0, - 3, 1 ), faceOf( 0, 1, 3 ), faceOf( 0, 1, - 3 ) ], [ 0, 1, 2, 3, 4, 5 ] );
	assert.equal( faceOf( 1, 1, 0 ), 0, 'a tie goes to the first axis' );
	assert.equal( faceOf( 0, 0, 0 ), - 1 );
	const atOrigin = createRayFan( [ 1, 2, 3 ], [ 1, 2, 3 ] );
	const target = new Float64Array( 1 );
	assert.equal( rayFirstHits( atOrigin, Float32Array.of( 0, 0, 0, 9, 0, 0, 0, 9, 0 ), Uint32Array.of( 0, 1, 2 ), 1, target ), 0, 'a point at the origin has no ray' );
	assert.equal( target[ 0 ], Infinity );
	assert.throws( () => createRayFan( [ 0, 0 ], [ 1, 2, 3 ] ), /three finite coordinates/ );

} );

test( 'seeded random meshes and rays: the same first crossings as a brute-force loop over every triangle', () => {

	const seed = 1998;
	console.log( `rayFirstHit: seed ${ seed }` );
	const random = seededRandom( seed );
	let hitsSeen = 0, missesSeen = 0;
	for ( let trial = 0; trial < 12; trial ++ ) {

		const origin = [ 6 * random() - 3, 6 * random() - 3, trial % 3 === 0 ? 0 : 4 * random() - 2 ];
		// A closed wobbly sphere round a centre near the origin, holding it but every fourth time.
		const away = trial % 4 === 1 ? 60 : 0;
		const mesh = sphere( [ origin[ 0 ] + 4 * random() - 2 + away, origin[ 1 ] + 4 * random() - 2, 0 ], 15 + 20 * random(), 0.15, random );
		// Plus a soup of large triangles that straddle the cube's faces.
		const soup = 20;
		const base = mesh.positions.length / 3;
		const positions = new Float32Array( mesh.positions.length + 9 * soup );
		positions.set( mesh.positions );
		for ( let k = mesh.positions.length; k < positions.length; k ++ ) positions[ k ] = 80 * random() - 40;
		const triangles = new Uint32Array( mesh.triangles.length + 3 * soup );
		triangles.set( mesh.triangles );
		for ( let k = 0; k < 3 * soup; k ++ ) triangles[ mesh.triangles.length + k ] = base + k;

		// Rays: random points, points in the plane z = 0 through the origin's height (when the
		// origin is on it), points on the pyramids' edges (|x| = |y|) and through mesh vertices.
		const count = 300;
		const points = new Float64Array( 3 * count );
		for ( let k = 0; k < count; k ++ ) {

			const kind = k % 4;
			const d = [ 60 * random() - 30, 60 * random() - 30, 60 * random() - 30 ];
			if ( kind === 1 ) d[ 2 ] = - origin[ 2 ];
			if ( kind === 2 ) d[ 1 ] = ( random() < 0.5 ? - 1 : 1 ) * d[ 0 ];
			if ( kind === 3 ) {

				const v = Math.floor( random() * base );
				for ( let i = 0; i < 3; i ++ ) d[ i ] = positions[ 3 * v + i ] - origin[ i ];

			}

			for ( let i = 0; i < 3; i ++ ) points[ 3 * k + i ] = origin[ i ] + d[ i ];

		}

		const fan = createRayFan( origin, points, { cells: trial % 2 ? FAN_CELLS : 5 } );
		const { hits } = assertSameHits( fan, positions, triangles, `seed ${ seed }, trial ${ trial }` );
		hitsSeen += hits;
		missesSeen += count - hits;

	}

	assert.ok( hitsSeen > 1000 && missesSeen > 0, `the cases both hit (${ hitsSeen }) and miss (${ missesSeen })` );

} );

test( 'rays from the hub through points round the fitted tongue all cross it, first where the brute force finds', () => {

	const rig = new TongueRig( RIG );
	const surface = rig.createSurface();
	const values = Float32Array.from( RIG.parameters, ( p ) => p.neutral );
	rig.evaluate( values, surface );
	const hub = [ rig.hub[ 0 ], rig.hub[ 1 ], 0 ];
	// Mid-sagittal points (z = 0, as an observed outline) and points off it, 2 mm outside or inside vertices.
	const random = seededRandom( 11 );
	const count = 400;
	const points = new Float64Array( 3 * count );
	for ( let k = 0; k < count; k ++ ) {

		let v = Math.floor( random() * rig.vertexCount );
		// Not a vertex straight above or below the hub, whose mid-sagittal point would be the hub.
		while ( Math.hypot( surface.positions[ 3 * v ] - hub[ 0 ], surface.positions[ 3 * v + 1 ] - hub[ 1 ] ) < 3 ) v = Math.floor( random() * rig.vertexCount );
		const scale = 1 + ( random() - 0.5 ) * 0.2;
		for ( let i = 0; i < 3; i ++ ) points[ 3 * k + i ] = hub[ i ] + scale * ( surface.positions[ 3 * v + i ] - hub[ i ] );
		if ( k % 2 === 0 ) points[ 3 * k + 2 ] = 0;

	}

	const fan = createRayFan( hub, points );
	const { target, hits } = assertSameHits( fan, surface.positions, rig.index, 'fitted tongue' );
	assert.equal( hits, count, 'the hub is inside the tongue: every ray leaves it' );
	// Points off the plane are a vertex scaled by 0.9 to 1.1 about the hub: t = 1 / scale there.
	for ( let k = 1; k < count; k += 2 ) assert.ok( target[ k ] > 0.85 && target[ k ] < 1.15, `ray ${ k }: t ${ target[ k ] } is not near the scaled vertex` );

} );

test( 'a call allocates nothing: thousands of calls trigger no garbage collection', async () => {

	const random = seededRandom( 5 );
	const mesh = sphere( [ 0, 0, 0 ], 20, 0.1, random, 8, 16 );
	const points = Float64Array.from( { length: 3 * 200 }, () => 50 * random() - 25 );
	const fan = createRayFan( [ 1, 1, 0 ], points );
	const target = new Float64Array( fan.count );
	const count = mesh.triangles.length / 3;
	const call = ( i ) => {

		mesh.positions[ 0 ] = 20 + ( i % 5 ) * 0.1; // the mesh moves between calls, as the tongue does
		rayFirstHits( fan, mesh.positions, mesh.triangles, count, target );

	};

	for ( let i = 0; i < 1000; i ++ ) call( i ); // let the JIT settle
	const calls = 3000;
	const quiet = await fewestGarbageCollections( () => {

		for ( let i = 0; i < calls; i ++ ) call( i );

	} );
	// The control allocates 32 KiB a call besides (96 MiB in all), so that it collects whatever
	// size the young generation has grown to; 1.6 KiB a call (5 MiB) once fitted in it.
	const kept = [];
	const noisy = await garbageCollections( () => {

		for ( let i = 0; i < calls; i ++ ) {

			call( i );
			fan.scratch = new Float64Array( target );
			kept[ i % 4 ] = new Float64Array( 4096 );

		}

	} );
	assert.equal( quiet, 0, `${ quiet } collections during ${ calls } calls` );
	assert.ok( noisy > 0, 'allocating per call should trigger collections' );

} );
