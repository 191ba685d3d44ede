// End-to-end: the label layer of the head view in Debian's Chromium. Switches the labels on and
// off, hovers the tongue and reads the named part from `window.glasshead.labels`, and checks that
// no label lies under the EPG card or the side panel, or on another label, at 1920 x 1080 and
// 1024 x 768; screenshots of both in e2e/screenshots/ are for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { openLoaded, readDebug, saveScreenshot, serverAndBrowser, settle, waitForStill } from './harness.js';

describe( 'the label layer', { timeout: 240_000 }, () => {

	let server, browser, page, landmarks;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		landmarks = await ( await fetch( `${ server.baseUrl }/api/v1/anatomy/landmarks` ) ).json();
		page = await openLoaded( browser, `${ server.baseUrl }/?still#/`, { width: 1920, height: 1080 } ); // no blinks: a still head must draw nothing

	} );

	const labelsButton = () => page.getByRole( 'button', { name: 'Labels' } );

	/** Every shown label's box that covers the EPG card, the side panel or another label. */
	function clashes() {

		return page.evaluate( () => {

			const box = ( el ) => el.getBoundingClientRect();
			const meet = ( a, b ) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
			const labels = [ ...document.querySelectorAll( '.label-layer .label' ) ].map( ( el ) => ( { name: el.dataset.landmark, rect: box( el ) } ) );
			const panels = [ ...document.querySelectorAll( '.epg-overlay, .panel' ) ].map( ( el ) => ( { name: el.className, rect: box( el ) } ) );
			const found = [];
			labels.forEach( ( a, i ) => {

				for ( const p of panels ) if ( meet( a.rect, p.rect ) ) found.push( `${ a.name } on ${ p.name }` );
				for ( const b of labels.slice( 0, i ) ) if ( meet( a.rect, b.rect ) ) found.push( `${ a.name } on ${ b.name }` );

			} );
			return { found, labels: labels.length, panels: panels.length };

		} );

	}

	async function setLabels( on ) {

		if ( ( await labelsButton().getAttribute( 'aria-pressed' ) ) !== String( on ) ) await labelsButton().click();
		await settle( page );

	}

	test( 'the labels switch on and off', async () => {

		assert.deepEqual( ( await readDebug( page ) ).labels, { visible: false, count: 0, names: [], hidden: [], hovered: null, overlapping: 0 } );
		await setLabels( true );
		const shown = landmarks.landmarks.filter( ( e ) => e.kind !== 'reference' ).length;
		let state = await readDebug( page );
		assert.equal( state.labels.visible, true );
		assert.equal( state.labels.count, shown );
		assert.equal( state.labels.names.length, shown, 'every label is on show' );
		assert.ok( await page.getByText( 'alveolar ridge', { exact: true } ).isVisible() );
		await setLabels( false );
		state = await readDebug( page );
		assert.equal( state.labels.visible, false );
		assert.equal( await page.getByText( 'alveolar ridge', { exact: true } ).isVisible(), false );
		assert.deepEqual( page.problems, [] );

	} );

	test( 'a still head with its labels shown draws no new frames', async () => {

		await setLabels( true );
		await waitForStill( page );
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
		const wide = await clashes();
		assert.equal( wide.panels, 2, 'the EPG card and the side panel are on the page' );
		assert.ok( wide.labels > 10 );
		assert.deepEqual( wide.found, [], 'at 1920 x 1080' );
		assert.equal( ( await readDebug( page ) ).labels.overlapping, 0 );
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
		await page.waitForFunction( () => window.glasshead.labels.hovered !== null, null, { timeout: 60_000 } );
		const { hovered } = ( await readDebug( page ) ).labels;
		assert.match( hovered, /^tongue (tip|blade|front|back|root)$/ );
		assert.ok( await page.getByRole( 'status' ).filter( { hasText: hovered } ).isVisible() );
		await saveScreenshot( page, 'labels-hover-1920' );
		await page.setViewportSize( { width: 1024, height: 768 } );
		await settle( page );
		await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
		await settle( page );
		await page.mouse.move( 0, 0 );
		await saveScreenshot( page, 'labels-profile-1024' );
		assert.deepEqual( ( await clashes() ).found, [], 'at 1024 x 768' );
		assert.equal( ( await readDebug( page ) ).labels.overlapping, 0 );
		assert.deepEqual( page.problems, [] );

	} );

} );
