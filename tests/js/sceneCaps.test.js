// The caps on the cut faces of the tongue and the lips (web/src/scene/SectionCap.js, Head.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
	BackSide,
	BoxGeometry,
	DecrementWrapStencilOp,
	FrontSide,
	IncrementWrapStencilOp,
	Matrix4,
	NotEqualStencilFunc,
	Plane,
	Vector3,
} from 'three';

import { Head } from '../../web/src/scene/Head.js';
import { CAP_SIZE_MM, SectionCap } from '../../web/src/scene/SectionCap.js';

function headWithMouth() {

	const head = new Head();
	head.addPart( { name: 'tongue_rest', role: 'tongue' }, new BoxGeometry( 40, 20, 30 ) );
	head.addPart( { name: 'mandible', role: 'mandible' }, new BoxGeometry( 60, 20, 60 ).translate( 0, - 30, 0 ) );
	head.addPart( { name: 'upper_lip', role: 'lip' }, new BoxGeometry( 8, 6, 40 ).translate( 36, 3, 0 ) );
	head.addPart( { name: 'lower_lip', role: 'lip' }, new BoxGeometry( 8, 6, 40 ).translate( 36, - 3, 0 ) );
	head.addPart( { name: 'face_skin', role: 'skin' }, new BoxGeometry( 200, 200, 200 ) );
	return head;

}

test( 'the tongue and the lips get caps, each counted and drawn in its own turn', () => {

	const head = headWithMouth();
	const capped = [ 'tongue_rest', 'upper_lip', 'lower_lip' ].map( ( name ) => head.part( name ).cap );
	assert.ok( capped.every( Boolean ) );
	assert.equal( head.part( 'mandible' ).cap, undefined );
	assert.equal( head.part( 'face_skin' ).cap, undefined ); // a shell round a hollow head
	const orders = capped.flatMap( ( cap ) => [ cap.counters[ 0 ].renderOrder, cap.cap.renderOrder ] );
	for ( let i = 1; i < orders.length; i ++ ) assert.ok( orders[ i ] > orders[ i - 1 ], `render orders ${ orders }` );
	// Counting: back faces add, front faces subtract, through everything, clipped by the cut.
	const [ back, front ] = capped[ 0 ].counters.map( ( mesh ) => mesh.material );
	assert.equal( back.side, BackSide );
	assert.equal( front.side, FrontSide );
	assert.equal( back.stencilZPass, IncrementWrapStencilOp );
	assert.equal( front.stencilZPass, DecrementWrapStencilOp );
	assert.ok( ! back.depthTest && ! back.colorWrite && back.clippingPlanes[ 0 ] === head.clipPlane );
	assert.equal( capped[ 0 ].cap.material.stencilFunc, NotEqualStencilFunc );

} );

test( 'caps show with the cutaway only, and not over faded lips', () => {

	const head = headWithMouth();
	const visible = ( name ) => head.part( name ).cap.meshes.every( ( mesh ) => mesh.visible );
	assert.ok( ! visible( 'tongue_rest' ) && ! visible( 'upper_lip' ) );
	head.setCutaway( true );
	assert.ok( visible( 'tongue_rest' ) && visible( 'upper_lip' ) && visible( 'lower_lip' ) );
	head.setTransparency( 100 ); // no skin: the lips fade, and are seen through, cut or not
	assert.ok( visible( 'tongue_rest' ) );
	assert.ok( ! visible( 'upper_lip' ) && ! visible( 'lower_lip' ) );
	head.setCutaway( false );
	assert.ok( ! visible( 'tongue_rest' ) );

} );

test( 'the cap follows a replaced geometry and lies on the cutting plane', () => {

	const head = headWithMouth();
	const tongue = new BoxGeometry( 30, 30, 30 );
	head.setGeometry( 'tongue_rest', tongue );
	const cap = head.part( 'tongue_rest' ).cap;
	assert.ok( cap.counters.every( ( mesh ) => mesh.geometry === tongue ) );

	// An oblique plane: the unit square's corners land on it, spread to the cap's size.
	const plane = new Plane( new Vector3( 1, 2, 2 ).normalize(), - 7 );
	const oblique = new SectionCap( tongue, plane, '#ff0000', 1 );
	oblique.alignWithCut();
	const corners = [ [ 0.5, 0.5 ], [ - 0.5, 0.5 ], [ 0.5, - 0.5 ] ].map( ( [ x, y ] ) => new Vector3( x, y, 0 ).applyMatrix4( oblique.cap.matrixWorld ) );
	for ( const corner of corners ) assert.ok( Math.abs( plane.distanceToPoint( corner ) ) < 1e-9, `corner ${ corner.toArray() } is off the plane` );
	assert.ok( Math.abs( corners[ 0 ].distanceTo( corners[ 1 ] ) - CAP_SIZE_MM ) < 1e-6 );
	// The parent's motion does not move it off the plane: it is placed in world space when drawn.
	head.setCutaway( true );
	head.part( 'tongue_rest' ).group.applyMatrix4( new Matrix4().makeTranslation( 0, 0, 40 ) );
	head.group.updateMatrixWorld( true );
	cap.alignWithCut();
	assert.ok( Math.abs( new Vector3().setFromMatrixPosition( cap.cap.matrixWorld ).z ) < 1e-12 );
	oblique.dispose();

} );
