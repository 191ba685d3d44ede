// End-to-end: the workbench's cue layer in Debian's Chromium at 1920 x 1080. The cues switch on
// and off, lowering the velum gives the nasal flow strength, raising the tongue tip makes the
// oral flow turbulent, and a hidden layer draws nothing while the head is still. Assertions read
// `window.glasshead`; the screenshots cues-profile and cues-nasal are for a person to look at.

import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { launchBrowser, openLoaded, readDebug, saveScreenshot, settle, startServer } from './harness.js';

describe( 'the cues', { timeout: 240_000 }, () => {

	let server, browser, page;

	before( async () => {

		server = await startServer();
		browser = await launchBrowser();
		page = await openLoaded( browser, `${ server.baseUrl }/#/workbench`, { width: 1920, height: 1080 } );

	} );

	after( async () => {

		await browser?.close();
		await server?.stop();

	} );

	const cues = () => page.getByRole( 'group', { name: 'Cues' } );
	const button = ( name ) => cues().getByRole( 'button', { name, exact: true } );
	const slider = ( name ) => page.getByRole( 'slider', { name, exact: true } );

	async function setParam( name, label, value ) {

		await slider( label ).fill( String( value ) );
		await page.waitForFunction( ( [ n, v ] ) => window.glasshead.params[ n ] === v, [ name, value ] );

	}

	/** Out from the mouth to the whole tract, larynx to nose, for the screenshot. */
	async function zoomOut() {

		const box = await page.locator( '.wb-stage canvas' ).boundingBox();
		await page.mouse.move( box.x + box.width * 0.55, box.y + box.height * 0.6 );
		for ( let k = 0; k < 3; k ++ ) await page.mouse.wheel( 0, 250 );
		await settle( page );
		await page.waitForTimeout( 300 );

	}

	test( 'the cues are off by default, and a still workbench without them draws nothing', async () => {

		const state = await readDebug( page );
		assert.deepEqual( state.cues, { visible: false, voicing: true, nasal: true, oral: true, turbulence: false, nasalStrength: state.cues.nasalStrength } );
		assert.equal( await button( 'Voicing' ).isVisible(), false, 'the cue switches show with the layer' );
		await page.waitForTimeout( 1000 );
		assert.equal( ( await readDebug( page ) ).frames, state.frames, 'no frames while nothing moves' );

	} );

	test( 'the Cues toggle shows the layer, and it animates', async () => {

		await button( 'Cues' ).click();
		const before = await readDebug( page );
		assert.equal( before.cues.visible, true );
		assert.equal( await button( 'Voicing' ).getAttribute( 'aria-pressed' ), 'true' );
		assert.equal( await button( 'Oral airflow' ).getAttribute( 'aria-pressed' ), 'true' );
		// Frames come as fast as the machine allows (software WebGL): wait for a few.
		await page.waitForFunction( ( frames ) => window.glasshead.frames > frames + 3, before.frames, { timeout: 60_000, polling: 100 } );

	} );

	test( 'a raised velum gives no nasal flow and hides its switch; lowering it gives the flow strength', async () => {

		await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
		await setParam( 'velum_opening', 'Velum opening', 0 );
		await page.waitForFunction( () => window.glasshead.cues.nasalStrength === 0 );
		assert.equal( await button( 'Nasal airflow' ).isVisible(), false, 'no nasal switch with the port closed' );
		await setParam( 'velum_opening', 'Velum opening', 1 );
		await page.waitForFunction( () => window.glasshead.cues.nasalStrength > 0 );
		const { cues: state, velum } = await readDebug( page );
		assert.ok( state.nasalStrength > 0.9, `nasal strength ${ state.nasalStrength } at a port of ${ velum.nasalPortAreaMm2 } mm2` );
		assert.equal( await button( 'Nasal airflow' ).isVisible(), true );
		await page.waitForTimeout( 300 );
		await saveScreenshot( page, 'cues-nasal' );
		await setParam( 'velum_opening', 'Velum opening', 0 );

	} );

	test( 'raising the tongue tip to the ridge makes the oral flow turbulent', async () => {

		// The lips at rest are 1.75 mm apart (a closed mouth): raise the upper lip, as for a vowel.
		await setParam( 'velum_opening', 'Velum opening', 0 );
		await setParam( 'upper_lip_raise', 'Upper lip raise', 4 );
		await page.waitForFunction( () => window.glasshead.constriction.widthMm > 2 );
		assert.equal( ( await readDebug( page ) ).cues.turbulence, false, 'no turbulence with the mouth open' );
		await setParam( 'tip_height', 'Tip height', 8 );
		await setParam( 'tip_advancement', 'Tip advancement', 2 );
		await setParam( 'blade_height', 'Blade height', 5 );
		await page.waitForFunction( () => window.glasshead.constriction.widthMm < 2 );
		const { cues: state, constriction } = await readDebug( page );
		assert.equal( state.turbulence, true, `turbulent at a constriction of ${ constriction.widthMm } mm` );
		await setParam( 'velum_opening', 'Velum opening', 1 );
		await zoomOut();
		await saveScreenshot( page, 'cues-profile' );
		await button( 'Oral airflow' ).click();
		assert.equal( ( await readDebug( page ) ).cues.turbulence, false, 'no turbulence without the oral flow' );
		await button( 'Oral airflow' ).click();

	} );

	test( 'switching the cues off stops the drawing, and no console errors appeared', async () => {

		await button( 'Cues' ).click();
		assert.equal( ( await readDebug( page ) ).cues.visible, false );
		await settle( page );
		const before = await readDebug( page );
		await page.waitForTimeout( 1000 );
		assert.equal( ( await readDebug( page ) ).frames, before.frames, 'no frames once the cues are off' );
		assert.deepEqual( page.problems, [] );

	} );

} );
