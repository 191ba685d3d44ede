// End-to-end test of the author's lesson editor (#/author) in Debian's Chromium: an author makes
// a lesson of two items in the form, is told beside the field what the server refused, previews
// an item on the head with its own views and speed, is told when bone hides a label the item
// names, saves, reloads and finds the lesson as saved;
// a save over a version someone else saved meanwhile gets the plain 412 message, keeps the
// author's edits, and overwrites knowingly. Screenshots: e2e/screenshots/author-*.png.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { account, apiSession, authHeaders, signIn } from './accounts.js';
import { openPage, saveScreenshot, serverAndBrowser } from './harness.js';

/** Smallest touch target, CSS pixels. */
const TOUCH_PX = 44;

describe( 'the lesson editor', { timeout: 900_000 }, () => {

	let server, browser;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		await account( server, 'author' );

	} );

	const author = ( page ) => page.evaluate( () => JSON.parse( JSON.stringify( window.glasshead?.author ?? null ) ) );
	const waitAuthor = ( page, predicate, arg = null, timeout = 60_000 ) => page.waitForFunction( predicate, arg, { timeout, polling: 100 } );
	const itemForm = ( page ) => page.getByRole( 'form', { name: 'Item' } );

	async function openEditor( size, hash = '#/author' ) {

		const page = await openPage( browser, { width: size[ 0 ], height: size[ 1 ] } );
		await signIn( page, server, 'author' );
		await page.goto( `${ server.baseUrl }/${ hash }` );
		return page;

	}

	/** Controls of the editor smaller than a finger, as "name w x h". */
	function smallControls( page ) {

		return page.evaluate( ( px ) => [ ...document.querySelectorAll( '.lesson-editor button, .lesson-editor select, .lesson-editor input:not([type="checkbox"]), .lesson-editor a' ) ]
			.filter( ( element ) => element.getClientRects().length > 0 && ! element.closest( '.sp-bottom' ) )
			.map( ( element ) => [ element.getAttribute( 'aria-label' ) || element.id || element.textContent.trim(), element.getBoundingClientRect() ] )
			.filter( ( [ , box ] ) => box.height < px || box.width < px )
			.map( ( [ name, box ] ) => `${ name } ${ Math.round( box.width ) } x ${ Math.round( box.height ) }` ), TOUCH_PX );

	}

	test( 'an author writes a lesson of two items, sees the server’s message beside a field, previews, saves and finds it after a reload', async () => {

		const page = await openEditor( [ 1366, 768 ] );
		await waitAuthor( page, () => window.glasshead?.author?.screen === 'list' && window.glasshead.author.lessons.length > 0 );
		await page.getByRole( 'link', { name: 'New lesson' } ).click();
		await waitAuthor( page, () => window.glasshead.author.screen === 'editor' && window.glasshead.author.lesson === null );

		await page.getByLabel( 'Title' ).fill( 'Sun and ship' );
		const form = itemForm( page );
		await form.getByLabel( 'Target', { exact: true } ).fill( 's' );
		await form.getByLabel( 'Presentation' ).selectOption( 'static' );
		await form.getByLabel( 'Cutaway' ).check();
		await page.getByRole( 'button', { name: 'Add an item' } ).click();
		await form.getByLabel( 'Target kind' ).selectOption( 'word' );
		await form.getByLabel( 'Target', { exact: true } ).fill( 'ship' );
		await form.getByLabel( 'Audio' ).selectOption( 'lowpass' );
		await form.getByLabel( 'Low-pass cut-off, Hz' ).fill( '800' );
		await form.getByLabel( /^Speed/ ).fill( '5' );
		let state = await author( page );
		assert.deepEqual( state.items, [ 's', 'ship' ] );
		assert.equal( state.selected, 1 );

		// Too fast for the server: its message is shown under the speed, and nothing is saved.
		await page.getByRole( 'button', { name: 'Save', exact: true } ).click();
		await waitAuthor( page, () => Object.keys( window.glasshead.author.errors ).includes( 'items.1.speed' ) );
		const speedError = form.locator( '.le-row', { has: page.getByLabel( /^Speed/ ) } ).getByRole( 'alert' );
		assert.match( await speedError.textContent(), /less than or equal to 1/ );
		assert.equal( await form.getByLabel( /^Speed/ ).getAttribute( 'aria-invalid' ), 'true' );
		assert.equal( ( await author( page ) ).lesson, null );
		await form.getByLabel( /^Speed/ ).fill( '0.5' );
		assert.equal( await speedError.isVisible(), false, 'the message goes when the field changes' );

		// The preview says the selected item with its own settings.
		await waitAuthor( page, () => window.glasshead.author.preview?.target?.text === 'ship' && window.glasshead.author.preview.settings?.speed === 0.5 && window.glasshead.author.preview.busy === false, null, 180_000 );
		state = await author( page );
		assert.equal( state.preview.settings.speed, 0.5 );
		assert.equal( state.preview.settings.hold, false );
		await page.getByRole( 'list', { name: 'Items' } ).getByRole( 'button', { name: /^1 Sound/ } ).click();
		await waitAuthor( page, () => window.glasshead.author.preview?.target?.text === 's' && window.glasshead.author.preview.busy === false, null, 120_000 );
		state = await author( page );
		assert.equal( state.preview.settings.cutaway, true );
		assert.equal( state.preview.settings.hold, true, 'a static item holds its target' );
		await page.getByRole( 'button', { name: 'Play the preview' } ).click();
		await waitAuthor( page, () => window.glasshead.speech?.playing === true || window.glasshead.speech?.time > 0, null, 30_000 );

		// The tongue tip named and seen from the front without the cutaway: the preview flags that
		// the jaw hides it; back in profile with the cutaway, the flag goes.
		await form.getByLabel( 'Labels', { exact: true } ).selectOption( 'chosen' );
		assert.equal( await form.getByLabel( 'tongue tip' ).isChecked(), true, 'choosing starts from the tongue tip' );
		await form.getByLabel( 'Seen from' ).selectOption( 'front' );
		await form.getByLabel( 'Cutaway' ).uncheck();
		await waitAuthor( page, () => window.glasshead.author.preview?.settings?.camera === 'front' && window.glasshead.author.preview.busy === false && window.glasshead.author.preview.hidden.length > 0, null, 120_000 );
		const warning = page.locator( '.le-preview-warning' );
		assert.match( await warning.textContent(), /bone hides the tongue tip/ );
		await form.getByLabel( 'Seen from' ).selectOption( 'profile' );
		await form.getByLabel( 'Cutaway' ).check();
		await waitAuthor( page, () => window.glasshead.author.preview?.settings?.camera === 'profile' && window.glasshead.author.preview.settings.cutaway && window.glasshead.author.preview.busy === false, null, 120_000 );
		assert.deepEqual( ( await author( page ) ).preview.hidden, [] );
		assert.equal( await warning.isVisible(), false );

		await page.getByRole( 'button', { name: 'Save', exact: true } ).click();
		await waitAuthor( page, () => window.glasshead.author.lesson !== null && window.glasshead.author.dirty === false );
		state = await author( page );
		assert.match( page.url(), new RegExp( `#/author\\?lesson=${ state.lesson }$` ) );
		assert.deepEqual( await smallControls( page ), [], 'every control of the editor is finger-sized at 1366x768' );
		await saveScreenshot( page, 'author-1366x768' );

		await page.reload();
		await waitAuthor( page, ( id ) => window.glasshead?.author?.screen === 'editor' && window.glasshead.author.lesson === id, state.lesson );
		const reloaded = await author( page );
		assert.equal( reloaded.title, 'Sun and ship' );
		assert.deepEqual( reloaded.items, [ 's', 'ship' ] );
		assert.equal( reloaded.dirty, false );
		const session = await apiSession( server, 'author' );
		const stored = await ( await fetch( `${ server.baseUrl }/api/v1/lessons/${ state.lesson }`, { headers: authHeaders( session ) } ) ).json();
		assert.deepEqual( stored.items.map( ( item ) => [ item.target.kind, item.target.text, item.presentation, item.speed, item.audio.kind, item.audio.cutoff_hz, item.views.cutaway, item.views.labels ] ), [
			[ 'phoneme', 's', 'static', 1, 'natural', null, true, [ 'tongue_tip' ] ],
			[ 'word', 'ship', 'dynamic', 0.5, 'lowpass', 800, false, false ],
		] );
		// The refused save is the one request that failed, as the test meant it to.
		assert.deepEqual( page.problems.filter( ( problem ) => ! /status of 422/.test( problem ) ), [] );
		await page.close();

	} );

	test( 'a save over someone else’s newer version gets the plain 412 message, keeps the edits and can overwrite', async () => {

		const session = await apiSession( server, 'author' );
		const made = await fetch( `${ server.baseUrl }/api/v1/lessons`, {
			method: 'POST', headers: authHeaders( session, { 'Content-Type': 'application/json' } ),
			body: JSON.stringify( { title: 'Nasals', items: [ { target: { kind: 'phoneme', text: 'm' } }, { target: { kind: 'word', text: 'bee' } } ] } ),
		} );
		assert.equal( made.status, 201 );
		const lesson = await made.json();
		const page = await openEditor( [ 768, 1024 ], `#/author?lesson=${ lesson.id }` );
		await waitAuthor( page, ( id ) => window.glasshead?.author?.screen === 'editor' && window.glasshead.author.lesson === id, lesson.id );
		await waitAuthor( page, () => window.glasshead.author.preview?.target?.text === 'm' && window.glasshead.author.preview.busy === false, null, 180_000 );
		await saveScreenshot( page, 'author-768x1024' );
		assert.deepEqual( await smallControls( page ), [], 'every control of the editor is finger-sized at 768x1024' );

		// Someone else saves a new title meanwhile.
		const theirs = await fetch( `${ server.baseUrl }/api/v1/lessons/${ lesson.id }`, {
			method: 'PATCH', headers: authHeaders( session, { 'Content-Type': 'application/json' } ), body: JSON.stringify( { title: 'Nasals (their version)' } ),
		} );
		assert.equal( theirs.status, 200 );

		await page.getByLabel( 'Description' ).fill( 'my notes' );
		await page.getByRole( 'button', { name: 'Move down item 1' } ).click();
		await page.getByRole( 'button', { name: 'Save', exact: true } ).click();
		await waitAuthor( page, () => window.glasshead.author.conflict === true );
		const alert = page.locator( '.le-conflict' );
		assert.match( await alert.textContent(), /Someone else changed this lesson/ );
		await saveScreenshot( page, 'author-conflict-768x1024' );
		let state = await author( page );
		assert.equal( state.dirty, true );
		assert.deepEqual( state.items, [ 'bee', 'm' ], 'the edits are kept' );
		assert.equal( await page.getByLabel( 'Description' ).inputValue(), 'my notes' );

		// Closed or reloaded before deciding: the edits come back, and saving them is still a 412.
		await page.reload();
		await waitAuthor( page, ( id ) => window.glasshead?.author?.screen === 'editor' && window.glasshead.author.lesson === id, lesson.id );
		state = await author( page );
		assert.equal( state.dirty, true );
		assert.deepEqual( state.items, [ 'bee', 'm' ], 'the edits are back after a reload' );
		assert.equal( await page.getByLabel( 'Description' ).inputValue(), 'my notes' );
		await page.getByRole( 'button', { name: 'Save', exact: true } ).click();
		await waitAuthor( page, () => window.glasshead.author.conflict === true );

		await page.getByRole( 'button', { name: 'Overwrite with mine' } ).click();
		await waitAuthor( page, () => window.glasshead.author.conflict === false && window.glasshead.author.dirty === false );
		const stored = await ( await fetch( `${ server.baseUrl }/api/v1/lessons/${ lesson.id }`, { headers: authHeaders( session ) } ) ).json();
		assert.equal( stored.description, 'my notes' );
		assert.deepEqual( stored.items.map( ( item ) => item.target.text ), [ 'bee', 'm' ] );
		assert.equal( stored.title, 'Nasals', 'the overwrite is the author’s whole lesson' );
		assert.deepEqual( page.problems.filter( ( problem ) => ! /status of 412/.test( problem ) ), [] );
		await page.close();

	} );

} );
