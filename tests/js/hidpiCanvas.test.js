// The HiDPI canvas of the panels and plots (web/src/ui/shared/hidpiCanvas.js), on a stand-in
// document whose canvases record what is done to their 2D context.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { canvasPixelRatio, HiDpiCanvas, MAX_PIXEL_RATIO } from '../../web/src/ui/shared/hidpiCanvas.js';

/** A document whose canvases keep their attributes, style and the calls on their context. */
function fakeDocument() {

	return {
		createElement: () => {

			const calls = [];
			const ctx = { setTransform: ( ...a ) => calls.push( [ 'setTransform', ...a ] ), clearRect: ( ...a ) => calls.push( [ 'clearRect', ...a ] ) };
			const attributes = {};
			return { calls, style: {}, attributes, setAttribute: ( k, v ) => ( attributes[ k ] = v ), getContext: ( kind ) => ( kind === '2d' ? ctx : null ) };

		},
	};

}

test( 'a canvas is sized in CSS pixels and drawn at the device pixel ratio, at most 2', ( t ) => {

	t.after( () => delete globalThis.devicePixelRatio );
	globalThis.devicePixelRatio = 1.5;
	const canvas = new HiDpiCanvas( { width: 301, height: 170, ariaLabel: 'Dominance', className: 'sp-canvas', document: fakeDocument() } );
	const element = canvas.element;
	assert.equal( element.className, 'sp-canvas' );
	assert.deepEqual( element.attributes, { role: 'img', 'aria-label': 'Dominance' } );
	assert.deepEqual( [ element.style.width, element.style.height, element.width, element.height ], [ '301px', '170px', 452, 255 ] );
	assert.deepEqual( element.calls, [ [ 'setTransform', 1.5, 0, 0, 1.5, 0, 0 ] ] );
	assert.equal( canvas.ctx, element.getContext( '2d' ) );

	canvas.resize( 400 );
	assert.deepEqual( [ canvas.width, canvas.height, element.width, element.height ], [ 400, 170, 600, 255 ] );
	element.calls.length = 0;
	assert.equal( canvas.clear(), canvas.ctx );
	assert.deepEqual( element.calls, [ [ 'setTransform', 1.5, 0, 0, 1.5, 0, 0 ], [ 'clearRect', 0, 0, 400, 170 ] ] );

	globalThis.devicePixelRatio = 3;
	assert.equal( canvasPixelRatio(), MAX_PIXEL_RATIO );
	delete globalThis.devicePixelRatio;
	assert.equal( canvasPixelRatio(), 1 );

} );

test( 'without a 2D context there is nothing to draw into, and no error', () => {

	const document = { createElement: () => ( { style: {}, setAttribute: () => {}, getContext: () => null } ) };
	const canvas = new HiDpiCanvas( { width: 10, height: 10, document } );
	assert.equal( canvas.ctx, null );
	assert.equal( canvas.clear(), null );

} );
