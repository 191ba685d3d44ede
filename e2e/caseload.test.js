// End-to-end, in Debian's Chromium: a clinician imports a real recording (the emuR engassim set)
// for a child of their caseload, chosen by name in the clinician view's import box, and the
// server keeps it as that child's (child_id); the box lists only the clinician's own children.

import assert from 'node:assert/strict';
import { join, resolve } from 'node:path';
import { describe, test } from 'node:test';
import { apiSession, authHeaders, signIn } from './accounts.js';
import { openPage, readDebug, REPO, serverAndBrowser } from './harness.js';

const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( REPO, '..', 'shared', 'data' );
/** Real recordings (the emuR engassim set) to import for a child. */
const EMUR = join( DATA_DIR, 'epg', 'emur-engassim.json' );

describe( 'recordings of a caseload', { timeout: 300_000 }, () => {

	let server, browser;

	serverAndBrowser( ( running ) => ( { server, browser } = running ) );

	test( 'a clinician imports a recording for a child of their caseload, chosen in the import box', async () => {

		const session = await apiSession( server, 'clinician' );
		const post = async ( path, body, as = session ) => {

			const response = await fetch( `${ server.baseUrl }/api/v1${ path }`, { method: 'POST', headers: authHeaders( as, { 'Content-Type': 'application/json' } ), body: JSON.stringify( body ) } );
			assert.equal( response.status, 201, `POST ${ path }: ${ await response.clone().text() }` );
			return response.json();

		};
		const caseload = await post( '/classes', { name: 'Tuesday clinic (e2e)' } );
		const child = await post( '/children', { class_id: caseload.id, display_name: 'Robin (e2e)', avatar: 'owl' } );
		// A teacher's class and child, which the clinician's box must not offer.
		const teacher = await apiSession( server, 'teacher' );
		const other = await post( '/classes', { name: 'Class 2B (e2e)' }, teacher );
		await post( '/children', { class_id: other.id, display_name: 'Sam (e2e)', avatar: 'fox' }, teacher );
		const page = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( page, server, 'clinician' );
		await page.goto( `${ server.baseUrl }/#/clinician` );
		await page.waitForFunction( () => window.glasshead?.clinician?.loaded === true, null, { timeout: 90_000, polling: 200 } );
		const from = page.getByLabel( 'Recorded from' );
		await page.waitForFunction( () => document.querySelectorAll( '#cv-import-child option' ).length > 1, null, { timeout: 30_000 } );
		assert.deepEqual( await from.locator( 'option' ).allTextContents(), [ 'Reference recording (no child)', 'Robin (e2e)' ] );
		await from.selectOption( { label: 'Robin (e2e)' } );
		await page.getByLabel( 'Import a recording file' ).setInputFiles( EMUR );
		await page.waitForFunction( () => window.glasshead.clinician.imported !== null, null, { timeout: 60_000, polling: 200 } );
		const { imported } = ( await readDebug( page ) ).clinician;
		assert.equal( imported.ok, true, imported.message );
		const stored = await ( await fetch( `${ server.baseUrl }/api/v1/epg/recordings/${ imported.ids[ 0 ] }`, { headers: authHeaders( session ) } ) ).json();
		assert.equal( stored.child_id, child.id, 'the recording is the child\'s' );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

} );
