// What may draw through the skin, without a browser: the electrodes' see-through pass and the
// lips against the skin passes' render orders, and the inside of the skin's depth writes.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BoxGeometry, NormalBlending, SphereGeometry } from 'three';

import { Electrodes, GHOST_RENDER_ORDER } from '../../web/src/scene/Electrodes.js';
import { Head } from '../../web/src/scene/Head.js';
import { LIP_RENDER_ORDER, SKIN_RENDER_ORDER } from '../../web/src/scene/skinPasses.js';

function loadedHead() {

	const head = new Head();
	head.addPart( { name: 'face_skin', role: 'skin' }, new SphereGeometry( 100, 24, 16 ) );
	head.addPart( { name: 'upper_lip', role: 'lip' }, new BoxGeometry( 10, 5, 30 ).translate( 40, 5, 0 ) );
	head.finishLoading();
	return head;

}

const pass = ( head, name ) => head.part( 'face_skin' ).meshes.find( ( mesh ) => mesh.userData.skinPass === name );
const lip = ( head ) => head.part( 'upper_lip' ).meshes[ 0 ];
const grid = { cells: 2, electrodes: [ { position: [ 10, 20, 5 ], normal: [ 0, - 1, 0 ], cell: 0 }, { position: [ 12, 20, - 5 ], normal: [ 0, - 1, 0 ], cell: 1 } ] };

test( 'the see-through electrodes are drawn in the opaque queue, after the anatomy and before the lips and the skin', () => {

	const electrodes = new Electrodes( grid );
	electrodes.setXray( true );
	for ( const ghost of [ electrodes.ghostDots, electrodes.ghostSquares ] ) {

		assert.equal( ghost.material.transparent, false, 'a transparent pass would be drawn after opaque skin' );
		assert.notEqual( ghost.material.blending, NormalBlending, 'it must still blend' );
		assert.ok( ghost.material.opacity > 0 && ghost.material.opacity < 1 );
		assert.equal( ghost.renderOrder, GHOST_RENDER_ORDER );

	}

	assert.ok( 0 < GHOST_RENDER_ORDER && GHOST_RENDER_ORDER < LIP_RENDER_ORDER && LIP_RENDER_ORDER < SKIN_RENDER_ORDER.back );
	electrodes.dispose();

} );

test( 'opaque lips and faded lips alike are drawn after the see-through electrodes', () => {

	const head = loadedHead();
	for ( const percent of [ 0, 40 ] ) {

		head.setTransparency( percent );
		assert.equal( lip( head ).renderOrder, LIP_RENDER_ORDER, `at ${ percent } %` );
		assert.equal( lip( head ).material.transparent, percent > 0 );

	}

} );

test( 'the inside of opaque skin writes depth only with the cut, where it is the section', () => {

	const head = loadedHead();
	head.setTransparency( 0 );
	assert.equal( pass( head, 'back' ).material.depthWrite, false );
	assert.equal( pass( head, 'front' ).material.depthWrite, true );
	head.setCutaway( true );
	assert.equal( pass( head, 'back' ).material.depthWrite, true );
	head.setTransparency( 40 );
	assert.equal( pass( head, 'back' ).material.depthWrite, false );

} );

test( 'the electrodes report where each is on the canvas', () => {

	const electrodes = new Electrodes( grid );
	const viewer = { screenRect: ( box ) => ( { x: box.min.x * 10, y: box.min.y * 10, width: 0, height: 0 } ) };
	const probe = electrodes.probe( viewer );
	assert.equal( probe.points.length, 2 );
	assert.deepEqual( probe.points[ 1 ], { point: [ 12, 20, - 5 ], x: 120, y: 200 } );
	electrodes.dispose();

} );
