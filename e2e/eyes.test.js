// End-to-end: the eyes of the head view in Debian's Chromium. Two eyes, a gaze that follows the
// camera between views, blinks now and then; screenshots of the default view and a front close-up
// in e2e/screenshots/ are for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { openLoaded, readDebug, saveScreenshot, serverAndBrowser, settle, waitForStill } from './harness.js';

describe( 'the eyes', { timeout: 240_000 }, () => {

	let server, browser, page;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		page = await openLoaded( browser, `${ server.baseUrl }/#/` );

	} );

	async function showView( name ) {

		await page.getByRole( 'button', { name, exact: true } ).click();
		// The eyes settle after the camera: wait for a frame with nothing to draw, the gaze at its
		// target and no blink under way.
		await waitForStill( page );
		return ( await readDebug( page ) ).eyes;

	}

	test( 'two eyes are in the face, looking toward the camera in the three-quarter view', async () => {

		const eyes = await showView( 'Three-quarter' );
		assert.equal( eyes.count, 2 );
		assert.ok( Math.abs( eyes.gaze[ 0 ] ) > 10, `gaze ${ eyes.gaze } should turn toward a camera at the side` );
		assert.ok( Math.abs( eyes.gaze[ 0 ] ) <= 25 && Math.abs( eyes.gaze[ 1 ] ) <= 25 );
		await saveScreenshot( page, 'eyes-three-quarter' );

	} );

	test( 'the gaze turns when the camera view changes', async () => {

		const side = await showView( 'Three-quarter' );
		const front = await showView( 'Front' );
		assert.ok( Math.abs( front.gaze[ 0 ] ) < 5, `front gaze ${ front.gaze }` );
		assert.ok( Math.abs( side.gaze[ 0 ] - front.gaze[ 0 ] ) > 10 );
		await page.mouse.move( 490, 400 );
		for ( let i = 0; i < 4; i ++ ) await page.mouse.wheel( 0, - 400 );
		await waitForStill( page );
		await saveScreenshot( page, 'eyes-front-close' );
		assert.deepEqual( page.problems, [] );

	} );

	test( 'the eyes blink now and then', async () => {

		// Read at every animation frame: a blink starts in one and ends in a later one, however far
		// apart they are. Blinks come 4 to 9 s apart.
		await page.waitForFunction( () => window.glasshead.eyes.blinking === true, null, { timeout: 60_000, polling: 'raf' } );

	} );

	test( 'with the skin see-through the eyes look straight ahead', async () => {

		await page.getByRole( 'slider', { name: 'Skin transparency' } ).fill( '50' );
		await waitForStill( page );
		assert.deepEqual( ( await readDebug( page ) ).eyes.gaze, [ 0, 0 ] );
		await page.getByRole( 'slider', { name: 'Skin transparency' } ).fill( '0' );
		await settle( page );

	} );

} );
