// Eyes in the eye openings: placement, gaze and blinks (web/src/core/eyes.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { approachAngle, blinkClosure, EYE_MOTION, eyeballPlacement, gazeBasis, gazeToward, lidPositions, nextBlinkDelay, restClosure } from '../../web/src/core/eyes.js';

const TOL = 1e-9;

/** A flat circular rim of radius `r` mm in the plane x = 0 about the origin, facing +x. */
function flatRim( r, n = 16 ) {

	const positions = new Float32Array( 3 * n );
	for ( let i = 0; i < n; i ++ ) positions.set( [ 0, r * Math.cos( 2 * Math.PI * i / n ), r * Math.sin( 2 * Math.PI * i / n ) ], 3 * i );
	return { positions, loop: [ ...Array( n ).keys() ], frame: { centre: [ 0, 0, 0 ], normal: [ 1, 0, 0 ] } };

}

test( 'an eyeball behind a round opening puts the rim on its surface, on the opening\'s normal', () => {

	const { positions, loop, frame } = flatRim( 9 );
	const eye = eyeballPlacement( positions, loop, frame, 12 );
	assert.equal( eye.radius, 12 );
	assert.ok( Math.abs( eye.depth - Math.sqrt( 144 - 81 ) ) < 1e-5 );
	assert.ok( Math.abs( eye.centre[ 0 ] + eye.depth ) < TOL && eye.centre[ 1 ] === 0 && eye.centre[ 2 ] === 0 );

} );

test( 'an opening wider than the eyeball never pulls it more than 0.45 radius out of the face', () => {

	const { positions, loop, frame } = flatRim( 30 );
	assert.ok( Math.abs( eyeballPlacement( positions, loop, frame, 12 ).depth - 0.55 * 12 ) < TOL );
	assert.throws( () => eyeballPlacement( positions, loop, frame, 0 ), /radius must be positive/ );

} );

test( 'two eyes tilted sideways look straight ahead between their normals', () => {

	const basis = gazeBasis( [ [ 0.97, 0, 0.24 ], [ 0.97, 0, - 0.24 ] ] );
	assert.deepEqual( basis.forward.map( ( x ) => Math.round( x * 1e9 ) / 1e9 + 0 ), [ 1, 0, 0 ] );
	assert.deepEqual( basis.up.map( ( x ) => Math.round( x * 1e9 ) / 1e9 + 0 ), [ 0, 1, 0 ] );
	assert.deepEqual( basis.side.map( ( x ) => Math.round( x * 1e9 ) / 1e9 + 0 ), [ 0, 0, 1 ] );

} );

test( 'the gaze turns toward a point within the limit, and clamps beyond it or behind the eyes', () => {

	const basis = gazeBasis( [ [ 1, 0, 0 ] ] );
	const out = [ NaN, NaN ];
	gazeToward( 100, 0, 100 * Math.tan( 10 * Math.PI / 180 ), [ 0, 0, 0 ], basis, 25, out );
	assert.ok( Math.abs( out[ 0 ] - 10 ) < 1e-9 && Math.abs( out[ 1 ] ) < 1e-9 );
	gazeToward( 100, 100, 0, [ 0, 0, 0 ], basis, 25, out );
	assert.deepEqual( out, [ 0, 25 ] );
	gazeToward( 100, 0, - 1000, [ 0, 0, 0 ], basis, 25, out );
	assert.deepEqual( out, [ - 25, 0 ] );
	assert.equal( gazeToward( - 100, 5, 5, [ 0, 0, 0 ], basis, 25, out ), out );
	assert.deepEqual( out, [ 0, 0 ] );

} );

test( 'the gaze approaches its target smoothly and then arrives exactly', () => {

	let angle = 20;
	const seen = [];
	for ( let frame = 0; frame < 60 && angle !== 0; frame ++ ) seen.push( angle = approachAngle( angle, 0, 1 / 60 ) );
	assert.equal( angle, 0 );
	for ( let i = 1; i < seen.length; i ++ ) assert.ok( seen[ i ] < seen[ i - 1 ] );
	assert.ok( seen.length > 5, 'not a jump' );

} );

test( 'a blink closes fully and opens again within its duration', () => {

	const d = EYE_MOTION.blinkDuration;
	assert.equal( blinkClosure( 0 ), 0 );
	assert.equal( blinkClosure( - 1 ), 0 );
	assert.equal( blinkClosure( d ), 0 );
	assert.ok( Math.abs( blinkClosure( EYE_MOTION.blinkClose * d ) - 1 ) < 1e-9 );
	assert.ok( blinkClosure( 0.2 * d ) > 0 && blinkClosure( 0.2 * d ) < 1 );
	assert.ok( blinkClosure( 0.9 * d ) > 0 && blinkClosure( 0.9 * d ) < 0.2 );

} );

test( 'blinks follow each other after 4 to 9 seconds', () => {

	assert.equal( nextBlinkDelay( 0 ), 4 );
	assert.equal( nextBlinkDelay( 0.5 ), 6.5 );
	assert.ok( nextBlinkDelay( 0.999 ) < 9 );

} );

test( 'the lid rests just over the top of the iris', () => {

	// Opening 9 mm up and 9 mm down: the lid edge 5.8 - 1.4 = 4.4 mm above the centre.
	assert.ok( Math.abs( restClosure( 9, - 9 ) - ( 9 - 4.4 ) / 18 ) < 1e-12 );
	assert.equal( restClosure( 2, - 9 ), 0 );
	assert.throws( () => restClosure( - 1, 1 ), /must be above/ );

} );

test( 'the lid wraps the eyeball with a gap and stays flat beyond it', () => {

	const flat = Float32Array.from( [ 0, 0, 0, 0, 0, 20 ] );
	const out = new Float32Array( 6 );
	lidPositions( flat, [ 1, 0, 0 ], { centre: [ - 6, 0, 0 ], radius: 12 }, 0.5, out );
	assert.ok( Math.abs( out[ 0 ] - 6.5 ) < 1e-6 );
	assert.deepEqual( Array.from( out.slice( 3 ) ), [ 0, 0, 20 ] );

} );
