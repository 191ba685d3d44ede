// What the clinician view says in words (web/src/ui/clinician/clinicianText.js, clinicianUrl.js) and how it
// imports a file (clinicianImport.js, on a fake fetch): readable index names, recording titles,
// kappa beside the raw share, the selection in the URL and bad values there, plain-word errors.
import assert from 'node:assert/strict';
import test from 'node:test';

import { agreementText, indexLabel, INDEX_LABELS, recordingTitle, speakerOf } from '../../web/src/ui/clinician/clinicianText.js';
import { missingChoiceMessage, parseSelection, SelectionUrl, selectionHash } from '../../web/src/ui/clinician/clinicianUrl.js';
import { importErrorMessage, importRecordingFile, MAX_IMPORT_BYTES } from '../../web/src/ui/clinician/clinicianImport.js';
import { createApi } from '../../web/src/api.js';
import { DEFAULT_SPEED, SPEEDS, speedLabel } from '../../web/src/ui/clinician/clinicianLayout.js';
import { TABLE_INDICES } from '../../web/src/ui/clinician/clinicianRender.js';
import { recordingLabel } from '../../web/src/ui/clinician/clinicianData.js';

test( 'every index of the table has a readable name that says its unit or range', () => {

	for ( const name of TABLE_INDICES ) {

		const label = indexLabel( name );
		assert.notEqual( label, name, `${ name } has no readable name` );
		assert.match( label, /%|…|rows/, `${ name }: "${ label }" says no unit or range` );

	}

	assert.equal( INDEX_LABELS.cog, 'Centre of gravity (rows: 0.5 = back R8 … 7.5 = front R1)' );
	assert.equal( indexLabel( 'row3' ), 'row3' );

} );

test( 'a recording from the emuR import is titled by its word, segment and speaker', () => {

	const meta = { label: 's->k', word: 'bescan', utterance: 'sp1bescan', start_s: 155.962 };
	assert.equal( speakerOf( meta ), 'sp1' );
	assert.equal( recordingTitle( { name: 'sp1bescan s->k', meta } ), 'bescan (s→k), speaker sp1' );
	// The word as spelt in the meta need not end the utterance: the leading code is the speaker.
	assert.equal( speakerOf( { word: 'besgar', utterance: 'sp1besger' } ), 'sp1' );
	assert.equal( recordingTitle( { name: 'take 3.csv', meta: {} } ), 'take 3.csv' );
	assert.equal( recordingTitle( { name: 'x', meta: { word: 'tata' } } ), 'tata' );
	assert.equal( recordingLabel( { name: 'sp1bescan s->k', meta, n_frames: 52, frame_rate_hz: 199.6 } ), 'bescan (s→k), speaker sp1 (52 frames, 200 Hz)' );

} );

test( 'the agreement caption gives kappa beside the raw share, and the raw share alone without kappa', () => {

	const comparison = { agreement: [ 0.532, 1 ], kappa: [ 0, 1 ], summary: { mean_agreement: 0.593, mean_kappa: - 0.04 } };
	assert.equal( agreementText( comparison, 0 ), 'κ 0.00 (mean −0.04) · raw 53 % (mean 59 %)' );
	assert.equal( agreementText( comparison, 1 ), 'κ 1.00 (mean −0.04) · raw 100 % (mean 59 %)' );
	assert.equal( agreementText( { agreement: [ 0.5 ], summary: { mean_agreement: 0.5 } }, 0 ), 'raw 50 % (mean 50 %)' );

} );

test( 'playback starts at a tenth of real time, one of the speeds offered', () => {

	assert.equal( DEFAULT_SPEED, 0.1 );
	assert.ok( SPEEDS.includes( DEFAULT_SPEED ) && SPEEDS.includes( 1 ) );
	assert.equal( speedLabel( 0.1 ), '0.1 x (10 times slower)' );
	assert.equal( speedLabel( 1 ), 'Real time' );

} );

test( 'the selection goes into the URL and comes back out of it', () => {

	const hash = selectionHash( { target: 'pose:3', recording: 12, frame: 40 } );
	assert.equal( hash, '#/clinician?target=pose:3&recording=12&frame=40' );
	assert.deepEqual( parseSelection( hash ), { target: 'pose:3', recording: '12', frame: 40, problems: [] } );
	assert.equal( selectionHash( { target: 'phoneme:T', recording: null, frame: 0 } ), '#/clinician?target=phoneme:T' );
	assert.equal( selectionHash( {} ), '#/clinician' );
	assert.deepEqual( parseSelection( '#/clinician' ), { target: null, recording: null, frame: null, problems: [] } );

} );

test( 'bad values in the URL are dropped with a message naming each', () => {

	const selection = parseSelection( '#/clinician?target=nonsense&recording=-4&frame=2.5' );
	assert.equal( selection.target, null );
	assert.equal( selection.recording, null );
	assert.equal( selection.frame, null );
	assert.deepEqual( selection.problems, [
		'The link\'s target "nonsense" is not a target name (such as pose:3 or phoneme:T).',
		'The link\'s recording "-4" is not a recording number.',
		'The link\'s frame "2.5" is not a frame number.',
	] );
	const long = parseSelection( `#/clinician?recording=${ 'x'.repeat( 500 ) }` ).problems[ 0 ];
	assert.ok( long.length < 120, `a long value is cut in the message: ${ long.length } characters` );
	assert.equal( missingChoiceMessage( 'recording', '999' ), 'The link\'s recording 999 does not exist (any more): choose a recording from the list.' );

} );

/** A fake fetch answering `status` with `body`, keeping what it was sent. */
function fakeFetch( status, body ) {

	const sent = [];
	const fetchImpl = async ( url, init ) => {

		sent.push( { url, init } );
		return { ok: status < 300, status, json: async () => body };

	};
	return { fetchImpl, sent };

}

test( 'a chosen file is sent as a multipart upload and the imported recordings come back', async () => {

	const { fetchImpl, sent } = fakeFetch( 201, { total: 1, recordings: [ { id: 5, name: 'take' } ] } );
	const file = new File( [ 'frame,t_s\n' ], 'take.csv', { type: 'text/csv' } );
	const body = await importRecordingFile( file, { api: createApi( { fetchImpl } ) } );
	assert.deepEqual( body.recordings.map( ( r ) => r.id ), [ 5 ] );
	assert.equal( sent.length, 1 );
	assert.equal( sent[ 0 ].url, '/api/v1/epg/recordings' );
	assert.equal( sent[ 0 ].init.method, 'POST' );
	assert.ok( sent[ 0 ].init.body instanceof FormData );
	assert.equal( sent[ 0 ].init.body.get( 'file' ).name, 'take.csv' );

} );

test( 'a refused file is explained in plain words, and empty or oversized files are not sent', async () => {

	const { fetchImpl, sent } = fakeFetch( 422, { detail: 'frame 3, field rows: 7 rows, expected 8' } );
	await assert.rejects( importRecordingFile( new File( [ 'x' ], 'bad.csv' ), { api: createApi( { fetchImpl } ) } ),
		{ message: 'The file could not be imported, nothing was stored: frame 3, field rows: 7 rows, expected 8.' } );
	await assert.rejects( importRecordingFile( new File( [], 'empty.json' ), { api: createApi( { fetchImpl } ) } ), { message: '"empty.json" is empty: nothing was imported.' } );
	const huge = { name: 'huge.json', size: MAX_IMPORT_BYTES + 1 };
	await assert.rejects( importRecordingFile( huge, { api: createApi( { fetchImpl } ) } ), { message: 'The file is too large: recordings can be at most 32 MB.' } );
	assert.equal( sent.length, 1, 'only the first file reached the server' );
	assert.equal( importErrorMessage( 500, 'database locked' ), 'The import failed (HTTP 500): database locked.' );

} );

/** A window with a location hash, a history that replaces it, timers run by hand and events. */
function fakeWindow( hash ) {

	const listeners = {};
	const timers = [];
	const win = {
		location: { hash },
		history: { state: null, replaceState: ( state, title, url ) => ( win.location.hash = url ) },
		setTimeout: ( fn ) => timers.push( fn ),
		clearTimeout: () => timers.splice( 0 ),
		addEventListener: ( type, fn ) => ( listeners[ type ] = fn ),
		removeEventListener: ( type ) => delete listeners[ type ],
		runTimers: () => timers.splice( 0 ).forEach( ( fn ) => fn() ),
		navigate: ( next ) => {

			win.location.hash = next;
			listeners.hashchange?.();

		},
	};
	return win;

}

test( 'the URL is written after a change, applied when typed, and never overwritten when someone else changed it', () => {

	const win = fakeWindow( '#/clinician?target=pose:3' );
	let selection = { target: 'pose:3', recording: 12, frame: 0 };
	const applied = [];
	const url = new SelectionUrl( win, { selection: () => selection, writable: () => true, apply: ( hash ) => applied.push( hash ) } );
	assert.equal( url.read( win.location.hash ).target, 'pose:3' );
	url.write();
	win.runTimers();
	assert.equal( win.location.hash, '#/clinician?target=pose:3&recording=12' );
	// Typed into the address bar: applied, and a write pending from before does not undo it.
	url.write();
	win.navigate( '#/clinician?recording=5' );
	win.runTimers();
	assert.equal( win.location.hash, '#/clinician?recording=5' );
	assert.deepEqual( applied, [ '#/clinician?recording=5' ] );
	url.read( win.location.hash );
	selection = { target: null, recording: 5, frame: 7 };
	url.write();
	win.runTimers();
	assert.equal( win.location.hash, '#/clinician?recording=5&frame=7' );
	url.stop();
	win.navigate( '#/clinician?recording=6' );
	assert.equal( applied.length, 1, 'a stopped URL applies nothing' );

} );
