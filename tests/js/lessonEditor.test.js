import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
	authorHref, blankLesson, draftOf, fieldErrors, insertItem, isDirty, itemErrors, itemSummary,
	itemsWithErrors, labelMode, labelsOfMode, lessonBody, LISTEN_CHOICES, toggleLabel, SAID_AS_CHOICES, CAMERA_CHOICES, LABEL_CHOICES, listenChoice, listenFromChoice, moveItem, newItem, parseAuthorHash, parseLessonFile, readNumber, removeItem, setField,
} from '../../web/src/ui/author/LessonEditorModel.js';
import { createLessonClient } from '../../web/src/ui/author/LessonEditorClient.js';
import { createApi } from '../../web/src/api.js';
import { attachmentName } from '../../web/src/ui/shared/download.js';
import { readFileSync } from 'node:fs';

const SCHEMA = JSON.parse( readFileSync( new URL( '../../docs/lesson.schema.json', import.meta.url ), 'utf8' ) );

const SERVER_LESSON = {
	id: 7, title: 'sip, ship', language: 'en-US', description: '', format_version: 1,
	items: [
		{ target: { kind: 'phoneme', text: 's' }, presentation: 'static', audio: { kind: 'natural', cutoff_hz: null, channels: null },
			views: { skin_transparency: 0.6, cutaway: true, diagram: false, cues: true, labels: [ 'tongue_tip', 'alveolar' ], epg: true, camera: 'profile', zoom: 1.5 }, speed: 1, said_as: 'alone' },
		{ target: { kind: 'word', text: 'ship' }, presentation: 'dynamic', audio: { kind: 'lowpass', cutoff_hz: 800, channels: null },
			views: { skin_transparency: 0.6, cutaway: false, diagram: false, cues: true, labels: false, epg: false, camera: 'front', zoom: 1 }, speed: 0.5 },
	],
};

test( 'a draft read from the server sends back exactly the lesson format, with only the audio options that apply', () => {

	const body = lessonBody( draftOf( SERVER_LESSON ) );
	assert.deepEqual( Object.keys( body ), [ 'format_version', 'title', 'language', 'description', 'items' ] );
	assert.deepEqual( body.items[ 0 ].audio, { kind: 'natural' } );
	assert.deepEqual( body.items[ 1 ].audio, { kind: 'lowpass', cutoff_hz: 800 } );
	assert.equal( body.items[ 1 ].speed, 0.5 );
	assert.deepEqual( body.items[ 0 ].views, SERVER_LESSON.items[ 0 ].views );
	assert.equal( body.items[ 0 ].said_as, 'alone' );
	assert.equal( 'said_as' in body.items[ 1 ], false, 'a word is not said as anything' );
	const vocoded = lessonBody( { ...blankLesson(), items: [ setField( setField( newItem(), 'audio.kind', 'vocoded' ), 'audio.channels', 6 ) ] } );
	assert.deepEqual( vocoded.items[ 0 ].audio, { kind: 'vocoded', channels: 6 } );

} );

test( 'the labels are none, all or a few chosen, kept in the label layer\'s order; choosing keeps the names chosen before', () => {

	assert.deepEqual( [ labelMode( false ), labelMode( true ), labelMode( [ 'lips' ] ) ], [ 'none', 'all', 'chosen' ] );
	assert.deepEqual( labelsOfMode( 'chosen', true ), [ 'tongue_tip' ] );
	assert.deepEqual( labelsOfMode( 'chosen', [ 'velar' ] ), [ 'velar' ] );
	assert.equal( labelsOfMode( 'all', [ 'velar' ] ), true );
	assert.equal( labelsOfMode( 'none', [ 'velar' ] ), false );
	assert.deepEqual( toggleLabel( [ 'velar' ], 'lips', true ), [ 'lips', 'velar' ] );
	assert.deepEqual( toggleLabel( [ 'velar', 'lips' ], 'velar', false ), [ 'lips' ] );
	assert.deepEqual( LABEL_CHOICES.map( ( c ) => c.value ), SCHEMA.$defs.Views.properties.labels.anyOf[ 1 ].items.enum );
	assert.deepEqual( CAMERA_CHOICES.map( ( c ) => c.value ).sort(), [ ...SCHEMA.$defs.Views.properties.camera.enum ].sort() );
	assert.deepEqual( SAID_AS_CHOICES.map( ( c ) => c.value ).filter( Boolean ), SCHEMA.$defs.Item.properties.said_as.anyOf[ 0 ].enum );

} );

test( 'an item left sparse gets the schema defaults, and the draft is a copy that edits do not reach back through', () => {

	const item = draftOf( { items: [ { target: { kind: 'word', text: 'sun' } } ] } ).items[ 0 ];
	assert.deepEqual( item, {
		target: { kind: 'word', text: 'sun' }, presentation: 'dynamic', audio: { kind: 'natural', cutoff_hz: null, channels: null },
		views: { skin_transparency: 0.6, cutaway: false, diagram: false, cues: true, labels: false, epg: false, camera: 'profile', zoom: 1 }, speed: 1, said_as: null, listen: null,
	} );
	// What a try is measured on goes through the editor as the lesson had it.
	const listened = { target: { kind: 'phoneme', text: 'i' }, listen: { measure: 'vowel', vowel: 'iy', within_sd: 2 } };
	assert.deepEqual( lessonBody( draftOf( { title: 't', items: [ listened ] } ) ).items[ 0 ].listen, listened.listen );
	assert.equal( 'listen' in lessonBody( draftOf( { title: 't', items: [ { target: { kind: 'word', text: 'sun' } } ] } ) ).items[ 0 ], false );
	const draft = draftOf( SERVER_LESSON );
	draft.items[ 0 ] = setField( draft.items[ 0 ], 'views.cutaway', false );
	assert.equal( SERVER_LESSON.items[ 0 ].views.cutaway, true );
	assert.equal( isDirty( draft, draftOf( SERVER_LESSON ) ), true );
	assert.equal( isDirty( draftOf( SERVER_LESSON ), draftOf( SERVER_LESSON ) ), false );

} );

test( 'items move, insert and go without changing the list they came from, and stay inside it', () => {

	const items = [ 'a', 'b', 'c' ];
	assert.deepEqual( moveItem( items, 0, 2 ), [ 'b', 'c', 'a' ] );
	assert.deepEqual( moveItem( items, 2, 1 ), [ 'a', 'c', 'b' ] );
	assert.deepEqual( moveItem( items, 0, - 1 ), [ 'a', 'b', 'c' ] );
	assert.deepEqual( moveItem( items, 1, 9 ), [ 'a', 'c', 'b' ] );
	assert.deepEqual( insertItem( items, 1, 'x' ), [ 'a', 'x', 'b', 'c' ] );
	assert.deepEqual( insertItem( items, 9, 'x' ), [ 'a', 'b', 'c', 'x' ] );
	assert.deepEqual( removeItem( items, 1 ), [ 'a', 'c' ] );
	assert.deepEqual( items, [ 'a', 'b', 'c' ] );

} );

test( 'the server’s 422 is split by field, an unknown phoneme lands on its item, and a message holding "; " stays whole', () => {

	const detail = "body.items.1.target: Value error, unknown phoneme symbol 'ʘ': use an ARPAbet or IPA symbol of GET /phonemes; "
		+ 'body.items.0.speed: Input should be greater than or equal to 0.1; body.title: String should have at least 1 character; '
		+ "body.items.0.presentation: Input should be 'static' or 'dynamic'; not both";
	const errors = fieldErrors( detail );
	assert.equal( errors.get( 'items.1.target' ), "unknown phoneme symbol 'ʘ': use an ARPAbet or IPA symbol of GET /phonemes" );
	assert.equal( errors.get( 'title' ), 'String should have at least 1 character' );
	assert.equal( errors.get( 'items.0.presentation' ), "Input should be 'static' or 'dynamic'; not both" );
	assert.deepEqual( itemsWithErrors( errors ), [ 0, 1 ] );
	assert.deepEqual( [ ...itemErrors( errors, 0 ).keys() ].sort(), [ 'presentation', 'speed' ] );
	assert.deepEqual( [ ...itemErrors( errors, 1 ) ], [ [ 'target', "unknown phoneme symbol 'ʘ': use an ARPAbet or IPA symbol of GET /phonemes" ] ] );
	assert.deepEqual( [ ...fieldErrors( 'the server is busy' ) ], [ [ '', 'the server is busy' ] ] );
	assert.deepEqual( [ ...fieldErrors( [ { loc: [ 'body', 'items', 2, 'speed' ], msg: 'too fast' } ] ) ], [ [ 'items.2.speed', 'too fast' ] ] );

} );

test( 'a lesson file must be JSON with items, and says so in plain words when it is not', () => {

	assert.equal( parseLessonFile( JSON.stringify( { title: 't', items: [] } ) ).title, 't' );
	assert.throws( () => parseLessonFile( '{ not json' ), /not JSON/ );
	assert.throws( () => parseLessonFile( '[1, 2]' ), /not a lesson/ );
	assert.throws( () => parseLessonFile( '{"title": "t"}' ), /not a lesson/ );

} );

test( 'editor addresses name a lesson, a new one or the list', () => {

	assert.deepEqual( parseAuthorHash( '#/author?lesson=12' ), { lesson: 12 } );
	assert.deepEqual( parseAuthorHash( '#/author?lesson=new' ), { lesson: 'new' } );
	assert.deepEqual( parseAuthorHash( '#/author' ), { lesson: null } );
	assert.deepEqual( parseAuthorHash( '#/author?lesson=0' ), { lesson: null } );
	assert.deepEqual( parseAuthorHash( '#/author?lesson=2x' ), { lesson: null } );
	assert.equal( authorHref( 12 ), '#/author?lesson=12' );
	assert.equal( authorHref(), '#/author' );

} );

test( 'small readers: numbers typed, download names, item summaries', () => {

	assert.equal( readNumber( ' 0.5 ' ), 0.5 );
	assert.equal( readNumber( '' ), null );
	assert.equal( readNumber( 'abc' ), null );
	assert.equal( attachmentName( 'attachment; filename="lesson-3.json"', 'x.json' ), 'lesson-3.json' );
	assert.equal( attachmentName( null, 'x.json' ), 'x.json' );
	assert.equal( itemSummary( draftOf( SERVER_LESSON ).items[ 0 ] ), 'Sound /s/, held' );
	assert.equal( itemSummary( draftOf( SERVER_LESSON ).items[ 1 ] ), 'Word "ship", 0.5x, lowpass' );

} );

function fakeFetch( answers ) {

	const calls = [];
	const fetchImpl = async ( url, init ) => {

		calls.push( { url, ...init } );
		const { status = 200, body = null, headers = {} } = answers.shift();
		return {
			ok: status >= 200 && status < 300, status, statusText: '',
			headers: { get: ( name ) => headers[ name.toLowerCase() ] ?? null },
			json: async () => body, text: async () => JSON.stringify( body ),
		};

	};

	return { fetchImpl, calls };

}

test( 'the client reads ETags, sends If-Match and the token, and a stale save is a 412 carrying the current ETag', async () => {

	const { fetchImpl, calls } = fakeFetch( [
		{ body: SERVER_LESSON, headers: { etag: '"lesson-7-v1"' } },
		{ status: 412, body: { detail: 'lesson 7 changed since it was read' }, headers: { etag: '"lesson-7-v2"' } },
		{ body: SERVER_LESSON, headers: { etag: '"lesson-7-v3"' } },
	] );
	const client = createLessonClient( { api: createApi( { fetchImpl, tokenSource: () => 'tok' } ) } );
	const { lesson, etag } = await client.get( 7 );
	assert.equal( lesson.id, 7 );
	assert.equal( etag, '"lesson-7-v1"' );
	const stale = await client.replace( 7, lessonBody( draftOf( lesson ) ), etag ).catch( ( error ) => error );
	assert.equal( stale.status, 412 );
	assert.equal( stale.etag, '"lesson-7-v2"' );
	assert.equal( calls[ 1 ].method, 'PUT' );
	assert.equal( calls[ 1 ].headers[ 'If-Match' ], '"lesson-7-v1"' );
	assert.equal( calls[ 1 ].headers.Authorization, 'Bearer tok' );
	assert.equal( JSON.parse( calls[ 1 ].body ).title, 'sip, ship' );
	const overwritten = await client.replace( 7, lessonBody( draftOf( lesson ) ), stale.etag );
	assert.equal( overwritten.etag, '"lesson-7-v3"' );
	assert.equal( calls[ 2 ].headers[ 'If-Match' ], '"lesson-7-v2"' );

} );

test( 'a draft is kept per lesson with the ETag it was made on, read back as a draft, and forgotten', async () => {

	const { DRAFT_KEY, forgetDraft, keepDraft, keptDraft } = await import( '../../web/src/ui/author/LessonEditorDrafts.js' );
	const items = new Map();
	const win = { localStorage: { getItem: ( k ) => items.get( k ) ?? null, setItem: ( k, v ) => items.set( k, String( v ) ), removeItem: ( k ) => items.delete( k ) } };
	const draft = draftOf( SERVER_LESSON );
	keepDraft( win, 7, draft, '"lesson-7-v1"' );
	keepDraft( win, null, blankLesson(), null );
	assert.deepEqual( [ ...items.keys() ].sort(), [ `${ DRAFT_KEY }.7`, `${ DRAFT_KEY }.new` ] );
	assert.deepEqual( keptDraft( win, 7 ), { draft, etag: '"lesson-7-v1"' } );
	assert.equal( keptDraft( win, 8 ), null );
	items.set( `${ DRAFT_KEY }.9`, '{ broken' );
	assert.equal( keptDraft( win, 9 ), null );
	forgetDraft( win, 7 );
	assert.equal( keptDraft( win, 7 ), null );
	assert.equal( keptDraft( { get localStorage() { throw new Error( 'denied' ); } }, 7 ), null );

} );

test( 'what a try is measured on is chosen from a list and keeps its zone while the measure stays', () => {

	for ( const { value } of LISTEN_CHOICES ) assert.equal( listenChoice( listenFromChoice( value ) ), value );
	assert.equal( listenFromChoice( '' ), null );
	assert.deepEqual( listenFromChoice( 'vowel:aa', { measure: 'vowel', vowel: 'iy', within_sd: 2 } ), { measure: 'vowel', vowel: 'aa', within_sd: 2 } );
	assert.deepEqual( listenFromChoice( 'sibilant:sh', { measure: 'vowel', vowel: 'iy', within_sd: 2 } ), { measure: 'sibilant', sound: 'sh' } );
	assert.deepEqual( listenFromChoice( 'rhotic', { measure: 'rhotic', f3_below_hz: 2200 } ), { measure: 'rhotic', f3_below_hz: 2200 } );
	assert.equal( listenChoice( { measure: 'sibilant', sound: 's', from_share: 0.7 } ), 'sibilant:s' );

} );
