// How the skin and lips are drawn at each transparency (web/src/scene/skinPasses.js), and the
// frame timer behind window.glasshead.frameTimeMs (web/src/scene/FrameTimer.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { LIP_FADE, lipOpacity, SKIN_RENDER_ORDER, skinPassState } from '../../web/src/scene/skinPasses.js';
import { FrameTimer } from '../../web/src/scene/FrameTimer.js';

test( 'at 0 % the skin is an ordinary opaque surface that writes depth', () => {

	assert.deepEqual( skinPassState( 0 ), { visible: true, transparent: false, opacity: 1, depthWrite: true, prepass: false, rim: 0 } );

} );

test( 'at 100 % the skin is not drawn at all', () => {

	const state = skinPassState( 100 );
	assert.equal( state.visible, false );
	assert.equal( state.opacity, 0 );

} );

test( 'in between, the skin blends without writing depth, after a depth pre-pass', () => {

	let previous = 1;
	for ( let percent = 1; percent < 100; percent += 7 ) {

		const state = skinPassState( percent );
		assert.equal( state.transparent, true );
		assert.equal( state.depthWrite, false );
		assert.equal( state.prepass, true );
		assert.ok( Math.abs( state.opacity - ( 1 - percent / 100 ) ) < 1e-12 );
		assert.ok( state.opacity < previous );
		assert.ok( state.rim > 0 && state.rim <= 1 );
		previous = state.opacity;

	}

} );

test( 'the skin passes are drawn back faces, then depth, then front faces', () => {

	assert.ok( SKIN_RENDER_ORDER.back < SKIN_RENDER_ORDER.prepass && SKIN_RENDER_ORDER.prepass < SKIN_RENDER_ORDER.front );

} );

test( 'a transparency outside 0 to 100 or not a number is refused', () => {

	for ( const bad of [ - 1, 100.5, Number.NaN, '50', null, Infinity ] ) assert.throws( () => skinPassState( bad ), RangeError );
	assert.throws( () => lipOpacity( 101 ), RangeError );

} );

test( 'the lips fade with the skin but never vanish', () => {

	assert.equal( lipOpacity( 0 ), 1 );
	assert.ok( Math.abs( lipOpacity( 100 ) - ( 1 - LIP_FADE ) ) < 1e-12 );
	assert.ok( lipOpacity( 100 ) > 0 && lipOpacity( 50 ) < 1 );

} );

test( 'the frame timer reports the median of the most recent frames', () => {

	const timer = new FrameTimer( 5 );
	assert.equal( timer.median(), null );
	for ( const ms of [ 10, 30, 20 ] ) timer.add( ms );
	assert.equal( timer.median(), 20 );
	timer.add( 40 );
	assert.equal( timer.median(), 25 );
	// Older samples fall out of the window of 5.
	for ( const ms of [ 100, 100, 100, 100 ] ) timer.add( ms );
	assert.equal( timer.median(), 100 );
	// Non-finite or negative times are ignored.
	timer.add( Number.NaN );
	timer.add( - 5 );
	timer.add( Infinity );
	assert.equal( timer.median(), 100 );
	assert.throws( () => new FrameTimer( 0 ), RangeError );

} );
