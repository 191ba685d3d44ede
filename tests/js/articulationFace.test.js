// The face in the articulation (web/src/scene/FacePose.js, Articulation.js): the real-time face
// rig of the shared vectors posing the skin, lips and head shell from the state's lip parameters
// and the jaw, the seam of the skin welded again, and the views' loadArticulation() putting it
// together from the API (a client on a fake fetch) or falling back to the rigid lower lip when it
// cannot.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fewestGarbageCollections } from './support/garbage.js';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { BoxGeometry, BufferAttribute, BufferGeometry, Group, Matrix4 } from 'three';

import { Head } from '../../web/src/scene/Head.js';
import { Articulation, parameterDefinitions } from '../../web/src/scene/Articulation.js';
import { createApi } from '../../web/src/api.js';
import { loadArticulation } from '../../web/src/ui/shared/loaders.js';
import { FacePose, seamGroups, weldSeam } from '../../web/src/scene/FacePose.js';
import { FACE_RIG_MESHES } from '../../web/src/core/constants.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { jawPose, POSE_LENGTH } from '../../web/src/core/jaw.js';
import { ParamState } from '../../web/src/core/paramState.js';
import { debugObject } from '../../web/src/debug.js';
import { nearArray } from './support/near.js';

const VECTORS = join( dirname( fileURLToPath( import.meta.url ) ), '..', 'vectors' );
const TONGUE = JSON.parse( readFileSync( join( VECTORS, 'tongue-surface.json' ), 'utf8' ) ).fixtures.rig;
const FACE = JSON.parse( readFileSync( join( VECTORS, 'face-rig.json' ), 'utf8' ) ).fixtures;

/** A geometry of the rest positions with stand-in triangles (consecutive vertex triples). */
function restGeometry( name ) {

	const positions = Float32Array.from( FACE.rest[ name ] );
	const count = positions.length / 3;
	const index = Uint32Array.from( { length: 3 * Math.floor( count / 3 ) }, ( _, k ) => k );
	const geometry = new BufferGeometry();
	geometry.setAttribute( 'position', new BufferAttribute( positions, 3 ) );
	geometry.setIndex( new BufferAttribute( index, 1 ) );
	geometry.computeVertexNormals();
	return geometry;

}

/** The parts FacePose reads, without a renderer: name, tissue, geometry, group, outline. */
function faceHead() {

	const parts = new Map( FACE_RIG_MESHES.map( ( name ) => [ name, {
		name, tissue: name === 'face_skin' || name === 'head_shell' ? 'skin' : 'lip', geometry: restGeometry( name ),
		group: new Group(), outline: { update() {} }, outlineStale: false,
	} ] ) );
	return { cutaway: false, part: ( name ) => parts.get( name ) };

}

function lipState() {

	return new ParamState( parameterDefinitions( TONGUE, FACE.rig ) );

}

const jaw = ( degrees ) => jawPose( degrees, TONGUE.jaw, new Float64Array( POSE_LENGTH ) );

test( 'the lip parameters join the state after the tongue rig\'s, in the lips group', () => {

	const state = lipState();
	assert.deepEqual( state.names.slice( TONGUE.parameters.length ), FACE.rig.parameters.map( ( p ) => p.name ) );
	assert.deepEqual( state.groups().map( ( g ) => g.group ).slice( 0, 2 ), [ 'jaw', 'lips' ] );

} );

test( 'the face rig poses the skin and lips in their geometries: the jaw opens the mouth, closing the lips shuts it', () => {

	const head = faceHead();
	const state = lipState();
	const face = new FacePose( FACE.rig, head, state );
	const lower = head.part( 'lower_lip' ).geometry.attributes.position.array;
	const rest = Float32Array.from( lower );
	const closedJaw = face.pose( state.values, jaw( 0 ) );
	const open = face.pose( state.values, jaw( 15 ) );
	assert.ok( open > closedJaw + 5, `lip gap ${ closedJaw } mm closed, ${ open } mm at 15 degrees` );
	assert.ok( lower.some( ( value, k ) => value !== rest[ k ] ), 'the lower lip moved in its own geometry' );
	assert.equal( head.part( 'lower_lip' ).outlineStale, true, 'its section outline is redrawn when next shown' );
	state.set( 'lip_opening', 0 );
	assert.ok( face.pose( state.values, jaw( 15 ) ) < 0.01, 'lip opening 0 closes the lips' );
	const normals = head.part( 'lower_lip' ).geometry.attributes.normal.array;
	for ( let v = 0; v < normals.length; v += 3 ) {

		const length = Math.hypot( normals[ v ], normals[ v + 1 ], normals[ v + 2 ] );
		assert.ok( length === 0 || Math.abs( length - 1 ) < 1e-5, `normal ${ v / 3 } has length ${ length }` );

	}

} );

test( 'skin vertices at one point of the seam share one normal after welding', () => {

	const part = ( positions, normals ) => {

		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( Float32Array.from( positions ), 3 ) );
		geometry.setAttribute( 'normal', new BufferAttribute( Float32Array.from( normals ), 3 ) );
		return { geometry };

	};

	const a = part( [ 0, 0, 0, 5, 0, 0 ], [ 1, 0, 0, 0, 1, 0 ] );
	const b = part( [ 0.001, 0, 0, 9, 9, 9 ], [ 0, 1, 0, 0, 0, 1 ] );
	const seam = seamGroups( [ a, b ] );
	assert.equal( seam.starts.length - 1, 1, 'one shared point' );
	weldSeam( seam );
	const h = Math.SQRT1_2;
	nearArray( a.geometry.attributes.normal.array, [ h, h, 0, 0, 1, 0 ], 1e-6, 'welded unit normals (float32)' );
	assert.deepEqual( Array.from( b.geometry.attributes.normal.array.subarray( 0, 3 ) ), Array.from( a.geometry.attributes.normal.array.subarray( 0, 3 ) ) );
	assert.deepEqual( Array.from( b.geometry.attributes.normal.array.subarray( 3 ) ), [ 0, 0, 1 ], 'a vertex off the seam keeps its normal' );

} );

test( 'with a face rig the lower lip is no longer carried rigidly: its group stays put and the rig moves it', () => {

	const head = faceHead();
	const mandible = { name: 'mandible', group: new Group(), geometry: new BoxGeometry(), outline: { update() {} } };
	const parts = new Map( [ [ 'mandible', mandible ] ] );
	const fullHead = { cutaway: false, part: ( name ) => parts.get( name ) ?? head.part( name ), setGeometry() {} };
	const state = lipState();
	const articulation = new Articulation( new TongueRig( TONGUE ), state ).attach( fullHead );
	articulation.setFaceRig( new FacePose( FACE.rig, fullHead, state ) );
	state.set( 'jaw_opening', 10 );
	articulation.update();
	assert.ok( head.part( 'lower_lip' ).group.matrix.equals( new Matrix4() ) );
	assert.equal( mandible.group.matrix.equals( new Matrix4() ), false, 'the mandible turned' );
	assert.ok( articulation.lipGap > 5, `lip gap ${ articulation.lipGap }` );

} );

/** A client whose fetch answers the API's three requests of loadArticulation(). */
function apiFetch( { face = FACE.rig } = {} ) {

	const answer = ( status, body ) => ( { ok: status === 200, status, statusText: '', json: async () => body } );
	return createApi( { fetchImpl: async ( url ) => {

		if ( url.endsWith( '/tongue/rig' ) ) return answer( 200, TONGUE );
		if ( url.endsWith( '/face/rig' ) ) return face ? answer( 200, face ) : answer( 503, { detail: 'face rig not built: run `glasshead build`' } );
		if ( url.endsWith( '/collision/tables' ) ) return answer( 503, { detail: 'collision tables not built' } );
		return answer( 404, { detail: `no route ${ url }` } );

	} } );

}

/** A head with stand-in meshes: the tongue, the mandible and, from the vectors, the face. */
function standInHead( { withFace = true } = {} ) {

	const head = new Head();
	head.addPart( { name: 'tongue_rest', role: 'tongue' }, new BoxGeometry( 40, 20, 30 ) );
	head.addPart( { name: 'mandible', role: 'mandible' }, new BoxGeometry( 60, 20, 60 ).translate( 0, - 30, 0 ) );
	for ( const name of [ 'upper_lip', 'lower_lip' ] ) head.addPart( { name, role: 'lip' }, restGeometry( name ) );
	if ( withFace ) for ( const name of [ 'face_skin', 'head_shell' ] ) head.part = wrapPart( head.part.bind( head ), name, restGeometry( name ) );
	head.finishLoading();
	return head;

}

/** Add a skin part without the skin's draw passes (their eye and nostril patches need a real mesh). */
function wrapPart( part, name, geometry ) {

	const extra = { name, tissue: 'skin', geometry, group: new Group(), outline: { update() {} } };
	return ( asked ) => ( asked === name ? extra : part( asked ) );

}

test( 'loadArticulation poses the face from the API\'s face rig and reports what it could not load', async () => {

	const head = standInHead();
	const articulation = await loadArticulation( head, null, { api: apiFetch() } );
	try {

		assert.equal( articulation.faceRigError, null );
		assert.match( articulation.tablesError, /503/ );
		assert.ok( articulation.faceRig instanceof FacePose );
		assert.ok( articulation.state.names.includes( 'lip_rounding' ) );
		assert.equal( debugObject().collision.enabled, false );
		const closed = debugObject().lipGap;
		articulation.state.set( 'jaw_opening', 10 );
		articulation.update();
		assert.ok( debugObject().lipGap > closed + 5, `lip gap ${ closed } then ${ debugObject().lipGap }` );

	} finally {

		articulation.dispose();

	}

} );

test( 'without a face rig, or without the meshes it poses, the lower lip rides on the jaw', async () => {

	for ( const [ api, message ] of [
		[ apiFetch( { face: null } ), /503: face rig not built/ ],
		[ apiFetch(), /needs the mesh "face_skin"/ ],
	] ) {

		const head = standInHead( { withFace: false } );
		const articulation = await loadArticulation( head, null, { api } );
		try {

			assert.match( articulation.faceRigError, message );
			assert.equal( articulation.faceRig, null );
			articulation.state.set( 'jaw_opening', 10 );
			articulation.update();
			assert.equal( head.part( 'lower_lip' ).group.matrix.equals( new Matrix4() ), false, 'the lower lip turned with the jaw' );

		} finally {

			articulation.dispose();

		}

	}

} );

test( 'posing the face allocates nothing: a thousand poses trigger no garbage collection', async () => {

	const head = faceHead();
	const state = lipState();
	const face = new FacePose( FACE.rig, head, state );
	const poses = [ 0, 5, 10, 15, 20 ].map( jaw );
	const k = state.index.get( 'lip_rounding' );
	const frame = ( i ) => {

		state.values[ k ] = i % 7;
		face.pose( state.values, poses[ i % poses.length ] );

	};

	for ( let i = 0; i < 500; i ++ ) frame( i ); // let the JIT settle
	const quiet = await fewestGarbageCollections( () => {

		for ( let i = 0; i < 1000; i ++ ) frame( i );

	} );

	assert.equal( quiet, 0, `${ quiet } collections during 1,000 face poses` );

} );

test( 'posing the face again with the same lips and jaw changes nothing and redoes nothing', () => {

	const head = faceHead();
	const state = lipState();
	const face = new FacePose( FACE.rig, head, state );
	state.set( 'lip_rounding', 3 );
	const gap = face.pose( state.values, jaw( 10 ) );
	const positions = head.part( 'lower_lip' ).geometry.attributes.position;
	const before = positions.version;
	assert.equal( face.pose( state.values, jaw( 10 ) ), gap );
	assert.equal( positions.version, before, 'the geometry was not flagged for upload' );
	assert.notEqual( face.pose( state.values, jaw( 12 ) ), gap, 'a new jaw pose poses the face' );
	assert.ok( positions.version > before );

} );
