// The keyboard and the tablet layout, without a browser: which key turns or zooms the 3D view and
// by how much, how far an arrow moves a workbench slider, and which corner the EPG card takes.

import assert from 'node:assert/strict';
import { test } from 'node:test';
import { keyMove, ROTATE_STEP_DEG, ZOOM_FACTOR } from '../../web/src/scene/keyboardOrbit.js';
import { arrowValue, keyStep } from '../../web/src/ui/workbench/ParameterPanel.js';
import { chooseCorner, cornerRect, overlapArea } from '../../web/src/ui/shared/epgCardPlacement.js';

const STEP = ROTATE_STEP_DEG * Math.PI / 180;

test( 'the arrow keys turn the camera by a fixed step, four times that with Shift', () => {

	assert.deepEqual( keyMove( 'ArrowLeft' ), { theta: - STEP } );
	assert.deepEqual( keyMove( 'ArrowRight' ), { theta: STEP } );
	assert.deepEqual( keyMove( 'ArrowUp' ), { phi: - STEP } );
	assert.ok( Math.abs( keyMove( 'ArrowDown', true ).phi - 4 * STEP ) < 1e-12 );

} );

test( 'plus zooms in and minus zooms out by the same factor; other keys do nothing', () => {

	assert.ok( Math.abs( keyMove( '+' ).zoom * ZOOM_FACTOR - 1 ) < 1e-12 );
	assert.equal( keyMove( '=' ).zoom, keyMove( '+' ).zoom );
	assert.equal( keyMove( '-' ).zoom, ZOOM_FACTOR );
	assert.equal( keyMove( 'a' ), null );
	assert.equal( keyMove( 'Tab' ), null );

} );

test( 'an arrow press crosses any parameter range in at most 100 presses and at least 40', () => {

	for ( const [ min, max ] of [ [ - 4, 10 ], [ 0, 25 ], [ 0, 50 ], [ - 3, 3 ], [ 0, 4 ], [ 0, 1 ], [ - 1, 1 ], [ 0, 0.8 ] ] ) {

		const presses = ( max - min ) / keyStep( { min, max } );
		assert.ok( presses <= 100 + 1e-9 && presses >= 40 - 1e-9, `${ min }..${ max }: ${ presses } presses` );

	}

	assert.equal( keyStep( { min: - 3, max: 3 } ), 0.1 );
	assert.equal( keyStep( { min: 0, max: 25 } ), 0.5 );
	assert.equal( keyStep( { min: 1, max: 1 } ), 1 );

} );

test( 'an arrow press moves a slider one key step and stops at the ends of the range', () => {

	const p = { min: - 3, max: 3 };
	assert.ok( Math.abs( arrowValue( p, 0, 'ArrowRight' ) - 0.1 ) < 1e-9 );
	assert.ok( Math.abs( arrowValue( p, 0, 'ArrowDown' ) + 0.1 ) < 1e-9 );
	assert.equal( arrowValue( p, 2.95, 'ArrowUp' ), 3 );
	assert.equal( arrowValue( p, - 3, 'ArrowLeft' ), - 3 );
	assert.equal( arrowValue( p, 0, 'PageUp' ), null );

} );

test( 'the EPG card stays bottom left unless the lips are there, then takes the next clear corner', () => {

	const stage = { x: 0, y: 0, width: 768, height: 500 };
	const card = { width: 188, height: 230 };
	assert.deepEqual( cornerRect( 'bottom-left', stage, card, 16 ), { x: 16, y: 254, width: 188, height: 230 } );
	assert.deepEqual( cornerRect( 'top-right', stage, card, 16 ), { x: 564, y: 16, width: 188, height: 230 } );
	assert.equal( chooseCorner( stage, card, { x: 300, y: 200, width: 100, height: 60 } ), 'bottom-left' );
	assert.equal( chooseCorner( stage, card, { x: 150, y: 300, width: 100, height: 60 } ), 'top-left' );
	assert.equal( chooseCorner( stage, card, { x: 150, y: 200, width: 100, height: 60 } ), 'bottom-right' );
	assert.equal( chooseCorner( stage, card, null ), 'bottom-left' );
	// Lips across the whole stage: the corner that covers least of them.
	const everywhere = { x: 100, y: 0, width: 668, height: 500 };
	const corner = chooseCorner( stage, card, everywhere );
	assert.equal( corner, 'bottom-left' );
	assert.ok( overlapArea( cornerRect( corner, stage, card ), everywhere ) < card.width * card.height );

} );

test( 'with the velum in section too, the card takes the corner clear of the lips that covers least of the velum', () => {

	const stage = { x: 0, y: 0, width: 768, height: 500 };
	const card = { width: 188, height: 230 };
	const lips = { x: 100, y: 330, width: 80, height: 60 }; // bottom left
	const velum = { x: 560, y: 180, width: 120, height: 140 }; // right, lower half
	assert.equal( chooseCorner( stage, card, lips ), 'top-left' );
	assert.equal( chooseCorner( stage, card, lips, 16, velum ), 'top-left' );
	const nose = { x: 40, y: 40, width: 160, height: 120 }; // lips at the top left instead
	assert.equal( chooseCorner( stage, card, nose, 16, velum ), 'bottom-left', 'clear of both' );
	assert.equal( chooseCorner( stage, card, { x: 0, y: 0, width: 300, height: 500 }, 16, { x: 560, y: 0, width: 208, height: 260 } ), 'bottom-right', 'the lips first, then the velum' );

} );
