// Synthetic EPG contact in JS against the shared vectors (answered by the Python twin), against
// its own brute force, and its guarantees: exact probe reach, no allocation per frame.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fewestGarbageCollections, garbageCollections } from './support/garbage.js';
import { createHash } from 'node:crypto';
import { decodeF32, nearRelative, readVectors } from './support/vectors.js';

import {
	COLLISION_TOL, EPG_CONTACT_BEHIND_MM, EPG_CONTACT_TOLERANCE_MM, EPG_LAYOUT_FORMAT_VERSION,
} from '../../web/src/core/constants.js';
import { contactRows, createContactModel, electrodeContacts, electrodeContactsBruteForce } from '../../web/src/core/epgContacts.js';
import { correctVertices } from '../../web/src/core/collision.js';
import { decodeCollisionTables } from '../../web/src/core/tables.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { epgIndices, INDEX_STRIDE, SLOT_CONTACTS, SLOT_PERCENT } from '../../web/src/core/epgIndices.js';

const VECTORS = readVectors( 'epg-contacts.json' );
const { fixtures: FIXTURES } = VECTORS;
const TABLES_FILE = readVectors( FIXTURES.tables.file );
const TABLES = decodeCollisionTables( TABLES_FILE );
const RIG = new TongueRig( FIXTURES.rig );
const GRIDS = [ 'reading62', 'dense96' ];
const MODELS = Object.fromEntries( GRIDS.map( ( name ) => [ name, createContactModel( FIXTURES.layout.grids[ name ], RIG.index, RIG.vertexCount ) ] ) );
// Contacts are compared exactly: the generator keeps every pose and tongue clear of the probes'
// ends and sides by constants.margin_mm, far more than float32 rounding moves the tongue.
const POSES = VECTORS.cases.filter( ( c ) => 'params' in c.input );
const KERNEL_CASES = VECTORS.cases.filter( ( c ) => 'vertices' in c.input );

/** The corrected tongue for a parameter object, as the browser computes it. */
function correctedTongue( params, surface = RIG.createSurface() ) {

	RIG.evaluate( RIG.valuesFrom( params ), surface );
	correctVertices( surface.positions, RIG.vertexCount, TABLES, null, null );
	return surface.positions;

}

function rowsOf( model, positions ) {

	const frame = new Uint8Array( model.cells );
	const found = electrodeContacts( model, positions, frame );
	return { rows: contactRows( model, frame ), found, frame };

}

test( 'the vectors were computed on these tables, these constants and 100 or more poses', () => {

	assert.equal( createHash( 'sha256' ).update( TABLES_FILE ).digest( 'hex' ), FIXTURES.tables.sha256 );
	assert.equal( VECTORS.constants.tolerance_mm, EPG_CONTACT_TOLERANCE_MM );
	assert.equal( VECTORS.constants.behind_mm, EPG_CONTACT_BEHIND_MM );
	assert.equal( VECTORS.constants.barycentric, COLLISION_TOL.barycentric );
	assert.equal( FIXTURES.layout.format_version, EPG_LAYOUT_FORMAT_VERSION );
	assert.ok( POSES.length >= 100, `${POSES.length} poses` );
	assert.ok( POSES.some( ( c ) => c.input.params.jaw_opening > 5 ), 'the jaw is exercised over the upper half of its 0-10 degree range' );
	const descriptions = VECTORS.cases.map( ( c ) => c.description );
	assert.equal( new Set( descriptions ).size, descriptions.length );

} );

test( 'every seeded pose gives the Python contacts exactly, on both grids', () => {

	const surface = RIG.createSurface();
	let contacted = 0;
	for ( const c of POSES ) {

		const positions = correctedTongue( c.input.params, surface );
		for ( const name of GRIDS ) {

			const { rows, found } = rowsOf( MODELS[ name ], positions );
			assert.deepEqual( rows, c.expected[ name ].rows, `${c.description}, ${name}` );
			assert.equal( found, c.expected[ name ].contacted, `${c.description}, ${name}` );
			if ( name === 'reading62' ) contacted += found;

		}

	}

	assert.ok( contacted > 20 * POSES.length / 2, `only ${contacted} contacts in all: the vectors test too little` );

} );

test( 'corrected tongues given as float32 vertices give the Python contacts bit for bit', () => {

	for ( const c of KERNEL_CASES.filter( ( k ) => k.input.triangles === 'rig' ) ) {

		const positions = decodeF32( c.input.vertices );
		for ( const name of GRIDS ) {

			assert.deepEqual( rowsOf( MODELS[ name ], positions ).rows, c.expected[ name ].rows, `${c.description}, ${name}` );

		}

	}

} );

test( 'small hand-made meshes about one probe give the expected contacts', () => {

	const grid = FIXTURES.layout.grids.reading62;
	for ( const c of KERNEL_CASES.filter( ( k ) => Array.isArray( k.input.triangles ) ) ) {

		const positions = decodeF32( c.input.vertices );
		const index = Uint32Array.from( c.input.triangles );
		const model = createContactModel( grid, index, positions.length / 3 );
		const frame = new Uint8Array( 64 );
		electrodeContacts( model, positions, frame );
		const contacted = model.ids.filter( ( id, k ) => frame[ model.cellOf[ k ] ] === 1 );
		assert.deepEqual( contacted, c.expected.contacted, c.description );
		assert.deepEqual( contactRows( model, frame ), c.expected.rows, c.description );

	}

} );

test( 'the broad phase gives the brute force answer on 80 seeded random tongues (seed 99)', () => {

	let seed = 99;
	const random = () => ( seed = ( seed * 16807 ) % 2147483647 ) / 2147483647;
	const values = new Float64Array( RIG.parameterCount );
	const surface = RIG.createSurface();
	const fast = new Uint8Array( 96 ), slow = new Uint8Array( 96 );
	let checked = 0;
	for ( let n = 0; n < 80; n ++ ) {

		// Every other tongue is raised (upper half of the heights, jaw nearly closed), so that
		// most of them reach the palate.
		for ( let k = 0; k < RIG.parameterCount; k ++ ) {

			const p = RIG.parameters[ k ];
			let lo = p.min, hi = p.max;
			if ( n % 2 && p.name === 'jaw_opening' ) hi = lo + 0.2 * ( hi - lo );
			else if ( n % 2 && /height|advancement/.test( p.name ) ) lo = p.neutral;
			values[ k ] = lo + ( hi - lo ) * random();

		}

		RIG.evaluate( values, surface );
		correctVertices( surface.positions, RIG.vertexCount, TABLES, null, null );
		for ( const name of GRIDS ) {

			const model = MODELS[ name ];
			const a = electrodeContacts( model, surface.positions, fast );
			const b = electrodeContactsBruteForce( model, surface.positions, slow );
			assert.equal( a, b, `seed 99, tongue ${n}, ${name}` );
			assert.deepEqual( fast.subarray( 0, model.cells ), slow.subarray( 0, model.cells ), `seed 99, tongue ${n}, ${name}` );
			checked += a;

		}

	}

	assert.ok( checked > 400, `${checked} contacts: too few to test the broad phase` );

} );

test( 'the Reading frame keeps the R1 corners at 0 and fits epgIndices', () => {

	const model = MODELS.reading62;
	assert.equal( model.cells, 64 );
	assert.equal( model.count, 62 );
	assert.ok( ! model.ids.includes( 'R1C1' ) && ! model.ids.includes( 'R1C8' ) );
	const full = KERNEL_CASES.find( ( k ) => k.input.triangles === 'rig' && k.expected.reading62.contacted > 40 );
	const { frame } = rowsOf( model, decodeF32( full.input.vertices ) );
	assert.equal( frame[ 0 ], 0 );
	assert.equal( frame[ 7 ], 0 );
	const indices = epgIndices( frame, 0, new Float64Array( INDEX_STRIDE ) );
	assert.equal( indices[ SLOT_CONTACTS ], full.expected.reading62.contacted );
	// One division of integers: a relative 1e-12 allows only for how the kernel orders it.
	nearRelative( indices[ SLOT_PERCENT ], 100 * full.expected.reading62.contacted / 62, 1e-12, 'percent contact' );

} );

test( 'a frame allocates nothing: thousands of frames trigger no garbage collection', async () => {

	const model = MODELS.reading62;
	const positions = correctedTongue( POSES.find( ( c ) => c.expected.reading62.contacted > 30 ).input.params );
	const frame = new Uint8Array( 64 );
	for ( let i = 0; i < 500; i ++ ) electrodeContacts( model, positions, frame ); // let the JIT settle
	const frames = 6000;
	const quiet = await fewestGarbageCollections( () => {

		for ( let i = 0; i < frames; i ++ ) electrodeContacts( model, positions, frame );

	} );
	// The same loop with a fresh target per frame shows that the probe does see allocation.
	const noisy = await garbageCollections( () => {

		for ( let i = 0; i < frames; i ++ ) electrodeContacts( model, positions, new Uint8Array( 8192 ) );

	} );
	assert.equal( quiet, 0, `${quiet} collections during ${frames} frames` );
	assert.ok( noisy > 0, 'allocating a target per frame should trigger collections' );

} );

test( 'bad layouts and meshes are refused with a message', () => {

	const grid = FIXTURES.layout.grids.reading62;
	assert.throws( () => createContactModel( { ...grid, electrodes: [] }, RIG.index, RIG.vertexCount ), /no electrodes/ );
	const skewed = { ...grid, electrodes: grid.electrodes.map( ( e, k ) => ( k === 3 ? { ...e, normal: [ 0, 2, 0 ] } : e ) ) };
	assert.throws( () => createContactModel( skewed, RIG.index, RIG.vertexCount ), /R1C5.*not a unit vector/ );
	const repeated = { ...grid, electrodes: grid.electrodes.map( ( e, k ) => ( k === 1 ? { ...e, cell: grid.electrodes[ 0 ].cell } : e ) ) };
	assert.throws( () => createContactModel( repeated, RIG.index, RIG.vertexCount ), /repeated cell/ );
	assert.throws( () => createContactModel( grid, Uint32Array.of( 0, 1 ), 3 ), /3 vertex indices/ );
	assert.throws( () => createContactModel( grid, Uint32Array.of( 0, 1, 5 ), 3 ), /index 5 is not a vertex/ );

} );
