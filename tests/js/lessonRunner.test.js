// The lesson runner's pure parts (ui/lessons/LessonRunnerItems.js, ui/lessons/LessonRunnerPanel.js): what an item
// asks of the head (the POST /utterances body, the views, the speed, holding a static target), the
// runner's address and keys, and the practice table of the side panel. The item defaults are
// checked against the published lesson schema (docs/lesson.schema.json), which the server makes.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

import {
	DEFAULT_VIEWS, HELD_S, itemRequest, itemSettings, phonemeIndex, saidAs, parseRunnerHash, runnerAction, runnerHref, runnerSpeed, SLOW_SPEED, stepItem, targetLabel, listenHref,
} from '../../web/src/ui/lessons/LessonRunnerItems.js';
import { practiceRows } from '../../web/src/ui/lessons/LessonRunnerPanel.js';

const SCHEMA = JSON.parse( readFileSync( new URL( '../../docs/lesson.schema.json', import.meta.url ), 'utf8' ) );

const word = ( text, extra = {} ) => ( { target: { kind: 'word', text }, ...extra } );
const phoneme = ( text, extra = {} ) => ( { target: { kind: 'phoneme', text }, ...extra } );

test( 'a phoneme target is said as phonemes and a word, syllable or phrase as text, with natural audio by default', () => {

	assert.deepEqual( itemRequest( phoneme( 'ʃ' ) ), { phonemes: 'ʃ', audio: { kind: 'natural' }, dominance: true } );
	assert.deepEqual( itemRequest( word( 'ship' ) ), { text: 'ship', audio: { kind: 'natural' }, dominance: true } );
	assert.deepEqual( itemRequest( { target: { kind: 'phrase', text: 'Put the cat on the mat.' } } ).text, 'Put the cat on the mat.' );
	assert.deepEqual( itemRequest( { target: { kind: 'syllable', text: '/M AA/' } } ).phonemes, 'M AA' );

} );

const INVENTORY = phonemeIndex( [
	{ ipa: 's', arpabet: 'S', manner: 'fricative' }, { ipa: 't', arpabet: 'T', manner: 'stop' },
	{ ipa: 'tʃ', arpabet: 'CH', manner: 'affricate' }, { ipa: 'i', arpabet: 'IY', manner: 'close' },
] );

test( 'a sound that can be held is held 0.7 s between silences, as timed phones the server stretches', () => {

	for ( const symbol of [ 's', 'S', 'i' ] ) {

		const request = itemRequest( phoneme( symbol ), INVENTORY );
		assert.equal( request.phonemes, undefined );
		assert.deepEqual( request.phones.map( ( p ) => p.symbol ), [ 'sil', symbol, 'sil' ] );
		const held = request.phones[ 1 ];
		assert.ok( Math.abs( held.end_s - held.start_s - HELD_S ) < 1e-9 && HELD_S >= 0.6 && HELD_S <= 0.8 );
		assert.deepEqual( [ request.audio, request.dominance ], [ { kind: 'natural' }, true ] );

	}

} );

test( 'a stop or an affricate is said in a syllable unless the item says otherwise; any sound can be said three times or alone', () => {

	assert.equal( saidAs( phoneme( 't' ), INVENTORY.get( 't' ) ), 'syllable' );
	assert.equal( itemRequest( phoneme( 't' ), INVENTORY ).phonemes, 't ˈɑ' );
	assert.equal( itemRequest( phoneme( 'CH' ), INVENTORY ).phonemes, 'CH ˈɑ' );
	assert.equal( itemRequest( phoneme( 't', { said_as: 'repeated' } ), INVENTORY ).phonemes, 't ə sil t ə sil t ə' );
	assert.equal( itemRequest( phoneme( 't', { said_as: 'alone' } ), INVENTORY ).phonemes, 't', 'a stop alone: its burst, as the voice says it' );
	assert.equal( itemRequest( phoneme( 's', { said_as: 'syllable' } ), INVENTORY ).phonemes, 's ˈɑ' );
	assert.equal( itemRequest( phoneme( 's', { said_as: 'repeated' } ), INVENTORY ).phonemes, 's ə sil s ə sil s ə' );
	assert.equal( saidAs( phoneme( 's' ), INVENTORY.get( 's' ) ), 'alone' );

} );

test( 'an item\'s low-pass audio carries its cut-off and vocoded audio its channels; no sound is asked as none', () => {

	assert.deepEqual( itemRequest( word( 'sip', { audio: { kind: 'lowpass', cutoff_hz: 500 } } ) ).audio, { kind: 'lowpass', cutoff_hz: 500 } );
	assert.deepEqual( itemRequest( word( 'sip', { audio: { kind: 'vocoded', channels: 6 } } ) ).audio, { kind: 'vocoded', channels: 6 } );
	assert.deepEqual( itemRequest( word( 'sip', { audio: { kind: 'none' } } ) ).audio, { kind: 'none' } );

} );

test( 'the views an item leaves out are the published schema\'s defaults', () => {

	const properties = SCHEMA.$defs.Views.properties;
	assert.deepEqual( Object.keys( DEFAULT_VIEWS ).sort(), Object.keys( properties ).sort() );
	for ( const [ name, value ] of Object.entries( DEFAULT_VIEWS ) ) assert.equal( value, properties[ name ].default, name );
	assert.equal( SCHEMA.$defs.Item.properties.speed.default, itemSettings( word( 'a' ) ).speed );
	assert.equal( SCHEMA.$defs.Item.properties.presentation.default, 'dynamic' );

} );

test( 'an item\'s settings: skin transparency in percent, its switches, its speed, and a static item held', () => {

	const settings = itemSettings( phoneme( 's', { presentation: 'static', speed: 0.5, views: { skin_transparency: 0.8, epg: true, labels: true } } ) );
	assert.deepEqual( settings, { transparency: 80, cutaway: false, diagram: false, cues: true, labels: true, epg: true, camera: 'profile', zoom: 1, speed: 0.5, hold: true } );
	const chosen = itemSettings( phoneme( 't', { views: { labels: [ 'tongue_tip', 'alveolar' ], camera: 'front', zoom: 9 } } ) );
	assert.deepEqual( [ chosen.labels, chosen.camera, chosen.zoom ], [ [ 'tongue_tip', 'alveolar' ], 'front', 2.5 ] );
	const defaults = itemSettings( word( 'ship' ) );
	assert.deepEqual( [ defaults.transparency, defaults.hold, defaults.speed ], [ 60, false, 1 ] );

} );

test( 'slow motion plays at a quarter speed and never speeds up an item that is slower already', () => {

	assert.equal( SLOW_SPEED, 0.25 );
	assert.equal( runnerSpeed( { speed: 1 }, true ), 0.25 );
	assert.equal( runnerSpeed( { speed: 0.1 }, true ), 0.1 );
	assert.equal( runnerSpeed( { speed: 0.5 }, false ), 0.5 );

} );

test( 'the runner\'s address names a lesson and an item, and anything else is the list or the first item', () => {

	assert.equal( runnerHref(), '#/teach' );
	assert.equal( runnerHref( 7, 3 ), '#/teach?lesson=7&item=3' );
	assert.deepEqual( parseRunnerHash( runnerHref( 7, 3 ) ), { lesson: 7, item: 3, present: false } );
	assert.deepEqual( parseRunnerHash( '#/teach' ), { lesson: null, item: 0, present: false } );
	assert.deepEqual( parseRunnerHash( '#/teach?lesson=0&item=2' ), { lesson: null, item: 2, present: false } );
	assert.equal( runnerHref( 7, 0, { present: true } ), '#/teach?lesson=7&item=0&present=1' );
	assert.deepEqual( parseRunnerHash( runnerHref( 7, 0, { present: true } ) ), { lesson: 7, item: 0, present: true } );
	assert.deepEqual( parseRunnerHash( '#/teach?lesson=x1&item=-2' ), { lesson: null, item: 0, present: false } );
	assert.deepEqual( [ stepItem( 0, - 1, 5 ), stepItem( 4, 1, 5 ), stepItem( 2, 1, 5 ), stepItem( 9, 0, 5 ) ], [ 0, 4, 3, 4 ] );

} );

test( 'Space plays, the arrows move, S slows, F goes full screen and Esc leaves; keys typed into a field stay there', () => {

	const on = ( key, target = { tagName: 'BODY' }, extra = {} ) => runnerAction( { key, target, ...extra } );
	assert.deepEqual( [ ' ', 'ArrowLeft', 'ArrowRight', 's', 'S', 'f', 'Escape' ].map( ( key ) => on( key ) ), [ 'play', 'previous', 'next', 'slow', 'slow', 'fullscreen', 'leave' ] );
	assert.equal( on( 'ArrowDown' ), null );
	assert.equal( on( 's', { tagName: 'INPUT' } ), null );
	assert.equal( on( 'Escape', { tagName: 'SELECT' } ), 'leave' );
	const inDialog = { tagName: 'BUTTON', closest: ( selector ) => ( selector === 'dialog' ? {} : null ) };
	assert.equal( on( 'Escape', inDialog ), null, 'an open dialog closes on its own Esc' );
	assert.equal( on( 'ArrowRight', inDialog ), null );
	assert.equal( on( ' ', { tagName: 'BUTTON' } ), null, 'Space on a button presses that button' );
	assert.equal( on( 'f', undefined, { ctrlKey: true } ), null );

} );

test( 'the practice table lists only the class\'s children, newest first, with the item\'s target and the face of the rating', () => {

	const items = [ phoneme( 's' ), word( 'ship' ) ];
	const children = [ { id: 1, display_name: 'Ada', avatar: 'owl' }, { id: 2, display_name: 'Bo', avatar: 'cat' } ];
	const records = [
		{ id: 10, child_id: 1, item_index: 0, practised_at: '2026-11-25T10:00:00Z', replays: 2, rating: 3, rated_by: 'child' },
		{ id: 11, child_id: 9, item_index: 0, practised_at: '2026-11-25T11:00:00Z', replays: 0, rating: null, rated_by: null },
		{ id: 12, child_id: 2, item_index: 1, practised_at: '2026-11-25T10:30:00Z', replays: 0, rating: null, rated_by: null },
	];
	const rows = practiceRows( records, children, items );
	assert.deepEqual( rows.map( ( row ) => [ row.id, row.child.display_name, row.target, row.rating?.label ?? null ] ), [ [ 12, 'Bo', 'ship', null ], [ 10, 'Ada', '/s/', 'Got it' ] ] );
	assert.equal( targetLabel( items[ 0 ] ), '/s/' );

} );

test( 'the Live chart link opens the listening page with children\'s norms and a phoneme target', () => {

	assert.equal( listenHref( { target: { kind: 'phoneme', text: 'ʃ' } } ), '#/listen?group=child&phoneme=%CA%83' );
	assert.equal( listenHref( { target: { kind: 'word', text: 'ship' } } ), '#/listen?group=child' );
	assert.equal( listenHref( null ), '#/listen?group=child' );
	assert.equal( listenHref( { target: { kind: 'word', text: 'beat' }, listen: { measure: 'vowel', vowel: 'iy' } } ), '#/listen?group=child&vowel=iy' );

} );
