// The views under the role table, without a browser: what the bar's account corner says, which
// target lists the head view offers to whom, and a recording import that carries the token and
// the child it was recorded from.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { accountItem } from '../../web/src/ui/shared/NavBar.js';
import { sourceShown } from '../../web/src/ui/head/HeadTargets.js';
import { importErrorMessage, importRecordingFile, REFERENCE } from '../../web/src/ui/clinician/clinicianImport.js';
import { createApi } from '../../web/src/api.js';

const teacher = { kind: 'user', token: 't-1', expires_at: '2099-01-01T00:00:00Z', user: { id: 2, username: 'ann@school.example', display_name: 'Ann', role: 'teacher' } };
const child = { kind: 'child', token: 'c-1', expires_at: '2099-01-01T00:00:00Z', child: { id: 5, display_name: 'Fox' } };

test( 'the bar names who is signed in, or links to signing in and back to the view on screen', () => {

	assert.deepEqual( accountItem( teacher, '#/workbench' ), { signedIn: true, label: 'Ann (teacher)' } );
	assert.deepEqual( accountItem( child, '#/' ), { signedIn: true, label: 'Fox' } );
	assert.deepEqual( accountItem( null, '#/clinician?recording=4' ), { signedIn: false, href: '#/signin?next=%23%2Fclinician%3Frecording%3D4' } );
	assert.deepEqual( accountItem( null, '' ), { signedIn: false, href: '#/signin' } );
	assert.deepEqual( accountItem( null, '#/signin?next=%23%2Fspeak' ), { signedIn: false, href: '#/signin?next=%23%2Fspeak' }, 'on the sign-in view it keeps its way back' );

} );

test( 'the head view lists phoneme targets to everyone and saved poses only to a signed-in adult', () => {

	assert.equal( sourceShown( 'phoneme', null ), true );
	assert.equal( sourceShown( 'pose', null ), false );
	assert.equal( sourceShown( 'pose', child ), false );
	assert.equal( sourceShown( 'pose', teacher ), true );

} );

/** A fetch that answers `status` with `body`, recording what it was sent. */
function fakeFetch( status, body ) {

	const sent = [];
	const fetchImpl = async ( url, init ) => {

		sent.push( { url, init } );
		return { ok: status >= 200 && status < 300, status, json: async () => body };

	};
	return { fetchImpl, sent };

}

test( 'an import sends the bearer token and the child it was recorded from; a reference sends no child', async () => {

	const { fetchImpl, sent } = fakeFetch( 201, { recordings: [ { id: 8 } ], total: 1 } );
	const file = new File( [ 'frame,row\n' ], 'take.csv' );
	await importRecordingFile( file, { childId: '12', api: createApi( { fetchImpl, tokenSource: () => 'tok-7' } ) } );
	await importRecordingFile( file, { childId: REFERENCE, api: createApi( { fetchImpl, tokenSource: () => 'tok-7' } ) } );
	await importRecordingFile( file, { api: createApi( { fetchImpl, tokenSource: () => null } ) } );
	assert.equal( sent[ 0 ].init.headers.Authorization, 'Bearer tok-7' );
	assert.equal( sent[ 0 ].init.body.get( 'child_id' ), '12' );
	assert.equal( sent[ 1 ].init.body.get( 'child_id' ), null );
	assert.equal( sent[ 2 ].init.headers.Authorization, undefined, 'nobody signed in: no token' );

} );

test( 'a refused import says why in plain words and keeps the status for the view (401: sign in again)', async () => {

	const { fetchImpl } = fakeFetch( 401, { detail: 'a valid bearer token is needed' } );
	await assert.rejects( importRecordingFile( new File( [ 'x' ], 'take.csv' ), { api: createApi( { fetchImpl, tokenSource: () => 'old' } ) } ),
		{ name: 'ApiError', status: 401, message: 'Please sign in to import recordings.' } );
	assert.equal( importErrorMessage( 403 ), 'Only clinicians and admins can import recordings.' );
	assert.equal( importErrorMessage( 404 ), 'That child is not in your caseload: nothing was imported.' );

} );
