// End-to-end: the label layer of the head view in Debian's Chromium. Switches the labels on and
// off, hovers the tongue and reads the named part from `window.glasshead.labels`; screenshots at
// 1920 x 1080 and 1024 x 768 in e2e/screenshots/ are for a person to look at.

import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { launchBrowser, openLoaded, readDebug, saveScreenshot, settle, startServer } from './harness.js';

describe( 'the label layer', { timeout: 240_000 }, () => {

	let server, browser, page, landmarks;

	before( async () => {

		server = await startServer();
		landmarks = await ( await fetch( `${ server.baseUrl }/api/v1/anatomy/landmarks` ) ).json();
		browser = await launchBrowser();
		page = await openLoaded( browser, `${ server.baseUrl }/?still#/`, { width: 1920, height: 1080 } ); // no blinks: a still head must draw nothing

	} );

	after( async () => {

		await browser?.close();
		await server?.stop();

	} );

	const labelsButton = () => page.getByRole( 'button', { name: 'Labels' } );

	async function setLabels( on ) {

		if ( ( await labelsButton().getAttribute( 'aria-pressed' ) ) !== String( on ) ) await labelsButton().click();
		await settle( page );

	}

	test( 'the labels switch on and off', async () => {

		assert.deepEqual( ( await readDebug( page ) ).labels, { visible: false, count: 0, hovered: null } );
		await setLabels( true );
		const shown = landmarks.landmarks.filter( ( e ) => e.kind !== 'reference' ).length;
		let state = await readDebug( page );
		assert.equal( state.labels.visible, true );
		assert.equal( state.labels.count, shown );
		assert.ok( await page.getByText( 'alveolar ridge', { exact: true } ).isVisible() );
		await setLabels( false );
		state = await readDebug( page );
		assert.equal( state.labels.visible, false );
		assert.equal( await page.getByText( 'alveolar ridge', { exact: true } ).isVisible(), false );
		assert.deepEqual( page.problems, [] );

	} );

	test( 'a still head with its labels shown draws no new frames', async () => {

		await setLabels( true );
		const before = ( await readDebug( page ) ).frames;
		await new Promise( ( resolve ) => setTimeout( resolve, 2000 ) );
		const state = await readDebug( page );
		assert.equal( state.frames, before, 'the scene is redrawn while nothing moves' );
		assert.equal( state.renderPending, false );
		await setLabels( false );

	} );

	test( 'hovering the tongue in the cutaway profile names a part of the tongue', async () => {

		await page.getByRole( 'button', { name: 'Cutaway' } ).click();
		await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
		await settle( page );
		await setLabels( true );
		await saveScreenshot( page, 'labels-profile-1920' );
		// The tongue's back on the screen: project its landmark through the page's own camera by
		// reading where its dot is drawn.
		const dot = await page.evaluate( () => {

			const label = document.querySelector( '[data-landmark="tongue_back"]' );
			const circles = [ ...document.querySelectorAll( '.label-dot' ) ];
			const labels = [ ...document.querySelectorAll( '.label' ) ];
			const circle = circles[ labels.indexOf( label ) ];
			const box = circle.getBoundingClientRect();
			return { x: box.left + box.width / 2, y: box.top + box.height / 2 + 6 };

		} );
		await page.mouse.move( dot.x, dot.y );
		await page.waitForFunction( () => window.glasshead.labels.hovered !== null, null, { timeout: 10_000 } );
		const { hovered } = ( await readDebug( page ) ).labels;
		assert.match( hovered, /^tongue (tip|blade|front|back|root)$/ );
		assert.ok( await page.getByRole( 'status' ).filter( { hasText: hovered } ).isVisible() );
		await saveScreenshot( page, 'labels-hover-1920' );
		await page.setViewportSize( { width: 1024, height: 768 } );
		await settle( page );
		await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
		await settle( page );
		await saveScreenshot( page, 'labels-profile-1024' );
		assert.deepEqual( page.problems, [] );

	} );

} );
