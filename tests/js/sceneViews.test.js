// Camera poses of the named views and the flight between them (web/src/scene/viewPresets.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { easeInOut, fitDistance, interpolatePose, MOUTH_AND_THROAT, VIEW_ELEVATION_DEG, VIEW_NAMES, viewDirection, viewPose, zoomedPose } from '../../web/src/scene/viewPresets.js';

const close = ( actual, expected, tolerance = 1e-9 ) => assert.ok( Math.abs( actual - expected ) <= tolerance, `${ actual } is not ${ expected }` );
const length = ( v ) => Math.hypot( v[ 0 ], v[ 1 ], v[ 2 ] );
const offset = ( pose ) => pose.position.map( ( p, i ) => p - pose.target[ i ] );

test( 'the front camera looks at the face from +x (anterior)', () => {

	const [ x, y, z ] = viewDirection( 'front' );
	close( x, Math.cos( VIEW_ELEVATION_DEG * Math.PI / 180 ) );
	close( y, Math.sin( VIEW_ELEVATION_DEG * Math.PI / 180 ) );
	close( z, 0 );

} );

test( 'the profile camera sits on -z, facing the cut face of the kept left half', () => {

	const [ x, , z ] = viewDirection( 'profile' );
	close( x, 0 );
	assert.ok( z < - 0.9, `profile z is ${ z }` );

} );

test( 'the three-quarter camera lies halfway between front and profile', () => {

	const [ x, , z ] = viewDirection( 'three-quarter' );
	close( x, - z );
	assert.ok( x > 0.6 );

} );

test( 'every view direction is a unit vector and an unknown view is refused', () => {

	for ( const name of VIEW_NAMES ) close( length( viewDirection( name ) ), 1, 1e-12 );
	assert.throws( () => viewDirection( 'top' ), /unknown view "top"/ );

} );

test( 'the fitted distance keeps the bounding sphere inside the narrower field of view', () => {

	const radius = 100;
	const d = fitDistance( radius, 30, 1, 1 );
	close( radius / d, Math.sin( 15 * Math.PI / 180 ), 1e-12 );
	// A portrait view is limited by its width, so the camera moves back.
	assert.ok( fitDistance( radius, 30, 0.5 ) > fitDistance( radius, 30, 1 ) );
	close( fitDistance( radius, 30, 2 ), fitDistance( radius, 30, 1 ), 1e-9 ); // a wide view: the height limits
	assert.throws( () => fitDistance( 0, 30 ), RangeError );
	assert.throws( () => fitDistance( 10, 180 ), RangeError );

} );

test( 'a view pose is the view direction times the fitted distance from the centre', () => {

	const pose = viewPose( 'front', [ 10, 20, 0 ], 100, 30, 1 );
	assert.deepEqual( pose.target, [ 10, 20, 0 ] );
	close( length( offset( pose ) ), fitDistance( 100, 30, 1 ), 1e-9 );
	assert.ok( pose.position[ 0 ] > 10 + 300 );

} );

test( 'a zoomed pose comes closer by the zoom and turns onto the oral cavity, which it reaches at zoom 2', () => {

	const whole = zoomedPose( 'profile', 1, 40, 1.5 );
	assert.deepEqual( whole, viewPose( 'profile', MOUTH_AND_THROAT.center, MOUTH_AND_THROAT.radius, 40, 1.5 ) );
	for ( const zoom of [ 1.5, 2, 2.5 ] ) {

		const pose = zoomedPose( 'profile', zoom, 40, 1.5 );
		close( length( offset( pose ) ) * zoom, length( offset( whole ) ), 1e-6 );
		assert.ok( pose.target[ 1 ] > whole.target[ 1 ], 'up, toward the palate' );

	}

	assert.deepEqual( zoomedPose( 'profile', 2, 40, 1.5 ).target, zoomedPose( 'profile', 2.5, 40, 1.5 ).target );
	assert.deepEqual( zoomedPose( 'front', 0.2, 40, 1.5 ), zoomedPose( 'front', 1, 40, 1.5 ), 'never farther than zoom 1' );

} );

test( 'a flight starts and ends exactly at its poses', () => {

	const a = viewPose( 'front', [ 0, 0, 0 ], 100, 30 );
	const b = viewPose( 'profile', [ 5, 0, 0 ], 120, 30 );
	const out = { position: [ 0, 0, 0 ], target: [ 0, 0, 0 ] };
	interpolatePose( a, b, 0, out );
	a.position.forEach( ( v, i ) => close( out.position[ i ], v, 1e-9 ) );
	interpolatePose( a, b, 1, out );
	b.position.forEach( ( v, i ) => close( out.position[ i ], v, 1e-9 ) );
	b.target.forEach( ( v, i ) => close( out.target[ i ], v, 1e-9 ) );

} );

test( 'a flight swings around the head instead of cutting through it', () => {

	const a = viewPose( 'front', [ 0, 0, 0 ], 100, 30 );
	const b = viewPose( 'profile', [ 0, 0, 0 ], 100, 30 );
	const out = { position: [ 0, 0, 0 ], target: [ 0, 0, 0 ] };
	const distance = length( a.position );
	for ( let s = 0; s <= 1; s += 0.125 ) {

		interpolatePose( a, b, s, out );
		close( length( out.position ), distance, 1e-6 );

	}

	// Halfway, the camera is at the three-quarter azimuth (x = -z).
	interpolatePose( a, b, 0.5, out );
	close( out.position[ 0 ], - out.position[ 2 ], 1e-9 );

} );

test( 'the easing is monotonic from 0 to 1 and clamps outside', () => {

	let previous = - 1;
	for ( let s = 0; s <= 1; s += 0.05 ) {

		const e = easeInOut( s );
		assert.ok( e >= previous );
		previous = e;

	}

	assert.equal( easeInOut( 0 ), 0 );
	assert.equal( easeInOut( 1 ), 1 );
	close( easeInOut( 0.5 ), 0.5, 1e-15 );
	assert.equal( easeInOut( - 3 ), 0 );
	assert.equal( easeInOut( 7 ), 1 );

} );
