// The speech player's pure parts: the clock (ui/speak/speechClock.js) with a fake audio element and a
// fake time source, the phone lookup against a linear scan, the request built from what was typed
// (ui/speak/SpeechControls.js) and the dominance plot drawn through a recording 2D context.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { phoneIndexAt, SpeechClock } from '../../web/src/ui/speak/speechClock.js';
import { utteranceRequest } from '../../web/src/ui/speak/SpeechControls.js';
import { drawDominance } from '../../web/src/ui/speak/DominancePlot.js';

/** Seconds compared to this (float sums of milliseconds). */
const TOL = 1e-9;

/** An audio element's surface: time moves only when the test says so. */
function fakeAudio() {

	return {
		currentTime: 0, paused: true, ended: false, playbackRate: 1, preservesPitch: false, plays: 0,
		play() {

			this.paused = false;
			this.plays ++;
			return Promise.resolve();

		},
		pause() {

			this.paused = true;

		},
	};

}

function setUp( { audio = fakeAudio(), duration = 1, hasAudio = true } = {} ) {

	const clock = { ms: 1000 };
	const speech = new SpeechClock( { audio, now: () => clock.ms } );
	speech.load( duration, 100, hasAudio );
	return { speech, audio, clock };

}

test( 'while the audio plays its currentTime is the clock, whatever the page\'s time says', () => {

	const { speech, audio, clock } = setUp();
	speech.play();
	assert.equal( audio.paused, false );
	audio.currentTime = 0.37;
	clock.ms += 5000; // the page's clock would say 5 s
	assert.ok( Math.abs( speech.update() - 0.37 ) < TOL );
	assert.equal( speech.source, 'audio' );

} );

test( 'without audio the page\'s clock runs at the chosen speed', () => {

	const { speech, clock } = setUp( { hasAudio: false } );
	speech.setSpeed( 0.25 );
	speech.play();
	clock.ms += 400;
	assert.ok( Math.abs( speech.update() - 0.1 ) < TOL );
	assert.equal( speech.source, 'page' );

} );

test( 'slow motion sets the audio\'s playbackRate with its pitch kept, within 0.1x to 1x', () => {

	const { speech, audio } = setUp();
	assert.equal( speech.setSpeed( 0.5 ), 0.5 );
	assert.deepEqual( [ audio.playbackRate, audio.preservesPitch ], [ 0.5, true ] );
	assert.equal( speech.setSpeed( 0.01 ), 0.1 );
	assert.equal( speech.setSpeed( 3 ), 1 );
	assert.equal( audio.playbackRate, 1 );

} );

test( 'playing stops at the end, and starts again from 0 when looping', () => {

	const { speech, audio, clock } = setUp( { hasAudio: false } );
	speech.play();
	clock.ms += 1500;
	assert.equal( speech.update(), 1 );
	assert.equal( speech.playing, false );
	speech.setLoop( true );
	speech.play(); // from the start, being at the end
	clock.ms += 1200;
	assert.equal( speech.update(), 0 );
	assert.equal( speech.playing, true );
	clock.ms += 300;
	assert.ok( Math.abs( speech.update() - 0.3 ) < TOL );
	assert.equal( audio.plays, 0, 'no audio asked for' );

} );

test( 'a frame step pauses and moves one frame of the tracks; the audio follows', () => {

	const { speech, audio } = setUp();
	speech.seek( 0.5 );
	speech.play();
	assert.ok( Math.abs( speech.step( 1 ) - 0.51 ) < TOL );
	assert.equal( speech.playing, false );
	assert.equal( audio.paused, true );
	assert.ok( Math.abs( audio.currentTime - 0.51 ) < TOL );
	speech.step( - 3 );
	assert.equal( speech.frame, 48 );
	assert.equal( speech.seek( 7 ), 1, 'clamped to the end' );
	assert.equal( speech.seek( - 1 ), 0 );

} );

test( 'audio the browser refuses to play leaves the page\'s clock running', async () => {

	const audio = { ...fakeAudio(), play() {

		return Promise.reject( new Error( 'play() failed because the user didn\'t interact' ) );

	} };
	const { speech, clock } = setUp( { audio } );
	speech.play();
	await Promise.resolve();
	await Promise.resolve();
	assert.match( speech.audioError, /interact/ );
	clock.ms += 200;
	assert.ok( Math.abs( speech.update() - 0.2 ) < TOL );

} );

test( 'the phone at a time is found as a linear scan finds it, ends included', () => {

	const phones = [ 0, 0.05, 0.12, 0.3, 0.31, 0.6 ].map( ( start, k, all ) => ( { start_s: start, end_s: all[ k + 1 ] ?? 0.8 } ) );
	for ( let t = - 0.1; t < 1; t += 0.0037 ) {

		let expected = - 1;
		phones.forEach( ( p, k ) => {

			if ( p.start_s <= t ) expected = k;

		} );
		assert.equal( phoneIndexAt( phones, t ), Math.max( expected, 0 ), `t ${ t }` );

	}

	assert.equal( phoneIndexAt( [], 0.1 ), - 1 );

} );

test( 'what is typed between slashes is phonemes, anything else text, with the audio asked for', () => {

	assert.deepEqual( utteranceRequest( ' /M AA/ ', { kind: 'natural' } ), { phonemes: 'M AA', audio: { kind: 'natural' }, dominance: true } );
	assert.deepEqual( utteranceRequest( 'stew', { kind: 'lowpass', cutoff_hz: 500, channels: 4 } ), { text: 'stew', audio: { kind: 'lowpass', cutoff_hz: 500 }, dominance: true } );
	assert.deepEqual( utteranceRequest( 'key', { kind: 'vocoded', cutoff_hz: 500, channels: 8 } ).audio, { kind: 'vocoded', channels: 8 } );
	assert.equal( utteranceRequest( '   ', { kind: 'none' } ), null );

} );

test( 'the dominance plot draws one curve per phone, the parameter\'s track and the playhead', () => {

	const calls = [];
	const ctx = new Proxy( {}, {
		get: ( target, name ) => ( name in target ? target[ name ] : ( ...args ) => calls.push( [ name, ...args ] ) ),
		set: ( target, name, value ) => {

			target[ name ] = value;
			return true;

		},
	} );
	const utterance = {
		duration_s: 0.3, rate_hz: 10,
		phones: [ { symbol: 'M', ipa: 'm', start_s: 0, end_s: 0.1 }, { symbol: 'AA', ipa: 'ɑ', start_s: 0.1, end_s: 0.3 } ],
		tracks: { lip_opening: [ 0, 0.5, 1, 1 ] },
		dominance: { parameters: { lip_opening: 'lip_closure' }, groups: { lip_closure: [ [ 1, 0.5, 0.1, 0 ], [ 0, 0.2, 0.4, 0.4 ] ] } },
	};
	drawDominance( ctx, { utterance, parameter: 'lip_opening', time: 0.15, range: { min: 0, max: 1 } }, { width: 306, height: 124 } );
	const strokes = calls.filter( ( [ name ] ) => name === 'stroke' ).length;
	assert.equal( strokes, 2 + 2 + 1 + 1, 'two boundaries, two curves, the track, the playhead' );
	assert.deepEqual( calls.filter( ( [ name ] ) => name === 'fillText' ).map( ( c ) => c[ 1 ] ), [ 'm', 'ɑ' ] );
	// The playhead at 0.15 of 0.3 s: halfway across the 294 px plot, from x 6.
	assert.ok( calls.some( ( [ name, x ] ) => name === 'moveTo' && Math.abs( x - 153 ) < 1e-9 ) );
	// The track's last point: 1 at the top of the plot (y 8).
	assert.ok( calls.some( ( [ name, x, y ] ) => name === 'lineTo' && Math.abs( x - ( 6 + 294 * 0.3 / 0.3 ) ) < 1e-9 && Math.abs( y - 8 ) < 1e-9 ) );

} );
