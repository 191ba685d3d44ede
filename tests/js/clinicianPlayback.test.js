// The clinician view's playback clock (web/src/ui/clinician/playbackClock.js) on a stand-in time source and
// scheduler: frames come at their own times, times the speed, and playing ends on the last one.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { PlaybackClock } from '../../web/src/ui/clinician/playbackClock.js';

/** A clock on manual time: advance( ms ) moves time on and runs the tick that was scheduled. */
function manualClock() {

	let now = 1000;
	let pending = null;
	const frames = [];
	let stops = 0;
	const clock = new PlaybackClock( {
		onFrame: ( frame ) => frames.push( frame ),
		onStop: () => stops ++,
		now: () => now,
		schedule: ( tick ) => ( pending = tick, 1 ),
		cancel: () => ( pending = null ),
	} );
	const advance = ( ms ) => {

		now += ms;
		const tick = pending;
		pending = null;
		tick?.( now );

	};

	return { clock, frames, advance, stops: () => stops, pending: () => pending !== null };

}

/** Frames every 10 ms: 0, 0.01, ..., 0.09 s. */
const TIMES = Float64Array.from( { length: 10 }, ( _, i ) => i / 100 );

test( 'frames show at their own times and playing stops on the last one', () => {

	const { clock, frames, advance, stops, pending } = manualClock();
	assert.equal( clock.play( TIMES, 0 ), 0 );
	assert.equal( clock.playing, true );
	advance( 5 );
	assert.deepEqual( frames, [], 'still the first frame after 5 ms' );
	advance( 10 );
	advance( 10 );
	assert.deepEqual( frames, [ 1, 2 ] );
	advance( 100 );
	assert.deepEqual( frames, [ 1, 2, 9 ], 'a late tick jumps to the frame showing then' );
	assert.equal( clock.playing, false );
	assert.equal( stops(), 1 );
	assert.equal( pending(), false, 'nothing is scheduled after the end' );

} );

test( 'half speed takes twice as long, and a speed change keeps the time played so far', () => {

	const { clock, frames, advance } = manualClock();
	clock.play( TIMES, 0, 0.5 );
	advance( 30 );
	assert.deepEqual( frames, [ 1 ], '30 ms at half speed is 15 ms of the recording' );
	clock.setSpeed( 1 );
	advance( 10 );
	assert.deepEqual( frames, [ 1, 2 ], '15 ms then 10 ms at full speed' );

} );

test( 'playing starts from the frame shown, or from the first when that is the last', () => {

	const { clock, frames, advance } = manualClock();
	assert.equal( clock.play( TIMES, 4 ), 4 );
	advance( 10 );
	assert.deepEqual( frames, [ 5 ] );
	clock.pause();
	assert.equal( clock.play( TIMES, 9 ), 0 );

} );

test( 'pause stops the ticks; there is nothing to play with fewer than two frames', () => {

	const { clock, frames, advance, stops, pending } = manualClock();
	clock.play( TIMES, 0 );
	clock.pause();
	assert.equal( pending(), false );
	assert.equal( stops(), 1 );
	advance( 50 );
	assert.deepEqual( frames, [] );
	clock.pause( { silent: true } );
	assert.equal( stops(), 1, 'pausing a stopped clock says nothing' );
	assert.equal( clock.play( Float64Array.of( 0 ), 0 ), - 1 );
	assert.equal( clock.play( null, 0 ), - 1 );
	assert.equal( clock.playing, false );

} );
