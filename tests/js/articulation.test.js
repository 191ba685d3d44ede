// The per-frame articulation pipeline (web/src/scene/Articulation.js) in Node: the fitted tongue
// rig and collision tables from the shared vectors, a head of stand-in meshes. Parameters ->
// jaw pose on the mandible -> tongue surface -> collision correction -> the scene's tongue ->
// lips -> hooks, recomputed only when the parameters change, without allocating.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fewestGarbageCollections, garbageCollections } from './support/garbage.js';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { BoxGeometry, Matrix4 } from 'three';

import { Head } from '../../web/src/scene/Head.js';
import { Articulation, parameterDefinitions, TONGUE_PART } from '../../web/src/scene/Articulation.js';
import { lipGap, midlineCrossings } from '../../web/src/scene/FacePose.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { jawPose, POSE_LENGTH } from '../../web/src/core/jaw.js';
import { ParamState } from '../../web/src/core/paramState.js';
import { decodeCollisionTables } from '../../web/src/core/tables.js';
import { FLAG_CORRECTED } from '../../web/src/core/constants.js';
import { debugObject } from '../../web/src/debug.js';
import { near, nearArray } from './support/near.js';

const VECTORS = join( dirname( fileURLToPath( import.meta.url ) ), '..', 'vectors' );
const RIG = JSON.parse( readFileSync( join( VECTORS, 'tongue-surface.json' ), 'utf8' ) ).fixtures.rig;
const TABLES = decodeCollisionTables( readFileSync( join( VECTORS, 'collision-tables.bin' ) ) );

/** A head of stand-ins: a box for the rest tongue, the mandible and the two lips (in the mouth, touching at y = 0). */
function standInHead() {

	const head = new Head();
	head.addPart( { name: 'tongue_rest', role: 'tongue' }, new BoxGeometry( 40, 20, 30 ) );
	head.addPart( { name: 'mandible', role: 'mandible' }, new BoxGeometry( 60, 20, 60, 2, 2, 2 ).translate( 0, - 30, 0 ) );
	head.addPart( { name: 'upper_lip', role: 'lip' }, new BoxGeometry( 8, 6, 40, 1, 1, 2 ).translate( 36, 3, 0 ) );
	head.addPart( { name: 'lower_lip', role: 'lip' }, new BoxGeometry( 8, 6, 40, 1, 1, 2 ).translate( 36, - 3, 0 ) );
	head.finishLoading();
	return head;

}

function setUp( { tables = TABLES } = {} ) {

	const rig = new TongueRig( RIG );
	const state = new ParamState( parameterDefinitions( RIG ) );
	const head = standInHead();
	const articulation = new Articulation( rig, state, { tables } ).attach( head );
	return { rig, state, head, articulation };

}

/** The rig's own surface for a parameter object, uncorrected. */
function rigSurface( params ) {

	const rig = new TongueRig( RIG );
	return rig.evaluate( rig.valuesFrom( params ), rig.createSurface() );

}

test( 'the state lists the tongue rig\'s parameters first, in its order, then the face rig\'s new ones', () => {

	const lips = [ { name: 'lip_opening', unit: 'mm', min: 0, max: 50, neutral: 50, group: 'lips' }, RIG.parameters[ 0 ] ];
	const definitions = parameterDefinitions( RIG, { parameters: lips } );
	assert.deepEqual( definitions.map( ( p ) => p.name ), [ ...RIG.parameters.map( ( p ) => p.name ), 'lip_opening' ] );

} );

test( 'a state whose order differs from the rig is refused', () => {

	const shuffled = [ RIG.parameters[ 1 ], RIG.parameters[ 0 ], ...RIG.parameters.slice( 2 ) ];
	assert.throws( () => new Articulation( new TongueRig( RIG ), new ParamState( shuffled ) ), /parameter 0 is "tip_height" in the state but "tip_advancement" in the tongue rig/ );

} );

test( 'the parametric tongue replaces the rest tongue in the scene, with its triangles and normals', () => {

	const { head, articulation } = setUp( { tables: null } );
	const geometry = head.part( TONGUE_PART ).geometry;
	assert.equal( geometry, articulation.geometry );
	for ( const mesh of head.part( TONGUE_PART ).meshes ) assert.equal( mesh.geometry, geometry );
	assert.equal( geometry.attributes.position.array, articulation.positions, 'the scene draws the corrected array itself' );
	assert.equal( geometry.attributes.position.count, 2978 );
	assert.equal( geometry.index.count / 3, 5952 );
	const rest = rigSurface( {} );
	// The same kernel on the same values: equal up to float32 rounding (mm; unit normals, which the
	// frame takes from the float32 positions it draws: up to about 1e-5 off the float64 surface's
	// where the triangles are smallest, at the poles, so they are held to 1e-4).
	nearArray( articulation.positions, rest.positions, 1e-5, 'positions' );
	nearArray( articulation.normals, rest.normals, 1e-4, 'normals' );
	assert.ok( head.part( TONGUE_PART ).outline.segmentCount > 0 || head.part( TONGUE_PART ).outlineStale, 'the section outline follows the new tongue' );

} );

test( 'nothing is recomputed while the parameters stay the same', () => {

	const { state, articulation } = setUp();
	const updates = articulation.updates;
	assert.equal( articulation.update(), false );
	assert.equal( articulation.update(), false );
	assert.equal( articulation.updates, updates );
	state.set( 'tip_height', 3 );
	assert.equal( articulation.update(), true );
	assert.equal( articulation.update(), false );
	assert.equal( articulation.updates, updates + 1 );

} );

test( 'moving a tongue parameter moves the scene\'s tongue to the rig\'s surface for it', () => {

	const { state, head, articulation } = setUp( { tables: null } );
	const before = articulation.tongueReport();
	state.set( 'tip_advancement', 6 );
	articulation.update();
	nearArray( articulation.positions, rigSurface( { tip_advancement: 6 } ).positions, 1e-5, 'positions (mm)' );
	assert.equal( head.part( TONGUE_PART ).geometry.attributes.position.array, articulation.positions );
	const after = articulation.tongueReport();
	assert.ok( after.tip[ 0 ] - before.tip[ 0 ] > 4, `the tip went from x = ${ before.tip[ 0 ] } to ${ after.tip[ 0 ] }` );
	assert.notEqual( after.checksum, before.checksum );
	assert.equal( after.vertexCount, 2978 );
	assert.equal( after.samples.length, 8 );

} );

test( 'raising the tongue into the palate moves the offending vertices onto it and no others', () => {

	const { state, articulation } = setUp();
	assert.equal( articulation.stats[ 2 ], 0, 'the rest tongue does not touch the palate' );
	for ( const [ name, value ] of [ [ 'body_height', 8 ], [ 'dorsum_height', 10 ], [ 'blade_height', 8 ], [ 'tip_height', 8 ] ] ) state.set( name, value );
	articulation.update();
	const raw = rigSurface( { body_height: 8, dorsum_height: 10, blade_height: 8, tip_height: 8 } ).positions;
	const [ screened, tested, corrected ] = articulation.stats;
	assert.equal( screened, 2978 );
	assert.ok( corrected > 50 && tested >= corrected, `screened ${ screened }, tested ${ tested }, corrected ${ corrected }` );
	const O = TABLES.origin;
	let flagged = 0;
	for ( let v = 0; v < 2978; v ++ ) {

		const p = articulation.positions.subarray( 3 * v, 3 * v + 3 );
		const q = raw.subarray( 3 * v, 3 * v + 3 );
		if ( articulation.flags[ v ] !== FLAG_CORRECTED ) {

			assert.deepEqual( p, q, `vertex ${ v } was not in the palate and must not move` );
			continue;

		}

		flagged ++;
		// Moved toward O along the line O -> P: shorter, same direction.
		const d = [ 0, 1, 2 ].map( ( k ) => p[ k ] - O[ k ] );
		const e = [ 0, 1, 2 ].map( ( k ) => q[ k ] - O[ k ] );
		const cross = Math.hypot( d[ 1 ] * e[ 2 ] - d[ 2 ] * e[ 1 ], d[ 2 ] * e[ 0 ] - d[ 0 ] * e[ 2 ], d[ 0 ] * e[ 1 ] - d[ 1 ] * e[ 0 ] );
		assert.ok( Math.hypot( ...d ) < Math.hypot( ...e ), `vertex ${ v } moved away from O` );
		assert.ok( cross / Math.hypot( ...e ) < 1e-3 * Math.hypot( ...e ), `vertex ${ v } left its line toward O` );

	}

	assert.equal( flagged, corrected );
	for ( let v = 0; v < 2978; v ++ ) {

		const n = articulation.normals.subarray( 3 * v, 3 * v + 3 );
		assert.ok( Math.abs( Math.hypot( ...n ) - 1 ) < 1e-5, `normal ${ v } is not a unit vector` );

	}

	assert.ok( articulation.volume < meshVolumeOf( raw ), 'flattening against the palate takes volume away' );

} );

function meshVolumeOf( positions ) {

	const rig = new TongueRig( RIG );
	let sum = 0;
	const index = rig.index;
	for ( let t = 0; t < index.length; t += 3 ) {

		const [ a, b, c ] = [ 3 * index[ t ], 3 * index[ t + 1 ], 3 * index[ t + 2 ] ];
		sum += positions[ a ] * ( positions[ b + 1 ] * positions[ c + 2 ] - positions[ b + 2 ] * positions[ c + 1 ] )
			+ positions[ a + 1 ] * ( positions[ b + 2 ] * positions[ c ] - positions[ b ] * positions[ c + 2 ] )
			+ positions[ a + 2 ] * ( positions[ b ] * positions[ c + 1 ] - positions[ b + 1 ] * positions[ c ] );

	}

	return sum / 6;

}

test( 'the mandible\'s matrix is the jaw pose, and the lip gap grows as the jaw opens', () => {

	const { state, head, articulation } = setUp();
	const gaps = [];
	for ( const opening of [ 0, 3, 6, 10 ] ) {

		state.set( 'jaw_opening', opening );
		articulation.update();
		const pose = jawPose( opening, RIG.jaw, new Float64Array( POSE_LENGTH ) );
		const expected = new Matrix4().set( ...pose, 0, 0, 0, 1 );
		for ( const name of [ 'mandible', 'lower_lip' ] ) {

			const group = head.part( name ).group;
			assert.equal( group.matrixAutoUpdate, false );
			group.matrix.elements.forEach( ( value, k ) => assert.ok( Math.abs( value - expected.elements[ k ] ) < 1e-12, `${ name } matrix at ${ opening } deg` ) );

		}

		gaps.push( articulation.lipGap );

	}

	near( gaps[ 0 ], 0, 1e-9, 'the stand-in lips touch at rest (gap, mm)' );
	for ( let k = 1; k < gaps.length; k ++ ) assert.ok( gaps[ k ] > gaps[ k - 1 ] + 1, `lip gaps ${ gaps }` );
	assert.equal( head.part( 'upper_lip' ).group.matrixAutoUpdate, true, 'the upper lip stays with the skull' );

} );

test( 'the lip gap is measured where the lips cross the mid-sagittal plane', () => {

	const upper = midlineCrossings( new BoxGeometry( 8, 6, 40, 1, 1, 2 ).translate( 36, 5, 0 ) );
	const lower = midlineCrossings( new BoxGeometry( 8, 6, 40, 1, 1, 2 ).translate( 36, - 3, 0 ) );
	assert.ok( upper.length > 0 && upper.length % 2 === 0 );
	const identity = jawPose( 0, RIG.jaw, new Float64Array( POSE_LENGTH ) );
	assert.ok( Math.abs( lipGap( { upper, lower }, identity ) - 2 ) < 1e-12, 'lowest upper y 2 over highest lower y 0' );
	near( lipGap( { upper: lower, lower: upper }, identity ), 0, 1e-12, 'overlapping lips have no gap' );

} );

test( 'corrected-vertex hooks get the same array after every recompute until removed', () => {

	const { state, articulation } = setUp();
	const seen = [];
	const remove = articulation.onCorrected( ( positions, source ) => seen.push( [ positions, source, source.stats[ 2 ] ] ) );
	state.set( 'tip_height', 8 );
	articulation.update();
	state.set( 'blade_height', 8 );
	articulation.update();
	assert.equal( seen.length, 2 );
	assert.ok( seen.every( ( [ positions, source ] ) => positions === articulation.positions && source === articulation ) );
	assert.ok( seen[ 1 ][ 2 ] > seen[ 0 ][ 2 ], 'the hook sees the counts of its own frame' );
	remove();
	state.set( 'blade_height', 0 );
	articulation.update();
	assert.equal( seen.length, 2 );

} );

test( 'window.glasshead reports the parameters, tongue, collision counts and lip gap until disposed', () => {

	const { state, articulation } = setUp();
	articulation.registerDebugFields();
	state.set( 'body_height', 8 );
	state.set( 'dorsum_height', 10 );
	articulation.update();
	const debug = debugObject();
	assert.equal( debug.params.body_height, 8 );
	assert.equal( debug.tongue.vertexCount, 2978 );
	assert.ok( Math.abs( debug.tongue.volumeMm3 - articulation.volume ) < 1e-3 );
	const [ screened, tested, corrected ] = articulation.stats;
	assert.deepEqual( [ debug.collision.screened, debug.collision.tested, debug.collision.corrected ], [ screened, tested, corrected ] );
	assert.ok( debug.collision.corrected > 0 );
	assert.equal( debug.collision.enabled, true );
	assert.equal( typeof debug.lipGap, 'number' );
	articulation.dispose();
	assert.equal( 'collision' in debugObject(), false );

} );

test( 'a frame allocates nothing: thousands of recomputes trigger no garbage collection', async () => {

	const { state, articulation } = setUp();
	articulation.onCorrected( () => {} );
	const k = state.index.get( 'body_height' );
	const frame = ( i ) => {

		state.values[ k ] = ( i % 9 ); // into the palate and out again, as a track would
		state.touch();
		articulation.update();

	};

	for ( let i = 0; i < 2000; i ++ ) frame( i ); // let the JIT settle (it compiles in the first thousand)
	const frames = 3000;
	const quiet = await fewestGarbageCollections( () => {

		for ( let i = 0; i < frames; i ++ ) frame( i );

	} );

	// The same loop with a fresh array per frame shows that the probe does see allocation.
	const noisy = await garbageCollections( () => {

		for ( let i = 0; i < frames; i ++ ) {

			frame( i );
			articulation.scratch = new Float32Array( articulation.positions );

		}

	} );
	assert.equal( quiet, 0, `${ quiet } collections during ${ frames } frames` );
	assert.ok( noisy > 0, 'allocating per frame should trigger collections' );

} );
