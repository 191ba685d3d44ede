// Tongue collision with the velum and the pharyngeal wall in JS: against the shared vectors
// answered by the Python twin (tests/vectors/tract-collision.json), against a brute-force search
// over every triangle at openings between the measured poses, and without allocating.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { FLAG_CORRECTED, FLAG_SCREENED, FLAG_TESTED, VELUM_PARAMETER } from '../../web/src/core/constants.js';
import { STAT_CORRECTED, STAT_TESTED } from '../../web/src/core/collision.js';
import { createVelumRig, poseVelum, velumSegment } from '../../web/src/core/velum.js';
import {
	correctTract, createTractCollider, setTractPose, tractOrigin,
} from '../../web/src/core/tractCollision.js';
import { fewestGarbageCollections } from './support/garbage.js';
import { decodeF32, nearArray, readVectors, tolerance } from './support/vectors.js';
import { random } from '../../bench/support/stats.mjs';

const VECTORS = readVectors( 'tract-collision.json' );
const RIG = createVelumRig( readVectors( 'velum.json' ).fixtures.rig );
const POSITION_MM = tolerance( VECTORS, 'position_mm' );
const VELUM_TRIANGLES = Uint32Array.from( VECTORS.fixtures.velum_faces );
const PHARYNX = Float32Array.from( decodeF32( VECTORS.fixtures.pharynx_vertices_f32 ) );
const PHARYNX_TRIANGLES = Uint32Array.from( VECTORS.fixtures.pharynx_faces );

function makeCollider() {

	const collider = createTractCollider( tractOrigin( RIG.poses ), [
		{ name: 'velum', poses: RIG.poses, triangles: VELUM_TRIANGLES },
		{ name: 'pharynx', poses: [ PHARYNX ], triangles: PHARYNX_TRIANGLES },
	] );
	const velum = new Float32Array( 3 * RIG.vertexCount );
	return {
		collider,
		velum,
		pose( opening ) {

			const first = velumSegment( RIG, opening );
			poseVelum( RIG, opening, velum );
			setTractPose( collider, 0, velum, first, RIG.share[ 0 ] );

		},
	};

}

test( 'the origin and the screen are the Python twin\'s', () => {

	const { collider } = makeCollider();
	nearArray( collider.origin, VECTORS.constants.origin, 1e-9, 'origin' );
	assert.ok( Math.abs( collider.screenX - VECTORS.constants.screen_x ) <= 1e-9 );
	assert.ok( collider.origin[ 0 ] > collider.screenX, 'T lies in front of every tract mesh' );

} );

test( 'flags and corrected positions agree with the Python reference in every case', () => {

	const tract = makeCollider();
	let corrected = 0;
	for ( const { description, input, expected } of VECTORS.cases ) {

		const opening = input[ VELUM_PARAMETER ];
		if ( expected.error ) {

			assert.throws( () => tract.pose( opening ), new RegExp( expected.error.replace( /[[\]]/g, '\\$&' ) ), description );
			continue;

		}

		tract.pose( opening );
		const positions = Float32Array.from( decodeF32( input.vertices_f32 ) );
		const before = positions.slice();
		const count = positions.length / 3;
		const flags = new Uint8Array( count );
		const stats = new Int32Array( 3 );
		const moved = correctTract( positions, count, tract.collider, flags, stats );
		assert.deepEqual( Array.from( flags ), expected.flags, description );
		assert.equal( moved, expected.corrected.length, description );
		assert.equal( stats[ STAT_TESTED ], expected.counts.tested, description );
		const got = new Float64Array( 3 * moved );
		expected.corrected.forEach( ( v, k ) => {

			for ( let c = 0; c < 3; c ++ ) got[ 3 * k + c ] = positions[ 3 * v + c ];

		} );
		nearArray( got, expected.corrected_positions, POSITION_MM, description );
		for ( let v = 0; v < count; v ++ ) {

			if ( flags[ v ] === FLAG_CORRECTED ) continue;
			for ( let c = 0; c < 3; c ++ ) assert.equal( positions[ 3 * v + c ], before[ 3 * v + c ], `${ description }: vertex ${ v } was outside and must not move` );

		}

		corrected += moved;

	}

	assert.ok( corrected > 100, `the cases correct ${ corrected } vertices in all` );

} );

// The first crossing of T -> P over every triangle of both meshes: the definition of inside.
function bruteFirstHit( origin, px, py, pz, meshes ) {

	let best = Infinity;
	for ( const { positions, triangles } of meshes ) {

		for ( let f = 0; f < triangles.length; f += 3 ) {

			const a = 3 * triangles[ f ], b = 3 * triangles[ f + 1 ], c = 3 * triangles[ f + 2 ];
			const ax = positions[ a ] - origin[ 0 ], ay = positions[ a + 1 ] - origin[ 1 ], az = positions[ a + 2 ] - origin[ 2 ];
			const e1 = [ positions[ b ] - origin[ 0 ] - ax, positions[ b + 1 ] - origin[ 1 ] - ay, positions[ b + 2 ] - origin[ 2 ] - az ];
			const e2 = [ positions[ c ] - origin[ 0 ] - ax, positions[ c + 1 ] - origin[ 1 ] - ay, positions[ c + 2 ] - origin[ 2 ] - az ];
			const h = [ py * e2[ 2 ] - pz * e2[ 1 ], pz * e2[ 0 ] - px * e2[ 2 ], px * e2[ 1 ] - py * e2[ 0 ] ];
			const det = e1[ 0 ] * h[ 0 ] + e1[ 1 ] * h[ 1 ] + e1[ 2 ] * h[ 2 ];
			if ( det === 0 ) continue;
			const s = [ - ax, - ay, - az ];
			const u = ( s[ 0 ] * h[ 0 ] + s[ 1 ] * h[ 1 ] + s[ 2 ] * h[ 2 ] ) / det;
			const q = [ s[ 1 ] * e1[ 2 ] - s[ 2 ] * e1[ 1 ], s[ 2 ] * e1[ 0 ] - s[ 0 ] * e1[ 2 ], s[ 0 ] * e1[ 1 ] - s[ 1 ] * e1[ 0 ] ];
			const v = ( px * q[ 0 ] + py * q[ 1 ] + pz * q[ 2 ] ) / det;
			const t = ( e2[ 0 ] * q[ 0 ] + e2[ 1 ] * q[ 1 ] + e2[ 2 ] * q[ 2 ] ) / det;
			if ( u >= - 1e-9 && v >= - 1e-9 && u + v <= 1 + 1e-9 && t > 0 && t < best ) best = t;

		}

	}

	return best;

}

test( 'between the measured poses the blended boxes miss no crossing: the brute-force answer', () => {

	const tract = makeCollider();
	const next = random( 7 );
	const origin = tract.collider.origin;
	const count = 400;
	const points = new Float32Array( 3 * count );
	let inside = 0;
	for ( const opening of [ 0.05, 0.3, 0.61, 0.83, 0.97 ] ) {

		tract.pose( opening );
		const meshes = [ { positions: tract.velum, triangles: VELUM_TRIANGLES }, { positions: PHARYNX, triangles: PHARYNX_TRIANGLES } ];
		// Points around the velum and the wall: vertices of both, moved up to 4 mm either way.
		for ( let k = 0; k < count; k ++ ) {

			const source = k % 2 ? PHARYNX : tract.velum;
			const v = 3 * Math.floor( next() * source.length / 3 );
			for ( let c = 0; c < 3; c ++ ) points[ 3 * k + c ] = source[ v + c ] + ( next() - 0.5 ) * 8;

		}

		const before = points.slice();
		const flags = new Uint8Array( count );
		correctTract( points, count, tract.collider, flags, null );
		for ( let k = 0; k < count; k ++ ) {

			const px = before[ 3 * k ] - origin[ 0 ], py = before[ 3 * k + 1 ] - origin[ 1 ], pz = before[ 3 * k + 2 ] - origin[ 2 ];
			const t = bruteFirstHit( origin, px, py, pz, meshes );
			const wanted = t < 1;
			assert.equal( flags[ k ] === FLAG_CORRECTED, wanted, `opening ${ opening }, point ${ k }: t = ${ t }` );
			if ( wanted ) {

				inside ++;
				nearArray( points.subarray( 3 * k, 3 * k + 3 ), [ origin[ 0 ] + px * t, origin[ 1 ] + py * t, origin[ 2 ] + pz * t ], POSITION_MM, `point ${ k }` );

			} else assert.ok( flags[ k ] === FLAG_SCREENED || flags[ k ] === FLAG_TESTED );

		}

	}

	assert.ok( inside > 200, `${ inside } of the points lie beyond a tract surface` );

} );

test( 'an opening out of range is refused, naming the parameter', () => {

	const tract = makeCollider();
	assert.throws( () => tract.pose( 1.2 ), /velum_opening = 1.2 is outside its range \[0, 1\]/ );
	assert.throws( () => setTractPose( tract.collider, 0, tract.velum, 2, 0.5 ), RangeError );
	assert.throws( () => setTractPose( tract.collider, 0, new Float32Array( 9 ), 0, 0.5 ), /velum: 3 vertices, expected 3787/ );

} );

test( 'correcting allocates nothing', async () => {

	const tract = makeCollider();
	const input = Float32Array.from( decodeF32( VECTORS.cases[ 8 ].input.vertices_f32 ) );
	const positions = new Float32Array( input.length );
	const count = input.length / 3;
	const flags = new Uint8Array( count );
	const stats = new Int32Array( 3 );
	let total = 0;
	const quiet = await fewestGarbageCollections( () => {

		for ( let k = 0; k < 2000; k ++ ) {

			tract.pose( ( k % 101 ) / 100 );
			positions.set( input );
			total += correctTract( positions, count, tract.collider, flags, stats ) + stats[ STAT_CORRECTED ];

		}

	} );
	assert.ok( total > 0 );
	assert.equal( quiet, 0, `${ quiet } collections while correcting` );

} );
