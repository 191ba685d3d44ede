// Collision correction in JS against the shared vectors (answered by the Python twin), against a
// brute-force raycast over every triangle of the tables, and the loader's refusals.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createHash } from 'node:crypto';

import * as constants from '../../web/src/core/constants.js';
import {
	FLAG_CORRECTED, FLAG_SCREENED, FLAG_TESTED, COLLISION_TOL,
} from '../../web/src/core/constants.js';
import { correctVertices, STAT_CORRECTED, STAT_SCREENED, STAT_TESTED } from '../../web/src/core/collision.js';
import { CollisionTablesError, crc32, decodeCollisionTables } from '../../web/src/core/tables.js';
import { createApi } from '../../web/src/api.js';
import { loadCollisionTables } from '../../web/src/ui/shared/loaders.js';
import { near, nearRelative, readVectors, tolerance } from './support/vectors.js';

const CASES = readVectors( 'collision-correct.json' );
const CONSTANTS = readVectors( 'collision-constants.json' );
const FILE = readVectors( CASES.fixtures.tables.file );
const TABLES = decodeCollisionTables( FILE );
const CORRECTIONS = CASES.cases.filter( ( c ) => ! ( 'error' in c.expected ) );
const REFUSALS = CASES.cases.filter( ( c ) => 'error' in c.expected );
/** mm: float64 positions against the Python answers, and float32 ones (reasons in the file). */
const REFERENCE_MM = tolerance( CASES, 'reference_mm' );
const VERTEX_MM = tolerance( CASES, 'vertex_mm' );

/** A JS constant against the Python value: numbers within the file's relative tolerance. */
function sameConstant( js, py, path ) {

	if ( typeof py === 'number' ) nearRelative( js, py, tolerance( CONSTANTS, 'value' ), path );
	else if ( py !== null && typeof py === 'object' ) {

		assert.deepEqual( Object.keys( js ).sort(), Object.keys( py ).sort(), `${ path }: keys` );
		for ( const key of Object.keys( py ) ) sameConstant( js[ key ], py[ key ], `${ path }.${ key }` );

	} else assert.equal( js, py, path );

}

function fileCopy() {

	return new Uint8Array( FILE.buffer.slice( FILE.byteOffset, FILE.byteOffset + FILE.byteLength ) );

}

test( 'the vector tables are the file the vectors were computed on', () => {

	assert.equal( createHash( 'sha256' ).update( FILE ).digest( 'hex' ), CASES.fixtures.tables.sha256 );

} );

test( 'collision constants agree with the Python constants', () => {

	for ( const [ name, value ] of Object.entries( CONSTANTS.constants ) ) sameConstant( constants[ name ], value, name );

} );

test( 'crc32 matches zlib on a known string', () => {

	assert.equal( crc32( new TextEncoder().encode( 'The quick brown fox jumps over the lazy dog' ) ), 0x414FA339 );

} );

for ( const vector of CORRECTIONS ) {

	test( `vector: ${ vector.description }`, () => {

		const input = vector.input.vertices, expected = vector.expected;
		const n = input.length;
		const positions = new Float64Array( input.flat() );
		const flags = new Uint8Array( n ).fill( 255 );
		const stats = new Int32Array( 3 );
		const corrected = correctVertices( positions, n, TABLES, flags, stats );
		assert.deepEqual( Array.from( flags ), expected.flags );
		assert.equal( corrected, expected.counts.corrected );
		assert.deepEqual( Array.from( stats ), [ expected.counts.screened, expected.counts.tested, expected.counts.corrected ] );
		for ( let i = 0; i < n; i ++ ) {

			for ( let k = 0; k < 3; k ++ ) {

				const got = positions[ 3 * i + k ], want = expected.vertices[ i ][ k ];
				near( got, want, REFERENCE_MM, `vertex ${ i }[${ k }]` );
				// The input itself, passed through: the same bits, not a computed number.
				if ( expected.flags[ i ] !== FLAG_CORRECTED ) assert.equal( got, input[ i ][ k ], 'an untouched vertex is bit-identical' );

			}

		}

		// Float32 positions, as the browser holds them, agree within the shared tolerance.
		const positions32 = new Float32Array( input.flat() );
		const flags32 = new Uint8Array( n );
		correctVertices( positions32, n, TABLES, flags32, null );
		assert.deepEqual( Array.from( flags32 ), expected.flags );
		for ( let i = 0; i < 3 * n; i ++ ) near( positions32[ i ], expected.vertices[ Math.floor( i / 3 ) ][ i % 3 ], VERTEX_MM, `float32 vertex ${ Math.floor( i / 3 ) }[${ i % 3 }]` );

	} );

}

for ( const refusal of REFUSALS ) {

	test( `refusal: ${ refusal.description }`, () => {

		let bytes = fileCopy();
		if ( refusal.input.patch ) {

			const { offset, bytes: patch } = refusal.input.patch;
			bytes.set( patch, offset < 0 ? bytes.length + offset : offset );

		}

		if ( refusal.input.truncate !== undefined ) bytes = bytes.slice( 0, refusal.input.truncate );
		assert.throws( () => decodeCollisionTables( bytes ), ( error ) => error instanceof CollisionTablesError && error.message.includes( refusal.expected.error ) );

	} );

}

// Brute force: the first hit from O over every triangle of the tables (two-sided Moller-Trumbore).
function exactHit( px, py, pz ) {

	const tri = TABLES.triangles;
	let best = Infinity;
	for ( let o = 0; o < tri.length; o += 9 ) {

		const [ ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z ] = tri.subarray( o, o + 9 );
		const hx = py * e2z - pz * e2y, hy = pz * e2x - px * e2z, hz = px * e2y - py * e2x;
		const det = e1x * hx + e1y * hy + e1z * hz;
		if ( det === 0 ) continue;
		const u = ( - ax * hx - ay * hy - az * hz ) / det;
		const qx = - ay * e1z + az * e1y, qy = - az * e1x + ax * e1z, qz = - ax * e1y + ay * e1x;
		const v = ( px * qx + py * qy + pz * qz ) / det;
		const t = ( e2x * qx + e2y * qy + e2z * qz ) / det;
		if ( u >= - 1e-9 && v >= - 1e-9 && u + v <= 1 + 1e-9 && t > 0 && t < best ) best = t;

	}

	return best;

}

test( 'seeded random points: moved exactly when a brute-force ray from O crosses the maxilla, and onto it', () => {

	const seed = 1998;
	let state = seed;
	const random = () => ( ( state = ( state * 1103515245 + 12345 ) % 2147483648 ) / 2147483648 );
	const min = TABLES.header.voxels.bounds.min, max = TABLES.header.voxels.bounds.max;
	const [ ox, oy, oz ] = TABLES.origin;
	const n = 3000;
	const positions = new Float64Array( 3 * n );
	for ( let i = 0; i < 3 * n; i ++ ) {

		const k = i % 3, span = max[ k ] - min[ k ];
		positions[ i ] = min[ k ] - 0.2 * span + 1.4 * span * random();

	}

	const before = positions.slice();
	const flags = new Uint8Array( n );
	correctVertices( positions, n, TABLES, flags, null );
	let inside = 0;
	for ( let i = 0; i < n; i ++ ) {

		const px = before[ 3 * i ] - ox, py = before[ 3 * i + 1 ] - oy, pz = before[ 3 * i + 2 ] - oz;
		const t = exactHit( px, py, pz );
		const r = Math.hypot( px, py, pz );
		const moved = flags[ i ] === FLAG_CORRECTED;
		if ( Math.abs( t - 1 ) * r < COLLISION_TOL.surface ) continue; // on the surface: either answer
		assert.equal( moved, t < 1, `seed ${ seed }, point ${ i }: moved ${ moved }, exact t ${ t }` );
		if ( moved ) {

			inside ++;
			const q = [ positions[ 3 * i ] - ox, positions[ 3 * i + 1 ] - oy, positions[ 3 * i + 2 ] - oz ];
			const gap = Math.abs( Math.hypot( ...q ) - t * r );
			assert.ok( gap < COLLISION_TOL.length, `seed ${ seed }, point ${ i } lands on the first hit (off by ${ gap } mm)` );

		} else {

			assert.ok( flags[ i ] === FLAG_SCREENED || flags[ i ] === FLAG_TESTED );
			for ( let k = 0; k < 3; k ++ ) assert.equal( positions[ 3 * i + k ], before[ 3 * i + k ] );

		}

	}

	assert.ok( inside > 100, `seed ${ seed }: the sample reaches inside the maxilla (${ inside } points)` );

} );

test( 'stats and flags may be null, and the stats slots are in a fixed order', () => {

	const positions = new Float64Array( CORRECTIONS.at( - 1 ).input.vertices.flat() );
	const n = positions.length / 3;
	const stats = new Int32Array( 3 );
	const corrected = correctVertices( positions.slice(), n, TABLES, null, stats );
	assert.equal( stats[ STAT_SCREENED ], n );
	assert.ok( stats[ STAT_TESTED ] >= stats[ STAT_CORRECTED ] );
	assert.equal( stats[ STAT_CORRECTED ], corrected );
	assert.equal( correctVertices( positions.slice(), n, TABLES, null, null ), corrected );

} );

test( 'a buffer at an unaligned offset is copied, not misread', () => {

	const shifted = new Uint8Array( FILE.length + 3 );
	shifted.set( FILE, 3 );
	const tables = decodeCollisionTables( shifted.subarray( 3 ) );
	assert.deepEqual( Array.from( tables.voxels ), Array.from( TABLES.voxels ) );

} );

test( 'fetching tables follows the header URL and refuses another format version before downloading', async () => {

	const requested = [];
	const fakeFetch = ( version ) => async ( url ) => {

		requested.push( url );
		if ( url.endsWith( '/collision/tables' ) ) return { ok: true, json: async () => ( { format_version: version, url: '/assets/build/t.bin' } ) };
		return { ok: true, arrayBuffer: async () => fileCopy().buffer };

	};

	const load = ( version ) => loadCollisionTables( { api: createApi( { fetchImpl: fakeFetch( version ) } ) } );
	const tables = await load( constants.COLLISION_TABLES_FORMAT_VERSION );
	assert.deepEqual( requested, [ '/api/v1/collision/tables', '/assets/build/t.bin' ] );
	assert.equal( tables.nlon, TABLES.nlon );
	requested.length = 0;
	await assert.rejects( load( 99 ), /format version 99/ );
	assert.deepEqual( requested, [ '/api/v1/collision/tables' ] );

} );
