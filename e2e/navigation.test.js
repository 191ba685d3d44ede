// End-to-end tests of finding one's way in Debian's Chromium: the navigation bar on every view,
// the head view's first-run hint, and the head view's chooser of targets posing the tongue so
// that its palatogram shows contact. Screenshots of every view at four window sizes are in
// e2e/screenshots/nav-*.png for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { openSignedIn } from './accounts.js';
import { animationFrames, openLoaded, readDebug, saveScreenshot, serverAndBrowser, settle, waitForLoaded } from './harness.js';

const VIEWS = [
	{ path: '/', label: 'Head' },
	{ path: '/workbench', label: 'Workbench' },
	{ path: '/clinician', label: 'Clinician' },
	{ path: '/speak', label: 'Speak' },
	{ path: '/listen', label: 'Listen' },
	// For the clinician signed in here (authors and admins see it too).
	{ path: '/fits', label: 'Fit' },
];
const SIZES = [ [ 1366, 768 ], [ 1920, 1080 ], [ 1024, 768 ], [ 768, 1024 ] ];
/** Smallest touch target, CSS pixels. */
const TOUCH_PX = 44;

describe( 'finding one\'s way', { timeout: 1_200_000 }, () => {

	let server, browser, page;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		// A clinician: the clinician view and saving poses need one signed in.
		page = await openSignedIn( browser, server, 'clinician', `${ server.baseUrl }/#/`, { width: 1366, height: 768 } );

	} );

	const nav = ( target = page ) => target.getByRole( 'navigation', { name: 'Views' } );

	async function waitForView( target, path ) {

		await target.waitForFunction( ( wanted ) => window.glasshead?.route === wanted, path, { timeout: 60_000 } );
		// The clinician view reports under window.glasshead.clinician, the others at the top.
		await target.waitForFunction( () => window.glasshead.loaded === true || window.glasshead.clinician?.loaded === true || Boolean( window.glasshead.error ), null, { timeout: 300_000, polling: 200 } );
		assert.equal( ( await readDebug( target ) ).error ?? null, null, `${ path } reported an error` );

	}

	/** The nav's links to views as { label, href, current, height, width }, in order. */
	function readNav( target ) {

		return target.evaluate( () => [ ...document.querySelectorAll( 'nav[aria-label="Views"] .nav-list a' ) ].map( ( link ) => {

			const box = link.getBoundingClientRect();
			return { label: link.textContent, href: link.getAttribute( 'href' ), current: link.getAttribute( 'aria-current' ), height: box.height, width: box.width };

		} ) );

	}

	/** Where the bar and the views' container are, and whether any control of the view lies under the bar. */
	function readLayout( target ) {

		return target.evaluate( () => {

			const bar = document.querySelector( 'nav[aria-label="Views"]' ).getBoundingClientRect();
			const app = document.getElementById( 'app' ).getBoundingClientRect();
			const covered = [ ...document.querySelectorAll( '#app button, #app input, #app select, #app a, #app textarea' ) ]
				.filter( ( control ) => {

					const box = control.getBoundingClientRect();
					return box.width > 0 && box.height > 0 && box.top < bar.bottom - 0.5 && box.bottom > bar.top;

				} ).map( ( control ) => control.getAttribute( 'aria-label' ) ?? control.textContent.trim() );
			return { barBottom: bar.bottom, barHeight: bar.height, appTop: app.top, appBottom: app.bottom, innerHeight: window.innerHeight, covered };

		} );

	}

	test( 'the nav on every view is touch-sized, marks that view, lies above it at four window sizes, and its links reach every other view', async () => {

		// Head -> Workbench -> Clinician -> Speak -> Head, each step by a click on the bar.
		for ( const [ k, view ] of [ ...VIEWS, VIEWS[ 0 ] ].entries() ) {

			await page.setViewportSize( { width: 1366, height: 768 } );
			if ( k > 0 ) await nav().getByRole( 'link', { name: view.label, exact: true } ).click();
			await waitForView( page, view.path );
			const links = await readNav( page );
			assert.deepEqual( links.map( ( link ) => link.label ), VIEWS.map( ( v ) => v.label ) );
			assert.deepEqual( links.map( ( link ) => link.href ), VIEWS.map( ( v ) => `#${ v.path }` ) );
			assert.deepEqual( links.filter( ( link ) => link.current === 'page' ).map( ( link ) => link.label ), [ view.label ], `on ${ view.path }` );
			for ( const link of links ) assert.ok( link.height >= TOUCH_PX && link.width >= TOUCH_PX, `${ link.label } is ${ link.width } x ${ link.height } px on ${ view.path }` );
			if ( k === VIEWS.length ) break; // back at the head: its sizes were seen on the way out
			for ( const [ width, height ] of SIZES ) {

				await page.setViewportSize( { width, height } );
				await animationFrames( page ); // what a resize sets off (resize observers) has run
				const layout = await readLayout( page );
				const where = `${ view.path } at ${ width }x${ height }`;
				assert.ok( layout.appTop >= layout.barBottom - 0.5, `${ where }: the views start at ${ layout.appTop } px, the bar ends at ${ layout.barBottom } px` );
				assert.ok( Math.abs( layout.appBottom - layout.innerHeight ) <= 0.5, `${ where }: the views end at ${ layout.appBottom } px of ${ layout.innerHeight }` );
				assert.ok( layout.barHeight <= 60, `${ where }: the bar is ${ layout.barHeight } px tall` );
				assert.deepEqual( layout.covered, [], `${ where }: controls under the bar` );
				await saveScreenshot( page, `nav-${ view.label.toLowerCase() }-${ width }x${ height }` );

			}

		}

		assert.deepEqual( page.problems, [] );

	} );

	test( 'the first Tab reaches the nav; the first-run hint on the head view, once dismissed, stays dismissed after a reload', async () => {

		const fresh = await openLoaded( browser, `${ server.baseUrl }/#/`, { width: 1366, height: 768 } );
		await fresh.keyboard.press( 'Tab' );
		assert.equal( await fresh.evaluate( () => document.activeElement?.closest( 'nav' )?.getAttribute( 'aria-label' ) ?? null ), 'Views', 'the first Tab goes to the nav' );
		const hint = fresh.getByRole( 'complementary', { name: 'Hint' } );
		assert.match( await hint.textContent(), /Drag to turn the head, pinch or scroll to zoom/ );
		await hint.getByRole( 'button', { name: 'Got it' } ).click();
		assert.equal( await hint.count(), 0 );
		await fresh.reload();
		await waitForLoaded( fresh );
		assert.equal( await fresh.getByRole( 'complementary', { name: 'Hint' } ).count(), 0 );
		assert.deepEqual( fresh.problems, [] );
		await fresh.context().close();

	} );

	test( 'choosing the phoneme target /t/ on the head view poses the tongue: its EPG card shows contact', async () => {

		await page.setViewportSize( { width: 1366, height: 768 } );
		await waitForView( page, '/' );
		await settle( page );
		const before = await readDebug( page );
		assert.equal( before.epg.contacted, 0, 'the rest tongue touches no electrode' );
		const chooser = page.getByLabel( 'Show a pose or sound' );
		await page.waitForFunction( () => document.querySelector( '#head-target option[value="phoneme:T"]' ) !== null, null, { timeout: 30_000 } );
		await chooser.selectOption( 'phoneme:T' );
		await page.waitForFunction( () => window.glasshead.headTarget?.name === 'phoneme:T', null, { timeout: 30_000 } );
		await settle( page );
		const after = await readDebug( page );
		assert.ok( after.epg.contacted > 0, `the /t/ target contacts ${ after.epg.contacted } electrodes` );
		const caption = await page.locator( '.epg-overlay figcaption' ).textContent();
		assert.ok( Number.parseInt( caption, 10 ) > 0, `the card reads "${ caption }"` );
		await saveScreenshot( page, 'nav-head-target-t' );
		await chooser.selectOption( '' );
		await page.waitForFunction( () => window.glasshead.headTarget?.name === '', null, { timeout: 30_000 } );
		assert.equal( ( await readDebug( page ) ).epg.contacted, 0, 'back at rest, no contact' );
		assert.deepEqual( page.problems, [] );

	} );

	test( 'a pose name that is too long is refused in plain words, on screen next to Save at 1366 x 768', async () => {

		await nav().getByRole( 'link', { name: 'Workbench', exact: true } ).click();
		await waitForView( page, '/workbench' );
		await page.getByRole( 'textbox', { name: 'Pose name' } ).fill( 'n'.repeat( 121 ) );
		const save = page.getByRole( 'button', { name: 'Save pose' } );
		await save.scrollIntoViewIfNeeded();
		await save.click();
		await page.waitForFunction( () => window.glasshead.workbench.poseStatus !== null, null, { timeout: 60_000 } );
		const status = ( await readDebug( page ) ).workbench.poseStatus;
		assert.deepEqual( status, { ok: false, message: 'Names can be at most 120 characters. Shorten the name and save again.' } );
		const message = page.getByRole( 'alert' ).filter( { hasText: 'Names can be at most 120 characters' } );
		const [ box, button ] = [ await message.boundingBox(), await save.boundingBox() ];
		assert.ok( box && box.y >= 0 && box.y + box.height <= 768, `the message is at y ${ box?.y } to ${ box && box.y + box.height } px of 768` );
		assert.ok( box.y - ( button.y + button.height ) < 120, `the message is ${ box.y - ( button.y + button.height ) } px under the Save button` );
		await saveScreenshot( page, 'nav-workbench-save-message' );
		assert.deepEqual( page.problems.filter( ( problem ) => ! problem.includes( '422' ) ), [] );

	} );

} );
