// The head's scene state (web/src/scene/Head.js) without a browser: three.js objects work in Node,
// only drawing needs WebGL.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BoxGeometry, SphereGeometry } from 'three';

import { Head } from '../../web/src/scene/Head.js';
import { SKIN_RENDER_ORDER } from '../../web/src/scene/skinPasses.js';
import { nearArray } from './support/near.js';

function loadedHead() {

	const head = new Head();
	head.addPart( { name: 'face_skin', role: 'skin' }, new SphereGeometry( 100, 24, 16 ) );
	head.addPart( { name: 'tongue_rest', role: 'tongue' }, new BoxGeometry( 40, 20, 30 ) );
	head.addPart( { name: 'upper_lip', role: 'lip' }, new BoxGeometry( 10, 5, 30 ).translate( 40, 5, 0 ) );
	head.finishLoading();
	return head;

}

const skinMeshes = ( head ) => head.part( 'face_skin' ).meshes.filter( ( mesh ) => mesh.userData.skinPass );
const byPass = ( head, pass ) => skinMeshes( head ).find( ( mesh ) => mesh.userData.skinPass === pass );

test( 'the loaded meshes are reported with their triangle counts', () => {

	const head = loadedHead();
	assert.deepEqual( head.meshInfo(), [
		{ name: 'face_skin', triangles: new SphereGeometry( 100, 24, 16 ).index.count / 3 },
		{ name: 'tongue_rest', triangles: 12 },
		{ name: 'upper_lip', triangles: 12 },
	] );
	assert.throws( () => head.addPart( { name: 'tongue_rest', role: 'tongue' }, new BoxGeometry() ), /already loaded/ );

} );

test( 'opaque skin is drawn as one opaque surface that writes depth', () => {

	const head = loadedHead();
	head.setTransparency( 0 );
	const front = byPass( head, 'front' );
	assert.equal( front.visible, true );
	assert.equal( front.material.transparent, false );
	assert.equal( front.material.depthWrite, true );
	assert.equal( byPass( head, 'prepass' ).visible, false );

} );

test( 'transparent skin is drawn back faces first, then depth, then front faces, without writing depth', () => {

	const head = loadedHead();
	head.setTransparency( 40 );
	const [ back, prepass, front ] = [ 'back', 'prepass', 'front' ].map( ( pass ) => byPass( head, pass ) );
	assert.ok( back.visible && prepass.visible && front.visible );
	assert.ok( back.renderOrder < prepass.renderOrder && prepass.renderOrder < front.renderOrder );
	assert.equal( front.renderOrder, SKIN_RENDER_ORDER.front );
	assert.ok( Math.abs( front.material.opacity - 0.6 ) < 1e-12 );
	assert.equal( front.material.depthWrite, false );
	assert.equal( prepass.material.colorWrite, false );
	// The lips fade with the skin, and are drawn before it.
	const lip = head.part( 'upper_lip' ).meshes[ 0 ];
	assert.ok( lip.material.transparent && lip.material.opacity < 1 && lip.renderOrder < back.renderOrder );
	// The tongue is untouched: opaque, drawn first.
	const tongue = head.part( 'tongue_rest' ).meshes[ 0 ];
	assert.equal( tongue.material.transparent, false );

} );

test( 'at 100 % transparency no skin pass is drawn', () => {

	const head = loadedHead();
	head.setTransparency( 100 );
	assert.ok( skinMeshes( head ).every( ( mesh ) => ! mesh.visible ) );
	assert.equal( head.transparency, 100 );
	assert.throws( () => head.setTransparency( 120 ), RangeError );
	assert.equal( head.transparency, 100 );

} );

test( 'the cutaway keeps z >= 0 and shows the section outlines and cut colours', () => {

	const head = loadedHead();
	assert.ok( head.clipPlane.distanceToPoint( { x: 0, y: 0, z: - 50 } ) > 0, 'nothing is clipped before the cut' );
	head.setCutaway( true );
	assert.equal( head.clipPlane.distanceToPoint( { x: 0, y: 0, z: - 1 } ), - 1 );
	assert.equal( head.clipPlane.distanceToPoint( { x: 0, y: 0, z: 2 } ), 2 );
	const tongue = head.part( 'tongue_rest' );
	assert.equal( tongue.outline.visible, true );
	assert.ok( tongue.outline.segmentCount > 0 );
	assert.equal( tongue.meshes[ 0 ].material.userData.section.sectionOn.value, 1 );
	for ( const mesh of tongue.meshes ) assert.deepEqual( mesh.material.clippingPlanes, [ head.clipPlane ] );
	head.setCutaway( false );
	assert.equal( tongue.outline.visible, false );
	assert.equal( tongue.meshes[ 0 ].material.userData.section.sectionOn.value, 0 );

} );

test( 'moving a part\'s vertices moves its section outline with it', () => {

	const head = loadedHead();
	head.setCutaway( true );
	const tongue = head.part( 'tongue_rest' );
	const outlineX = () => {

		const array = tongue.outline.geometry.getAttribute( 'position' ).array;
		let max = - Infinity;
		for ( let i = 0; i < tongue.outline.segmentCount * 2; i ++ ) max = Math.max( max, array[ 3 * i ] );
		return max;

	};

	assert.equal( outlineX(), 20 );
	const moved = Float32Array.from( tongue.geometry.getAttribute( 'position' ).array );
	for ( let i = 0; i < moved.length; i += 3 ) moved[ i ] += 5;
	head.updateVertices( 'tongue_rest', moved );
	assert.equal( outlineX(), 25 );
	assert.throws( () => head.updateVertices( 'tongue_rest', new Float32Array( 6 ) ), /vertices/ );
	assert.throws( () => head.updateVertices( 'nothing', moved ), /no mesh called "nothing"/ );

} );

test( 'the mouth box is the box around the lips', () => {

	const head = loadedHead();
	const box = head.mouthBox();
	nearArray( [ box.min.x, box.max.x, box.min.y, box.max.y ], [ 35, 45, 2.5, 7.5 ], 1e-6, 'mouth box (mm, float32 positions)' );

} );
