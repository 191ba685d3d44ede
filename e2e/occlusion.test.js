// End-to-end: nothing draws through opaque skin, in Debian's Chromium. The electrodes' see-through
// pass (on while the skin is see-through or cut away) lies behind the opaque skin of the kept half
// in the Front view with the cutaway on; the pixel at each electrode must be the skin that covers
// it, as it is with the cut off (no see-through pass). Screenshots are for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { colourDistance as distance, pagePixel as pixel } from './png.js';
import { openLoaded, readDebug, saveScreenshot, serverAndBrowser, settle } from './harness.js';

/** RGB distance within which two renders of the same skin count as the same colour. */
const SAME_COLOUR = 10;
/** mm: electrodes this far into the kept half (z >= 0), clear of the cutting plane. */
const KEPT_Z = 3;

describe( 'nothing draws through opaque skin', { timeout: 240_000 }, () => {

	let server, browser;

	serverAndBrowser( ( running ) => ( { server, browser } = running ) );

	test( 'in the Front view with the cutaway on, the electrodes behind the opaque skin are not seen', async () => {

		const page = await openLoaded( browser, `${ server.baseUrl }/#/` );
		await page.waitForFunction( () => window.glasshead.electrodes?.points?.length > 0, null, { timeout: 60_000 } );
		await page.getByRole( 'button', { name: 'Front', exact: true } ).click();
		await settle( page );
		const probe = ( await readDebug( page ) ).electrodes;
		assert.equal( probe.xray, false, 'no see-through pass on opaque skin without the cut' );
		const kept = probe.points.filter( ( e ) => e.point[ 2 ] > KEPT_Z && e.x !== null );
		assert.ok( kept.length >= 20, `only ${ kept.length } electrodes in the kept half are on the canvas` );
		const uncut = [];
		for ( const e of kept ) uncut.push( await pixel( page, e.x, e.y ) );
		await page.getByRole( 'button', { name: 'Cutaway' } ).click();
		await settle( page );
		const after = ( await readDebug( page ) ).electrodes;
		assert.equal( after.xray, true, 'the cut turns the see-through pass on' );
		await saveScreenshot( page, 'occlusion-front-cutaway' );
		const worst = { d: 0, at: null };
		for ( const [ i, e ] of kept.entries() ) {

			const seen = await pixel( page, e.x, e.y );
			const d = distance( seen, uncut[ i ] );
			if ( d > worst.d ) Object.assign( worst, { d, at: e.point, seen, uncut: uncut[ i ] } );

		}

		assert.ok( worst.d < SAME_COLOUR, `at the electrode ${ worst.at } the skin ${ worst.uncut } became ${ worst.seen } with the cut on` );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

	test( 'in the workbench with the skin on, the lips and skin cover the contacts (screenshot)', async () => {

		const page = await openLoaded( browser, `${ server.baseUrl }/#/workbench` );
		const skin = page.getByRole( 'button', { name: 'Skin', exact: true } );
		await skin.click();
		await settle( page );
		assert.equal( await skin.getAttribute( 'aria-pressed' ), 'true' );
		await saveScreenshot( page, 'occlusion-workbench-skin' );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

} );
