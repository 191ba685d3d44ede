import { test } from 'node:test';
import assert from 'node:assert/strict';
import { childChoices, measuredSeries, measureWords, practiceRows, ratingWords, readableTime, recordingExportPath, RECORDING_SWITCH_ROLES, recordingHistoryLines, recordingSwitchWords } from '../../web/src/ui/clinician/clinicianChildRows.js';
import { downloadFile } from '../../web/src/ui/shared/download.js';
import { createApi } from '../../web/src/api.js';

test( 'the chooser groups the caseload’s children by class, classes by name, and leaves out empty classes', () => {

	const classes = [ { id: 2, name: 'Year 3' }, { id: 1, name: 'Caseload A' }, { id: 5, name: 'Empty' } ];
	const children = [ { id: 9, class_id: 2, display_name: 'Bo', avatar: 'frog' }, { id: 4, class_id: 1, display_name: 'Ada', avatar: 'owl' }, { id: 7, class_id: 2, display_name: 'Cy', avatar: 'cat' } ];
	assert.deepEqual( childChoices( classes, children ), [
		{ label: 'Caseload A', children: [ { value: '4', label: 'Ada (owl)' } ] },
		{ label: 'Year 3', children: [ { value: '9', label: 'Bo (frog)' }, { value: '7', label: 'Cy (cat)' } ] },
	] );

} );

test( 'practice rows name the lesson, the item from 1 and its target, and say the rating in words', () => {

	const lessons = new Map( [ [ 3, { title: 'sip, ship', items: [ { target: { kind: 'phoneme', text: 's' } }, { target: { kind: 'word', text: 'ship' } } ] } ] ] );
	const records = [
		{ id: 31, lesson_id: 3, item_index: 1, practised_at: '2026-03-02T09:30:12Z', replays: 2, rating: 3, rated_by: 'adult', measures: { centroid: 4012.4, verdict: 'off' }, has_audio: true },
		{ id: 30, lesson_id: 3, item_index: 0, practised_at: '2026-03-01T09:00:00.5+00:00', replays: 0, rating: null, rated_by: null, has_audio: false },
		{ id: 29, lesson_id: 8, item_index: 0, practised_at: '2026-03-01T08:00:00Z', replays: 1, rating: 1, rated_by: 'child' },
	];
	assert.deepEqual( practiceRows( records, lessons ), [
		{ id: 31, when: '2026-03-02 09:30', lesson: 'sip, ship', item: 2, target: 'ship', replays: 2, rating: '3, got it (adult)', heard: 'off: centroid 4012 Hz', audio: true },
		{ id: 30, when: '2026-03-01 09:00', lesson: 'sip, ship', item: 1, target: '/s/', replays: 0, rating: '', heard: '', audio: false },
		{ id: 29, when: '2026-03-01 08:00', lesson: 'lesson 8', item: 1, target: '', replays: 1, rating: '1, not yet (child)', heard: '', audio: false },
	], 'a go has a player only when the server says its sound was kept' );
	assert.equal( ratingWords( 2, null ), '2, nearly' );
	assert.equal( recordingExportPath( 12, 'emur-json' ), 'epg/recordings/12/export?format=emur-json' );

} );

test( 'a download sends the token, saves under the server’s file name, and a refusal is an error with its status', async () => {

	const calls = [];
	const saved = [];
	const answer = ( status, headers, body ) => ( {
		ok: status < 300, status, statusText: '', headers: { get: ( name ) => headers[ name.toLowerCase() ] ?? null },
		blob: async () => body, json: async () => JSON.parse( body ),
	} );
	const fetchImpl = async ( url, init ) => {

		calls.push( { url, init } );
		return calls.length === 1
			? answer( 200, { 'content-disposition': 'attachment; filename="child-3-practice.csv"' }, 'practice_id,child_id\r\n' )
			: answer( 404, {}, JSON.stringify( { detail: 'no child with id 4' } ) );

	};
	const options = { api: createApi( { fetchImpl, tokenSource: () => 'tok' } ), save: ( content, name ) => saved.push( [ content, name ] ) };
	assert.equal( await downloadFile( 'children/3/practice.csv', 'x.csv', options ), 'child-3-practice.csv' );
	assert.equal( calls[ 0 ].url, '/api/v1/children/3/practice.csv' );
	assert.equal( calls[ 0 ].init.headers.Authorization, 'Bearer tok' );
	assert.deepEqual( saved, [ [ 'practice_id,child_id\r\n', 'child-3-practice.csv' ] ] );
	const refused = await downloadFile( 'children/4/practice.csv', 'x.csv', options ).catch( ( error ) => error );
	assert.equal( refused.status, 404 );
	assert.match( refused.message, /no child with id 4/ );

} );

test( 'the measured goes are plotted oldest first, vowels by F1 and F2 and hisses by their centroid', () => {

	const records = [
		{ id: 3, practised_at: '2026-03-03T09:00:00Z', measures: { f1: 410, f2: 3050, verdict: 'in', target_vowel: 'iy' } },
		{ id: 1, practised_at: '2026-03-01T09:00:00Z', measures: { f1: 600, f2: 2500, verdict: 'off' } },
		{ id: 2, practised_at: '2026-03-02T09:00:00Z', measures: { centroid: 5600 } },
		{ id: 4, practised_at: '2026-03-04T09:00:00Z', measures: null },
	];
	assert.deepEqual( measuredSeries( records ), {
		vowel: [ { when: '2026-03-01T09:00:00Z', f1: 600, f2: 2500, verdict: 'off' }, { when: '2026-03-03T09:00:00Z', f1: 410, f2: 3050, verdict: 'in' } ],
		fricative: [ { when: '2026-03-02T09:00:00Z', centroid: 5600, verdict: null } ],
	} );
	assert.equal( measureWords( { f1: 410.4, f2: 3050.5, verdict: 'in' } ), 'in the target: F1 410, F2 3051 Hz' );
	assert.equal( measureWords( null ), '' );

} );

test( 'the recording switch says whether it is on, since when and by whom, in UTC whatever the browser\'s zone', () => {

	assert.equal( recordingSwitchWords( { enabled: false, set_by: null, set_by_name: null, set_at: null, history: [] } ), 'Off', 'never switched on' );
	assert.equal( recordingSwitchWords( { enabled: true, set_by: 3, set_by_name: 'Dr Ames', set_at: '2026-03-02T09:30:12Z' } ), 'On since 2 March 2026, 09:30 UTC, by Dr Ames' );
	assert.equal( recordingSwitchWords( { enabled: false, set_by: 4, set_by_name: 'Ben', set_at: '2026-12-31T23:59:59+01:00' } ), 'Off since 31 December 2026, 22:59 UTC, by Ben' );
	assert.equal( recordingSwitchWords( { enabled: true, set_at: '2026-01-05T07:04:00.123456' } ), 'On since 5 January 2026, 07:04 UTC', 'a time without a zone is UTC, and no name, no "by"' );
	assert.equal( recordingSwitchWords( null ), 'Off', 'nothing known: off' );
	assert.equal( recordingSwitchWords( { enabled: 'yes' } ), 'Off', 'only true is on' );
	assert.equal( readableTime( 'not a time' ), 'not a time' );
	assert.deepEqual( recordingHistoryLines( [
		{ enabled: false, set_by: 4, set_by_name: 'Ben', set_at: '2026-03-03T10:00:00Z' },
		{ enabled: true, set_by: 3, set_by_name: 'Dr Ames', set_at: '2026-03-02T09:30:00Z' },
	] ), [ 'Off: 3 March 2026, 10:00 UTC, by Ben', 'On: 2 March 2026, 09:30 UTC, by Dr Ames' ] );
	assert.deepEqual( recordingHistoryLines( undefined ), [] );
	assert.deepEqual( [ ...RECORDING_SWITCH_ROLES ].sort(), [ 'admin', 'clinician' ], 'teachers see it but do not change it' );

} );
