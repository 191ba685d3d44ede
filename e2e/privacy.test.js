// End-to-end test of privacy in Debian's Chromium: an admin on #/admin exports everything stored
// about one child (a JSON file with their practice, recording and sign-in) and deletes it after the
// page's confirmation; the server then has nothing about the child, and the child's classmate is
// untouched. A clinician who owns the class sees the child's history and exports its CSV on the
// clinician view first. Screenshots: e2e/screenshots/privacy-*.png.

import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { describe, test } from 'node:test';
import { apiSession, authHeaders, createAccounts, signIn } from './accounts.js';
import { openPage, readDebug, saveScreenshot, serverAndBrowser } from './harness.js';

describe( 'a child’s data', { timeout: 900_000 }, () => {

	let server, browser, setting;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		await createAccounts( server, [ 'clinician', 'admin' ] );
		setting = await makeSetting( server );

	} );

	test( 'the clinician who owns the caseload sees a child’s practice and recording and exports the CSV', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( page, server, 'clinician' );
		await page.goto( `${ server.baseUrl }/#/clinician` );
		await page.waitForFunction( () => window.glasshead?.clinicianChild?.loaded === true, null, { timeout: 90_000 } );
		const card = page.getByRole( 'figure', { name: 'A child’s history' } );
		await card.getByLabel( 'Child', { exact: true } ).selectOption( String( setting.ada.id ) );
		await page.waitForFunction( ( id ) => window.glasshead.clinicianChild.child === id && window.glasshead.clinicianChild.recordings.length === 1, setting.ada.id, { timeout: 30_000 } );
		const rows = await card.getByRole( 'table', { name: 'Practice history' } ).locator( 'tbody tr' ).allTextContents();
		assert.equal( rows.length, 2 );
		const [ first, last ] = setting.targets;
		assert.ok( rows[ 0 ].includes( last ), `newest first: the last item's ${ last } in "${ rows[ 0 ] }"` );
		assert.ok( rows[ 1 ].includes( first ), `the item's target is read from its lesson: ${ first } in "${ rows[ 1 ] }"` );
		assert.ok( rows[ 1 ].includes( 'in the target: centroid 5612 Hz' ), `what the voice measured: "${ rows[ 1 ] }"` );
		assert.equal( ( await readDebug( page ) ).clinicianChild.measured, 1, 'the spoken go is plotted' );
		const [ download ] = await Promise.all( [ page.waitForEvent( 'download' ), card.getByRole( 'button', { name: 'Export practice (CSV)' } ).click() ] );
		assert.equal( download.suggestedFilename(), `child-${ setting.ada.id }-practice.csv` );
		const csv = ( await readFile( await download.path(), 'utf8' ) ).trim().split( /\r?\n/ );
		assert.equal( csv.length, 3 );
		assert.match( csv[ 0 ], /^practice_id,child_id,child,lesson_id,lesson,item_index,target_kind,target,/ );
		await card.scrollIntoViewIfNeeded();
		await saveScreenshot( page, 'privacy-clinician-child-1366x768' );
		await page.close();

	} );

	test( 'an admin exports everything about a child, then deletes it after the confirmation', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( page, server, 'admin' );
		await page.goto( `${ server.baseUrl }/#/admin` );
		await page.waitForFunction( ( id ) => window.glasshead?.admin?.children?.includes( id ), setting.ada.id, { timeout: 30_000 } );
		const row = page.locator( `li[data-child="${ setting.ada.id }"]` );

		const [ download ] = await Promise.all( [ page.waitForEvent( 'download' ), row.getByRole( 'button', { name: 'Export everything about Ada' } ).click() ] );
		assert.equal( download.suggestedFilename(), `child-${ setting.ada.id }.json` );
		const exported = JSON.parse( await readFile( await download.path(), 'utf8' ) );
		assert.equal( exported.child.display_name, 'Ada' );
		assert.equal( exported.practice.length, 2 );
		assert.equal( exported.recordings.length, 1 );
		assert.equal( exported.recordings[ 0 ].frames.length, 3 );
		assert.equal( exported.tokens.length, 1 );

		await row.getByRole( 'button', { name: 'Delete everything about Ada…' } ).click();
		const dialog = row.getByRole( 'alertdialog', { name: 'Delete Ada’s data' } );
		assert.match( await dialog.textContent(), /cannot be undone/ );
		await saveScreenshot( page, 'privacy-admin-confirm-1366x768' );
		await dialog.getByRole( 'button', { name: 'Delete Ada’s data' } ).click();
		await page.waitForFunction( ( id ) => window.glasshead.admin.deleted.includes( id ), setting.ada.id, { timeout: 30_000 } );
		assert.equal( await row.count(), 0, 'the row is gone' );
		assert.match( await page.getByRole( 'region', { name: 'Privacy: children’s data' } ).getByRole( 'status' ).textContent(), /2 practice records, 1 EPG recording, 1 assignment and 1 sign-in/ );

		const admin = await apiSession( server, 'admin' );
		const get = async ( path ) => ( await fetch( `${ server.baseUrl }/api/v1/${ path }`, { headers: authHeaders( admin ) } ) );
		assert.equal( ( await get( `children/${ setting.ada.id }` ) ).status, 404 );
		assert.equal( ( await get( `epg/recordings/${ setting.recordingId }` ) ).status, 404 );
		assert.equal( ( await ( await get( `practice?child_id=${ setting.ada.id }` ) ).json() ).total, 0 );
		assert.equal( ( await ( await get( `practice?child_id=${ setting.bo.id }` ) ).json() ).total, 1, 'the classmate’s practice stays' );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

	test( 'an admin adds a teacher with a made-up password, who signs in with it; renames them, then removes them', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( page, server, 'admin' );
		await page.goto( `${ server.baseUrl }/#/admin` );
		await page.waitForFunction( () => ( window.glasshead?.admin?.people?.users.length ?? 0 ) >= 2, null, { timeout: 30_000 } );
		const people = page.getByRole( 'region', { name: 'People who sign in' } );
		const form = people.getByRole( 'form', { name: 'Add a person' } );
		await form.getByLabel( 'Name shown' ).fill( 'Ms Rivera' );
		await form.getByLabel( /^Username/ ).fill( 'rivera@school.example' );
		await form.getByLabel( 'Role' ).selectOption( 'teacher' );
		await form.getByRole( 'button', { name: 'Make one up' } ).click();
		const password = await form.getByLabel( /^First password/ ).inputValue();
		assert.match( password, /^[a-z2-9]{4}-[a-z2-9]{4}-[a-z2-9]{4}$/ );
		await form.getByRole( 'button', { name: 'Add this person' } ).click();
		await page.waitForFunction( () => window.glasshead.admin.people.added.length === 1, null, { timeout: 30_000 } );
		const [ id ] = ( await readDebug( page ) ).admin.people.added;
		assert.match( await people.getByRole( 'status' ).textContent(), new RegExp( `Added Ms Rivera \\(teacher\\)\\. Give them the username rivera@school\\.example and the password ${ password }` ) );
		const signedIn = await fetch( `${ server.baseUrl }/api/v1/auth/sessions`, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify( { username: 'rivera@school.example', password } ) } );
		assert.equal( signedIn.status, 201, 'the new teacher signs in with the password given' );
		await saveScreenshot( page, 'admin-people-1366x768' );

		const row = people.locator( `li[data-user="${ id }"]` );
		await row.getByRole( 'button', { name: 'Rename Ms Rivera…' } ).click();
		await row.getByLabel( 'New name for Ms Rivera' ).fill( 'Ms Rivera-Diaz' );
		await row.getByRole( 'button', { name: 'Save the name' } ).click();
		await page.waitForFunction( ( user ) => window.glasshead.admin.people.renamed.includes( user ), id, { timeout: 30_000 } );
		await people.locator( `li[data-user="${ id }"]` ).getByText( 'Ms Rivera-Diaz' ).waitFor( { timeout: 30_000 } );
		await people.locator( `li[data-user="${ id }"]` ).getByRole( 'button', { name: 'Remove Ms Rivera-Diaz…' } ).click();
		await people.getByRole( 'button', { name: 'Remove Ms Rivera-Diaz', exact: true } ).click();
		await page.waitForFunction( ( user ) => window.glasshead.admin.people.removed.includes( user ), id, { timeout: 30_000 } );
		const admin = await apiSession( server, 'admin' );
		assert.equal( ( await fetch( `${ server.baseUrl }/api/v1/users/${ id }`, { headers: authHeaders( admin ) } ) ).status, 404 );
		const me = ( await readDebug( page ) ).admin.people;
		assert.equal( await people.getByRole( 'button', { name: /^Remove E2E Admin/ } ).count(), 0, 'no one removes themselves here' );
		assert.ok( me.users.length >= 2 );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

} );

/** A clinician's caseload with Ada (two goes at a lesson, a recording, a sign-in) and Bo (one go). */
async function makeSetting( server ) {

	const clinician = await apiSession( server, 'clinician' );
	const send = async ( method, path, body ) => {

		const response = await fetch( `${ server.baseUrl }/api/v1/${ path }`, {
			method, headers: authHeaders( clinician, { 'Content-Type': 'application/json' } ), body: JSON.stringify( body ),
		} );
		const answer = await response.json();
		if ( response.status !== 201 ) throw new Error( `${ method } ${ path } answered ${ response.status }: ${ JSON.stringify( answer ) }` );
		return answer;

	};
	const caseload = await send( 'POST', 'classes', { name: 'Caseload P' } );
	const ada = await send( 'POST', 'children', { class_id: caseload.id, display_name: 'Ada', avatar: 'owl' } );
	const bo = await send( 'POST', 'children', { class_id: caseload.id, display_name: 'Bo', avatar: 'frog' } );
	const lessons = await ( await fetch( `${ server.baseUrl }/api/v1/lessons?limit=1`, { headers: authHeaders( clinician ) } ) ).json();
	const lesson = lessons.lessons[ 0 ];
	await send( 'POST', 'assignments', { lesson_id: lesson.id, child_id: ada.id } );
	for ( const [ child, index, when ] of [ [ ada, 0, '2026-03-01T09:00:00Z' ], [ ada, lesson.n_items - 1, '2026-03-02T09:00:00Z' ], [ bo, 0, '2026-03-01T10:00:00Z' ] ] ) {

		// Ada's first go was said into the microphone: what it measured goes with it.
		const measures = child === ada && index === 0 ? { centroid: 5612.4, duration_s: 0.2, verdict: 'in' } : undefined;
		await send( 'POST', 'practice', { child_id: child.id, lesson_id: lesson.id, item_index: index, practised_at: when, replays: 1, measures } );

	}

	// The CSV format of docs/epg-recordings.md: its first line, then t_s and the 62 electrodes,
	// R1 (front, columns 2 to 7) first; the first 8 electrodes contacted.
	const electrodes = [];
	for ( let r = 1; r <= 8; r ++ ) for ( let c = 1; c <= 8; c ++ ) if ( r > 1 || ( c > 1 && c < 8 ) ) electrodes.push( `R${ r }C${ c }` );
	const row = ( t ) => [ t, ...electrodes.map( ( _, k ) => ( k < 8 ? 1 : 0 ) ) ].join( ',' );
	const lines = [ '# glasshead-epg-csv 1', [ 't_s', ...electrodes ].join( ',' ), row( 0 ), row( 0.01 ), row( 0.02 ) ];
	const recording = await send( 'POST', 'epg/recordings', { format: 'csv', content: lines.join( '\n' ) + '\n', name: 'ada-take-1', child_id: ada.id } );
	const signedIn = await fetch( `${ server.baseUrl }/api/v1/auth/child-sessions`, {
		method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify( { join_code: caseload.join_code, child_id: ada.id } ),
	} );
	if ( signedIn.status !== 201 ) throw new Error( `the child's sign-in answered ${ signedIn.status }` );
	const { items } = await ( await fetch( `${ server.baseUrl }/api/v1/lessons/${ lesson.id }`, { headers: authHeaders( clinician ) } ) ).json();
	const shown = ( item ) => ( item.target.kind === 'phoneme' ? `/${ item.target.text }/` : item.target.text );
	return { caseload, ada, bo, lesson, targets: [ shown( items[ 0 ] ), shown( items[ items.length - 1 ] ) ], recordingId: recording.recordings[ 0 ].id };

}
