// The real-time face rig against the shared vectors written by the Python reference
// (tests/vectors/face-rig.json), plus its own guarantees: closure closes, the jaw opens the mouth,
// still vertices stay put, bad input is refused, and posing allocates nothing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { garbageCollections } from './support/garbage.js';

import {
	createFaceRig, GAP_LIPS, GAP_NATURAL, lipGap, lipValues, poseFace, restFaceRig,
} from '../../web/src/core/faceRig.js';
import { teethBound } from '../../web/src/core/faceTeeth.js';
import { jawPose, jawScrew, POSE_LENGTH, SCREW_SIZE } from '../../web/src/core/jaw.js';
import { FACE_RIG_LIP_PARAMETERS, FACE_RIG_MESHES, FACE_VERTEX_TOLERANCE_MM } from '../../web/src/core/constants.js';

import { near, nearArray, readVectors, tolerance } from './support/vectors.js';

const VECTORS = readVectors( 'face-rig.json' );
const { fixtures: FIXTURES } = VECTORS;
const REST = Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, Float32Array.from( FIXTURES.rest[ name ] ) ] ) );

function setup() {

	const rig = createFaceRig( FIXTURES.rig, REST );
	const out = Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, new Float32Array( REST[ name ].length ) ] ) );
	restFaceRig( rig, out );
	return { rig, out, values: new Float64Array( FACE_RIG_LIP_PARAMETERS.length ), pose: new Float64Array( POSE_LENGTH ) };

}

function poseCase( context, params ) {

	const { rig, out, values, pose } = context;
	const { jaw_opening: opening = 0, ...lips } = params;
	lipValues( rig, lips, values );
	jawPose( opening, FIXTURES.jaw, pose );
	return poseFace( rig, values, pose, out ).gaps[ GAP_LIPS ];

}

test( 'the vectors hold 100 or more seeded random sets, the jaw among them, with unique descriptions', () => {

	const random = VECTORS.cases.filter( ( c ) => c.description.startsWith( 'random set' ) );
	assert.ok( random.length >= 100, `${ random.length } random sets` );
	assert.ok( random.every( ( c ) => c.description.includes( `seed ${ VECTORS.constants.seed }` ) ) );
	const openings = random.map( ( c ) => c.input.params.jaw_opening );
	assert.ok( Math.max( ...openings ) - Math.min( ...openings ) > 8, 'the jaw opening spans its range (0 to 10 degrees)' );
	assert.ok( random.some( ( c ) => c.input.params.lip_opening === 0 ), 'some sets close the lips' );
	assert.equal( new Set( VECTORS.cases.map( ( c ) => c.description ) ).size, VECTORS.cases.length );
	assert.equal( tolerance( VECTORS, 'vertex_mm' ), FACE_VERTEX_TOLERANCE_MM );

} );

test( 'every vector case gives the Python gaps, closure and probe positions', () => {

	const context = setup();
	const gapMm = tolerance( VECTORS, 'gap_mm' ), vertexMm = tolerance( VECTORS, 'vertex_mm' );
	let worst = 0;
	for ( const vector of VECTORS.cases ) {

		const gap = poseCase( context, vector.input.params );
		const expected = vector.expected;
		const message = vector.description;
		near( gap, expected.lip_gap_mm, gapMm, `${ message }: lip gap` );
		near( context.rig.gaps[ GAP_NATURAL ], expected.natural_gap_mm, gapMm, `${ message }: natural gap` );
		expected.closure_mm.forEach( ( c, i ) => near( context.rig.closure[ i ], c, gapMm, `${ message }: closure ${ i }` ) );
		// A count decided by floats: the generator keeps every case clear of the teeth's thresholds.
		assert.equal( context.rig.counts[ 0 ], expected.teeth_clamped, `${ message }: points moved by the teeth` );
		for ( const name of FACE_RIG_MESHES ) {

			FIXTURES.probe_vertices[ name ].forEach( ( v, k ) => {

				for ( let i = 0; i < 3; i ++ ) {

					const error = Math.abs( context.out[ name ][ 3 * v + i ] - expected.probe_positions[ name ][ k ][ i ] );
					worst = Math.max( worst, error );
					assert.ok( error <= vertexMm, `${ message }: ${ name } vertex ${ v } off by ${ error } mm` );

				}

			} );

		}

	}

	assert.ok( worst < 1e-4, `float32 rounding only, got ${ worst } mm` );

} );

test( 'closing the lips leaves no gap at any jaw opening; open lips part wider as the jaw opens', () => {

	const context = setup();
	let previous = - 1;
	for ( const opening of [ 0, 5, 10, 15, 20, 25 ] ) {

		assert.ok( poseCase( context, { jaw_opening: opening, lip_opening: 0 } ) <= 0.5, `closed at ${ opening } deg` );
		const open = poseCase( context, { jaw_opening: opening } );
		assert.ok( open > previous, `gap ${ open } at ${ opening } deg after ${ previous }` );
		previous = open;

	}

	assert.ok( previous > 20, `the mouth opens wide at 25 deg: ${ previous } mm` );

} );

test( 'a pose of the jaw alone moves the lower lip with the mandible and leaves still vertices at rest', () => {

	const context = setup();
	poseCase( context, { jaw_opening: 20 } );
	const { rig, out } = context;
	for ( const name of FACE_RIG_MESHES ) {

		const mesh = rig.meshes[ name ];
		const moving = new Set( mesh.moving );
		for ( let v = 0; v < mesh.count; v ++ ) {

			if ( moving.has( v ) ) continue;
			for ( let i = 0; i < 3; i ++ ) assert.equal( out[ name ][ 3 * v + i ], REST[ name ][ 3 * v + i ], `${ name } vertex ${ v }` );

		}

	}

	assert.ok( rig.meshes.head_shell.moving.length < rig.meshes.head_shell.count / 2, 'most of the shell never moves' );
	// The lower lip's reference vertex (its top at the midline) goes down with the chin.
	const low = rig.meshes.lower_lip.reference;
	assert.ok( out.lower_lip[ 3 * low + 1 ] < REST.lower_lip[ 3 * low + 1 ] - 10 );

} );

test( 'the jaw screw of a pure rotation has no slide and reproduces the pose', () => {

	const pose = jawPose( 0, { pivot: [ 0, 0 ], translation_per_degree: [ 0, 0 ] }, new Float64Array( POSE_LENGTH ) );
	const screw = jawScrew( pose, new Float64Array( SCREW_SIZE ) );
	near( screw[ 3 ], 0, 1e-12, 'identity: no angle (rad)' );
	const turned = jawPose( 20, { pivot: [ - 50, 40 ], translation_per_degree: [ 0, 0 ] }, new Float64Array( POSE_LENGTH ) );
	jawScrew( turned, screw );
	assert.ok( Math.abs( screw[ 3 ] - 20 * Math.PI / 180 ) < 1e-12 );
	nearArray( screw.subarray( 0, 3 ), [ 0, 0, - 1 ], 1e-12, 'the screw axis (unit)' );
	assert.ok( Math.abs( screw[ 4 ] ) < 1e-12, 'a rotation about a z-parallel axis does not slide along it' );

} );

test( 'the incisor face recedes quadratically outside its table, with the matching slope', () => {

	const table = { y0: 0, z0: 0, step_y: 1, step_z: 1, rows: 2, cols: 2, x: [ 10, 10, 10, 10 ], recession: 4 };
	const bound = new Float64Array( 3 );
	teethBound( table, 0.5, 0.5, bound );
	nearArray( bound, [ 10, 0, 0 ], 1e-12, 'inside the table: F, dF/dy, dF/dz (mm)' );
	teethBound( table, - 0.5, 0.5, bound );
	nearArray( bound, [ 9, 4, 0 ], 1e-12, '0.5 mm below: 4 * 0.25 mm back, rising toward the table' );

} );

test( 'bad input is refused: parameters out of range, other meshes, another format', () => {

	const { rig } = setup();
	assert.throws( () => lipValues( rig, { lip_rounding: 99 } ), /lip_rounding = 99 is outside \[-4, 10\] mm/ );
	assert.throws( () => lipValues( rig, { lip_opening: Number.NaN } ), /lip_opening = NaN/ );
	const shifted = { ...REST, upper_lip: REST.upper_lip.map( ( x ) => x + 1 ) };
	assert.throws( () => createFaceRig( FIXTURES.rig, shifted ), /the rig was built for other meshes/ );
	assert.throws( () => createFaceRig( FIXTURES.rig, { ...REST, lower_lip: REST.lower_lip.subarray( 3 ) } ), /"lower_lip" has 515 vertices; the face rig was built for 516/ );
	assert.throws( () => createFaceRig( { ...FIXTURES.rig, format_version: 99 }, REST ), /format_version 99 is not 1/ );

} );

test( 'lipGap measures the midline crossings of any posed lips', () => {

	const { rig } = setup();
	const lowered = REST.lower_lip.map( ( x, k ) => ( k % 3 === 1 ? x - 4 : x ) );
	const rest = lipGap( rig, REST.upper_lip, REST.lower_lip );
	assert.ok( Math.abs( lipGap( rig, REST.upper_lip, lowered ) - rest - 4 ) < 1e-4 );
	const raised = REST.lower_lip.map( ( x, k ) => ( k % 3 === 1 ? x + 30 : x ) );
	assert.equal( lipGap( rig, REST.upper_lip, raised ), 0 );

} );

test( 'posing allocates nothing: thousands of poses trigger no garbage collection', async () => {

	const { rig, out } = setup();
	// Poses and parameter sets made beforehand, so that the loop measures the kernel alone.
	const poses = Array.from( { length: 25 }, ( _, k ) => jawPose( k, FIXTURES.jaw, new Float64Array( POSE_LENGTH ) ) );
	const sets = Array.from( { length: 10 }, ( _, k ) => lipValues( rig, { lip_opening: k / 10, lip_rounding: k - 4, lower_lip_tuck: k / 2 } ) );
	const pose = ( k ) => poseFace( rig, sets[ k % 10 ], poses[ k % 25 ], out );
	const calls = 3000;
	const loop = () => {

		for ( let k = 0; k < calls; k ++ ) pose( k );

	};
	loop(); // let the JIT settle
	const quiet = await garbageCollections( loop );
	const noisy = await garbageCollections( () => {

		for ( let k = 0; k < calls; k ++ ) poseFace( rig, sets[ 0 ], poses[ 0 ], Object.fromEntries( FACE_RIG_MESHES.map( ( n ) => [ n, new Float32Array( out[ n ].length ) ] ) ) );

	} );
	assert.equal( quiet, 0, `${ quiet } collections during ${ calls } poses` );
	assert.ok( noisy > 0, 'allocating outputs per pose should trigger collections' );

} );
