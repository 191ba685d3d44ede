// The track sampling kernel (web/src/core/trackSampling.js): linear interpolation of every track at
// a time t into the parameter array, checked on small exact cases and on seeded random tracks
// against a naive reference, and shown to allocate nothing per call.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { packTracks, sampleTracks, trackDuration } from '../../web/src/core/trackSampling.js';
import { fewestGarbageCollections, garbageCollections } from './support/garbage.js';

/** float32 storage against the float64 reference. */
const TOL = 1e-5; // absolute: float32 carries values up to 10 to about 1e-6

/** The naive reference: per track, the two frames around t and a lerp, in float64. */
function naiveSample( tracks, rateHz, t ) {

	const out = {};
	for ( const [ name, track ] of Object.entries( tracks ) ) {

		const f = Math.min( Math.max( t * rateHz, 0 ), track.length - 1 );
		const i = Math.floor( f );
		const j = Math.min( i + 1, track.length - 1 );
		out[ name ] = track[ i ] + ( f - i ) * ( track[ j ] - track[ i ] );

	}

	return out;

}

function random( seed ) {

	let state = seed >>> 0;
	return () => {

		state = ( Math.imul( state, 1664525 ) + 1013904223 ) >>> 0;
		return state / 2 ** 32;

	};

}

test( 'halfway between two frames a track takes the mean of their values', () => {

	const packed = packTracks( { jaw_opening: [ 0, 10, 20 ], lip_rounding: [ 1, 1, 3 ] }, 100, [ 'jaw_opening', 'lip_rounding' ] );
	const target = new Float32Array( 2 );
	sampleTracks( packed, 0.005, target );
	assert.deepEqual( Array.from( target ), [ 5, 1 ] );
	sampleTracks( packed, 0.015, target );
	assert.deepEqual( Array.from( target ), [ 15, 2 ] );

} );

test( 'before the first frame and after the last the end values hold', () => {

	const packed = packTracks( { a: [ 2, 4 ] }, 10, [ 'a' ] );
	const target = new Float32Array( 1 );
	sampleTracks( packed, - 1, target );
	assert.equal( target[ 0 ], 2 );
	sampleTracks( packed, 5, target );
	assert.equal( target[ 0 ], 4 );
	sampleTracks( packed, NaN, target );
	assert.equal( target[ 0 ], 2 );
	assert.equal( trackDuration( packed ), 0.1 );

} );

test( 'tracks go to their slots in the target, and parameters without a track keep their value', () => {

	const names = [ 'tip_height', 'jaw_opening', 'velum_opening' ];
	const packed = packTracks( { velum_opening: [ 0.5, 0.5 ], tip_height: [ 3, 3 ], unknown: [ 9, 9 ] }, 100, names );
	assert.deepEqual( packed.names, [ 'tip_height', 'velum_opening' ] );
	const target = Float32Array.of( 0, 7, 0 );
	sampleTracks( packed, 0.004, target );
	assert.deepEqual( Array.from( target ), [ 3, 7, 0.5 ] );

} );

test( 'sampled values are clamped into each parameter\'s range', () => {

	const packed = packTracks( { a: [ - 5, 5 ] }, 1, [ 'a' ], { minimum: Float32Array.of( - 1 ), maximum: Float32Array.of( 2 ) } );
	const target = new Float32Array( 1 );
	sampleTracks( packed, 0, target );
	assert.equal( target[ 0 ], - 1 );
	sampleTracks( packed, 1, target );
	assert.equal( target[ 0 ], 2 );

} );

test( 'tracks of unequal length, no usable track or no rate are refused naming the problem', () => {

	assert.throws( () => packTracks( { a: [ 1, 2 ], b: [ 1 ] }, 100, [ 'a', 'b' ] ), /"b" has 1 frames, not 2/ );
	assert.throws( () => packTracks( { c: [ 1 ] }, 100, [ 'a' ] ), /no track for any parameter \(tracks: c\)/ );
	assert.throws( () => packTracks( { a: [ 1 ] }, 0, [ 'a' ] ), /positive rate/ );

} );

test( 'seeded random tracks sample as the naive reference does at random times', () => {

	const seed = 1993;
	const next = random( seed );
	const names = Array.from( { length: 37 }, ( _, k ) => `p${ k }` );
	const frames = 240;
	const tracks = Object.fromEntries( names.map( ( name ) => [ name, Array.from( { length: frames }, () => 20 * next() - 10 ) ] ) );
	const rateHz = 100;
	const packed = packTracks( tracks, rateHz, names );
	const target = new Float32Array( names.length );
	for ( let s = 0; s < 500; s ++ ) {

		const t = 2.6 * next() - 0.1;
		sampleTracks( packed, t, target );
		const expected = naiveSample( tracks, rateHz, t );
		names.forEach( ( name, k ) => {

			assert.ok( Math.abs( target[ k ] - expected[ name ] ) <= TOL, `seed ${ seed }, t ${ t }, ${ name }: ${ target[ k ] } against ${ expected[ name ] }` );

		} );

	}

} );

test( 'sampling allocates nothing: thousands of samples trigger no garbage collection', async () => {

	const names = Array.from( { length: 40 }, ( _, k ) => `p${ k }` );
	const tracks = Object.fromEntries( names.map( ( name, k ) => [ name, Array.from( { length: 300 }, ( _, i ) => Math.sin( i / 10 + k ) ) ] ) );
	const packed = packTracks( tracks, 100, names );
	const target = new Float32Array( names.length );
	const frames = 200_000;
	const run = () => {

		for ( let i = 0; i < frames; i ++ ) sampleTracks( packed, i * 1.3e-5, target );

	};

	run(); // let the JIT settle
	const quiet = await fewestGarbageCollections( run );
	// The same loop with the naive reference shows that the probe does see allocation.
	const noisy = await garbageCollections( () => {

		for ( let i = 0; i < frames / 10; i ++ ) naiveSample( tracks, 100, i * 1.3e-4 );

	} );
	assert.equal( quiet, 0, `${ quiet } collections during ${ frames } samples` );
	assert.ok( noisy > 0, 'allocating per sample should trigger collections' );

} );
