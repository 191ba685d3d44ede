// The real-time velum against the shared vectors written by the Python reference
// (tests/vectors/velum.json): posed probe vertices and nasal port areas within the file's stated
// tolerances, refusals of openings out of range, and posing that allocates nothing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fewestGarbageCollections } from './support/garbage.js';

import { createVelumRig, nasalPortArea, poseVelum } from '../../web/src/core/velum.js';
import { VELUM_PARAMETER } from '../../web/src/core/constants.js';

import { near, nearArray, readVectors, tolerance } from './support/vectors.js';

const VECTORS = readVectors( 'velum.json' );
const { fixtures: FIXTURES } = VECTORS;
const VERTEX_MM = tolerance( VECTORS, 'vertex_mm' );
const AREA_MM2 = tolerance( VECTORS, 'area_mm2' );

test( 'posed probe vertices and port areas agree with the Python reference in every case', () => {

	const rig = createVelumRig( FIXTURES.rig );
	const out = new Float32Array( 3 * rig.vertexCount );
	const probes = new Float64Array( 3 * FIXTURES.probe_vertices.length );
	for ( const { description, input, expected } of VECTORS.cases ) {

		const opening = input[ VELUM_PARAMETER ];
		if ( expected.error ) {

			assert.throws( () => poseVelum( rig, opening, out ), new RegExp( expected.error.replace( /[[\]]/g, '\\$&' ) ), description );
			assert.throws( () => nasalPortArea( rig, opening ), RangeError, description );
			continue;

		}

		assert.equal( poseVelum( rig, opening, out ), out );
		FIXTURES.probe_vertices.forEach( ( v, k ) => {

			for ( let c = 0; c < 3; c ++ ) probes[ 3 * k + c ] = out[ 3 * v + c ];

		} );
		nearArray( probes, expected.probe_positions, VERTEX_MM, description );
		near( nasalPortArea( rig, opening ), expected.port_area_mm2, AREA_MM2, description );

	}

} );

test( 'the port is exactly closed when raised and never narrows as the velum lowers', () => {

	const rig = createVelumRig( FIXTURES.rig );
	assert.equal( nasalPortArea( rig, 0 ), 0 );
	let previous = 0;
	for ( let k = 1; k <= 1000; k ++ ) {

		const area = nasalPortArea( rig, k / 1000 );
		assert.ok( area >= previous - 1e-9, `area shrinks at opening ${ k / 1000 }: ${ previous } -> ${ area }` );
		previous = area;

	}

	assert.ok( nasalPortArea( rig, 1 ) > nasalPortArea( rig, rig.restShare ) + 1 );

} );

test( 'a rig of another format version is refused', () => {

	assert.throws( () => createVelumRig( { ...FIXTURES.rig, format_version: 99 } ), /format_version/ );

} );

test( 'posing and measuring the port allocate nothing', async () => {

	const rig = createVelumRig( FIXTURES.rig );
	const out = new Float32Array( 3 * rig.vertexCount );
	let sum = 0;
	const quiet = await fewestGarbageCollections( () => {

		for ( let k = 0; k < 3000; k ++ ) {

			poseVelum( rig, ( k % 101 ) / 100, out );
			sum += nasalPortArea( rig, ( k % 101 ) / 100 );

		}

	} );
	assert.ok( sum > 0 );
	assert.equal( quiet, 0, `${ quiet } collections while posing` );

} );
