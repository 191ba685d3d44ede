// The flesh points (EMA sensor points) against the shared vectors written by the Python reference
// (tests/vectors/flesh-points.json, on the rigs of tongue-surface.json and face-rig.json), and
// the frame's evaluation allocating nothing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fewestGarbageCollections } from './support/garbage.js';

import { createFaceRig, lipValues, poseFace, restFaceRig } from '../../web/src/core/faceRig.js';
import { FLESH_POINT_NAMES, FLESH_POINTS_LENGTH, fleshPoints, TONGUE_SENSOR_ARC_MM, tongueAnchors } from '../../web/src/core/fleshPoints.js';
import { jawPose, POSE_LENGTH } from '../../web/src/core/jaw.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { FACE_RIG_LIP_PARAMETERS, FACE_RIG_MESHES } from '../../web/src/core/constants.js';

import { near, readVectors, tolerance } from './support/vectors.js';

const VECTORS = readVectors( 'flesh-points.json' );
const { fixtures: FIXTURES } = VECTORS;
const TONGUE = readVectors( FIXTURES.tongue_rig ).fixtures.rig;
const FACE = readVectors( FIXTURES.face_rig ).fixtures;

function setup() {

	const tongue = new TongueRig( TONGUE );
	const surface = tongue.createSurface();
	tongue.evaluate( tongue.valuesFrom( {} ), surface, false );
	const anchors = tongueAnchors( tongue, surface.positions );
	const rest = Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, Float32Array.from( FACE.rest[ name ] ) ] ) );
	const face = createFaceRig( FACE.rig, rest );
	const posed = Object.fromEntries( FACE_RIG_MESHES.map( ( name ) => [ name, new Float32Array( rest[ name ].length ) ] ) );
	restFaceRig( face, posed );
	const incisors = { lower: FIXTURES.incisors.lower_incisor, upper: FIXTURES.incisors.upper_incisor };
	return {
		tongue, surface, anchors, face, posed, incisors,
		values: new Float64Array( tongue.parameterCount ), lips: new Float64Array( FACE_RIG_LIP_PARAMETERS.length ),
		pose: new Float64Array( POSE_LENGTH ), target: new Float64Array( FLESH_POINTS_LENGTH ),
	};

}

function frame( context, params ) {

	const { tongue, surface, anchors, face, posed, incisors, values, lips, pose, target } = context;
	const tongueParams = {}, lipParams = {};
	for ( const [ name, value ] of Object.entries( params ) ) {

		if ( tongue.parameterIndex.has( name ) ) tongueParams[ name ] = value;
		if ( FACE_RIG_LIP_PARAMETERS.includes( name ) ) lipParams[ name ] = value;

	}

	tongue.evaluate( tongue.valuesFrom( tongueParams, values ), surface, false );
	jawPose( values[ tongue.jawParameter ], tongue.jaw, pose );
	poseFace( face, lipValues( face, lipParams, lips ), pose, posed );
	return fleshPoints( tongue, surface.positions, anchors, incisors, pose, face, posed, target );

}

test( 'the vectors name the same points and arcs as this side, with unique descriptions', () => {

	assert.deepEqual( VECTORS.constants.names, [ ...FLESH_POINT_NAMES ] );
	assert.deepEqual( VECTORS.constants.arcs_mm, { ...TONGUE_SENSOR_ARC_MM } );
	assert.ok( VECTORS.cases.length > 100 );
	assert.equal( new Set( VECTORS.cases.map( ( c ) => c.description ) ).size, VECTORS.cases.length );

} );

test( 'the tongue sensors are anchored on the same stations as in Python', () => {

	const { anchors } = setup();
	const expected = FIXTURES.anchors;
	assert.deepEqual( [ ...anchors.first ], expected.first );
	assert.deepEqual( [ ...anchors.second ], expected.second );
	const tol = tolerance( VECTORS, 'weight' );
	anchors.weight.forEach( ( w, k ) => near( w, expected.weight[ k ], tol, `weight ${ k }` ) );

} );

test( 'every vector case gives the Python flesh points', () => {

	const context = setup();
	const tol = tolerance( VECTORS, 'point_mm' );
	let worst = 0;
	for ( const vector of VECTORS.cases ) {

		const points = frame( context, vector.input.params );
		FLESH_POINT_NAMES.forEach( ( name, k ) => {

			const expected = vector.expected.points[ name ];
			for ( let c = 0; c < 3; c ++ ) {

				const error = Math.abs( points[ 3 * k + c ] - expected[ c ] );
				worst = Math.max( worst, error );
				assert.ok( error <= tol, `${ vector.description }: ${ name }[${ c }] = ${ points[ 3 * k + c ] }, expected ${ expected[ c ] }` );

			}

		} );

	}

	assert.ok( worst > 0 && worst <= tol, `worst ${ worst } mm` );

} );

test( 'a frame of flesh points allocates nothing', async () => {

	const context = setup();
	const { tongue, surface, anchors, face, posed, incisors, pose, target } = context;
	tongue.evaluate( tongue.valuesFrom( { tip_height: 3 }, context.values ), surface, false );
	jawPose( 4, tongue.jaw, pose );
	poseFace( face, context.lips, pose, posed );
	const collections = await fewestGarbageCollections( () => {

		for ( let i = 0; i < 20000; i ++ ) fleshPoints( tongue, surface.positions, anchors, incisors, pose, face, posed, target );

	} );
	assert.equal( collections, 0 );
	assert.equal( target[ 21 ], incisors.upper[ 0 ] );

} );
