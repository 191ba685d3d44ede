// A lesson item on the speech player (ui/lessons/LessonRunnerViews.js's ItemPresenter), against a stand-in
// for SpeechView that records what it is asked: the views set before the target is said, the
// request for the target, the item's speed, a static item held on its first spoken phone and held
// again when played to its end, replays counted, and a newer item winning over a slower older one.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { firstSpokenPhone, ItemPresenter } from '../../web/src/ui/lessons/LessonRunnerViews.js';

/** Just enough of a mounted SpeechView, with its calls in `log`. */
function fakeView( { sayDelays = [] } = {} ) {

	const log = [];
	const hooks = [];
	let says = 0;
	const view = {
		log, hooks, ready: Promise.resolve( true ), busy: false, utterance: null, landmarks: null, panels: null, unregister: [],
		state: { skin: false, transparency: 70, cutaway: true, hold: null },
		root: { classList: { toggle: ( name, on ) => log.push( [ 'class', name, on ] ) } },
		epg: { panel: { hidden: false }, electrodes: { group: { visible: true } } },
		viewer: {
			requestRender() {}, onFrame: ( hook ) => ( hooks.push( hook ), () => hooks.splice( hooks.indexOf( hook ), 1 ) ),
			camera: { fov: 40 }, aspect: 1.5, animating: false, flyTo: ( pose, ms ) => log.push( [ 'fly', pose.target.map( Math.round ), ms ] ),
		},
		clock: { playing: false, time: 0, duration: 0.6, pause() {

			this.playing = false;

		} },
		apply: () => log.push( [ 'apply', view.state.skin, view.state.transparency, view.state.cutaway ] ),
		async say( body ) {

			const delay = sayDelays[ says ++ ] ?? 0;
			log.push( [ 'say', body ] );
			await new Promise( ( resolve ) => setTimeout( resolve, delay ) );
			view.utterance = { phones: body.phones ?? [ { symbol: 'sil' }, { symbol: body.phonemes ?? 'W' }, { symbol: 'sil' } ] };

		},
		setSpeed: ( speed ) => log.push( [ 'speed', speed ] ),
		goToPhone: ( index ) => log.push( [ 'goTo', index ] ),
		async holdCurrent() {

			view.state.hold = 'held';
			log.push( [ 'hold' ] );

		},
		seek: ( t ) => log.push( [ 'seek', t ] ),
		togglePlay() {

			view.state.hold = null;
			view.clock.playing = ! view.clock.playing;
			log.push( [ 'toggle', view.clock.playing ] );

		},
	};
	return view;

}

const phoneme = { target: { kind: 'phoneme', text: 'S' }, presentation: 'static', views: { skin_transparency: 0.8, epg: false, zoom: 2 }, speed: 1 };
/** The inventory as GET /phonemes gives it, for the one sound the tests say. */
const inventory = async () => new Map( [ [ 'S', { ipa: 's', arpabet: 'S', manner: 'fricative' } ] ] );
const presenterOf = ( view ) => new ItemPresenter( view, { inventory } );
const word = { target: { kind: 'word', text: 'sip' }, speed: 0.5 };

test( 'the first spoken phone is the first that is not silence', () => {

	assert.equal( firstSpokenPhone( [ { symbol: 'sil' }, { symbol: 'S' } ] ), 1 );
	assert.equal( firstSpokenPhone( [ { symbol: 'sil' } ] ), - 1 );

} );

test( 'a static item sets its views before it is said, then its speed, and holds its first spoken phone', async () => {

	const view = fakeView();
	const presenter = presenterOf( view );
	assert.equal( await presenter.present( phoneme ), true );
	assert.deepEqual( view.log, [
		[ 'fly', [ - 8, 4, 0 ], 0 ],
		[ 'apply', true, 80, false ],
		[ 'class', 'with-diagram', false ],
		[ 'say', { phones: [ { symbol: 'sil', start_s: 0, end_s: 0.2 }, { symbol: 'S', start_s: 0.2, end_s: 0.9 }, { symbol: 'sil', start_s: 0.9, end_s: 1.1 } ], audio: { kind: 'natural' }, dominance: true } ],
		[ 'speed', 1 ],
		[ 'goTo', 1 ],
		[ 'hold' ],
	] );
	await presenter.present( phoneme );
	assert.deepEqual( view.log.filter( ( [ what ] ) => what === 'fly' ).map( ( entry ) => entry[ 2 ] ), [ 0, 500 ], 'the camera jumps to the first item and flies to the next' );
	assert.deepEqual( [ view.epg.panel.hidden, view.epg.electrodes.group.visible ], [ true, false ] );

} );

test( 'a static item played to its end is held again; a dynamic one is left where it ended', async () => {

	const view = fakeView();
	const presenter = presenterOf( view );
	await presenter.present( phoneme );
	presenter.replay();
	assert.equal( view.clock.playing, true );
	view.hooks.forEach( ( hook ) => hook() ); // a frame while playing
	view.clock.playing = false;
	view.clock.time = view.clock.duration;
	view.log.length = 0;
	view.hooks.forEach( ( hook ) => hook() ); // the frame that reached the end
	await new Promise( ( resolve ) => setTimeout( resolve, 0 ) );
	assert.deepEqual( view.log, [ [ 'goTo', 1 ], [ 'hold' ] ] );
	await presenter.present( word );
	presenter.replay();
	view.hooks.forEach( ( hook ) => hook() );
	view.clock.playing = false;
	view.log.length = 0;
	view.hooks.forEach( ( hook ) => hook() );
	assert.deepEqual( view.log, [] );
	assert.equal( view.hooks.length, 1, 'one watcher however many items' );

} );

test( 'every play counts, from the start after a replay; a new item starts the count again', async () => {

	const view = fakeView();
	const presenter = presenterOf( view );
	await presenter.present( word );
	presenter.replay();
	presenter.togglePlay(); // pause: no play
	presenter.togglePlay();
	assert.equal( presenter.plays, 2 );
	assert.ok( view.log.some( ( [ what, t ] ) => what === 'seek' && t === 0 ) );
	await presenter.present( phoneme );
	assert.equal( presenter.plays, 0 );

} );

test( 'a newer item wins over an older one whose target is still being said', async () => {

	const view = fakeView( { sayDelays: [ 30, 0 ] } );
	const presenter = presenterOf( view );
	const older = presenter.present( phoneme );
	const newer = presenter.present( word );
	assert.deepEqual( await Promise.all( [ older, newer ] ), [ false, true ] );
	assert.equal( presenter.item, word );
	assert.ok( ! view.log.some( ( [ what ] ) => what === 'hold' ), 'the older static item is not held over the newer one' );

} );
