// End-to-end: on the workbench the tongue meets the velum and the pharyngeal wall instead of
// passing through them, in Debian's Chromium. Assertions read window.glasshead.collision.tract;
// the screenshot (profile cutaway, 1920 x 1080) is for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { openPage, readDebug, saveScreenshot, serverAndBrowser, settle, waitForLoaded } from './harness.js';

describe( 'the tongue against the velum and the pharyngeal wall', { timeout: 300_000 }, () => {

	let server, browser;

	serverAndBrowser( ( running ) => ( { server, browser } = running ) );

	test( 'a raised back of the tongue flattens against a lowered velum, and a retracted root against the wall', async () => {

		const page = await openPage( browser, { width: 1920, height: 1080 } );
		await page.goto( `${ server.baseUrl }/#/workbench` );
		await waitForLoaded( page );
		const slider = ( name ) => page.getByRole( 'slider', { name, exact: true } );
		let state = await readDebug( page );
		assert.equal( state.collision.tract.enabled, true, 'the workbench collides the tongue with the tract' );
		// At rest the velum lies on the back of the tongue (it does in a real mouth too): a few vertices.
		const rest = state.collision.tract.corrected;
		assert.ok( rest < 20, `${ rest } vertices held at rest` );

		await slider( 'Velum opening' ).fill( '1' );
		await slider( 'Back dorsum height' ).fill( await slider( 'Back dorsum height' ).getAttribute( 'max' ) );
		await slider( 'Dorsum height' ).fill( await slider( 'Dorsum height' ).getAttribute( 'max' ) );
		await slider( 'Dorsum advancement' ).fill( await slider( 'Dorsum advancement' ).getAttribute( 'min' ) );
		await settle( page );
		state = await readDebug( page );
		const lowered = state.collision.tract.corrected;
		assert.ok( lowered > rest + 10, `a raised back meets the lowered velum: ${ lowered } vertices held on it, ${ rest } at rest` );
		await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
		await settle( page );
		await saveScreenshot( page, 'tract-velum-contact' );

		await slider( 'Velum opening' ).fill( '0' );
		await settle( page );
		state = await readDebug( page );
		assert.ok( state.collision.tract.corrected < lowered, `raising the velum frees the tongue: ${ state.collision.tract.corrected } held, ${ lowered } lowered` );

		await slider( 'Root advancement' ).fill( await slider( 'Root advancement' ).getAttribute( 'min' ) );
		await settle( page );
		state = await readDebug( page );
		assert.ok( state.collision.tract.tested > 0 );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

} );
