// End-to-end: the flat mid-sagittal diagram of the workbench and the constriction in Debian's
// Chromium at 1366 x 768, a projector's size. Assertions read `window.glasshead`; the screenshots
// diagram-rest, diagram-tip-raised (the panel) and diagram-workbench (the page) are for a person to
// look at.

import assert from 'node:assert/strict';
import { join } from 'node:path';
import { describe, test } from 'node:test';
import { decodePng } from './png.js';
import { openLoaded, readDebug, saveScreenshot, SCREENSHOT_DIR, serverAndBrowser, settle, waitForStill } from './harness.js';

describe( 'the diagram', { timeout: 240_000 }, () => {

	let server, browser, page;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		page = await openLoaded( browser, `${ server.baseUrl }/#/workbench`, { width: 1366, height: 768 } );

	} );

	const diagram = () => page.getByRole( 'img', { name: /^Diagram: the vocal tract/ } );
	const slider = ( name ) => page.getByRole( 'slider', { name, exact: true } );

	/** Distinct colours in the diagram's pixels (coarsely quantised): a drawing has several. */
	async function colours( name ) {

		await diagram().screenshot( { path: join( SCREENSHOT_DIR, `${ name }.png` ) } );
		const image = decodePng( await diagram().screenshot() );
		const seen = new Set();
		for ( let i = 0; i < image.data.length; i += 4 * 7 ) seen.add( ( image.data[ i ] >> 4 ) << 8 | ( image.data[ i + 1 ] >> 4 ) << 4 | ( image.data[ i + 2 ] >> 4 ) );
		return seen.size;

	}

	test( 'the diagram is drawn, and the constriction is reported with its width, place and name', async () => {

		const state = await readDebug( page );
		assert.ok( state.workbench.diagramDraws > 0, 'the diagram was drawn' );
		assert.equal( state.workbench.landmarksError, null );
		const { constriction } = state;
		assert.ok( constriction, 'window.glasshead.constriction is set' );
		assert.ok( constriction.widthMm > 0 && constriction.widthMm < 30, `width ${ constriction.widthMm } mm` );
		assert.ok( constriction.atMm >= 0, `at ${ constriction.atMm } mm` );
		assert.equal( typeof constriction.place, 'string' );
		assert.ok( await colours( 'diagram-rest' ) >= 6, 'air, tongue, bone, lips and lines in several colours' );

	} );

	test( 'raising the tongue tip narrows the constriction, toward the front', async () => {

		const rest = ( await readDebug( page ) ).constriction;
		await slider( 'Tip height' ).fill( '8' );
		await page.waitForFunction( () => window.glasshead.params.tip_height === 8 );
		await settle( page );
		const raised = ( await readDebug( page ) ).constriction;
		assert.ok( raised.widthMm < rest.widthMm, `tip raised ${ raised.widthMm } mm, rest ${ rest.widthMm } mm` );
		assert.ok( raised.atMm < 40, `tip raised at ${ raised.atMm } mm from the lips` );
		await colours( 'diagram-tip-raised' );
		await saveScreenshot( page, 'diagram-workbench' );

	} );

	test( 'a still workbench draws nothing more, and no console errors appeared', async () => {

		await waitForStill( page );
		const before = await readDebug( page );
		await page.waitForTimeout( 1500 );
		const later = await readDebug( page );
		assert.equal( later.frames, before.frames, 'no 3D frames while nothing changes' );
		assert.equal( later.workbench.diagramDraws, before.workbench.diagramDraws, 'no diagram redraws while nothing changes' );
		assert.deepEqual( page.problems, [] );

	} );

} );
