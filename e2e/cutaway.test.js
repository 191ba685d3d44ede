// End-to-end: the cutaway shows air, and lowering the velum opens the nasal port, in Debian's
// Chromium. Assertions read `window.glasshead`; the screenshots (projector 1920 x 1080, tablet
// 1024 x 768) are for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { colourDistance as distance, pagePixel as pixel } from './png.js';
import { openPage, readDebug, saveScreenshot, serverAndBrowser, settle, waitForLoaded } from './harness.js';

/** [r, g, b] of '#rrggbb'. */
const rgb = ( hex ) => [ 1, 3, 5 ].map( ( i ) => parseInt( hex.slice( i, i + 2 ), 16 ) );

describe( 'the cutaway shows air and the velum', { timeout: 300_000 }, () => {

	let server, browser;

	serverAndBrowser( ( running ) => ( { server, browser } = running ) );

	for ( const [ device, width, height ] of [ [ 'projector', 1920, 1080 ], [ 'tablet', 1024, 768 ] ] ) {

		test( `in the cutaway profile (${ device }), the oral cavity between tongue and palate is air, not tissue`, async () => {

			const page = await openPage( browser, { width, height } );
			await page.goto( `${ server.baseUrl }/#/` );
			await waitForLoaded( page );
			await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
			await settle( page );
			const before = ( await readDebug( page ) ).airProbe;
			assert.equal( before.visible, false, 'no air without the cut' );
			const solid = await pixel( page, before.x, before.y );
			await page.getByRole( 'button', { name: 'Cutaway' } ).click();
			await settle( page );
			const state = await readDebug( page );
			const probe = state.airProbe;
			assert.equal( probe.visible, true );
			assert.ok( probe.x > 0 && probe.x < width && probe.y > 0 && probe.y < height, `the air point ${ probe.point } is off the canvas at ${ probe.x }, ${ probe.y }` );
			const seen = await pixel( page, probe.x, probe.y );
			const air = rgb( probe.airColor );
			const tissue = rgb( probe.tissueColor );
			assert.ok( distance( seen, air ) < distance( seen, tissue ), `pixel ${ seen } at the air point is nearer the tissue colour ${ tissue } than the air ${ air }` );
			assert.ok( Math.min( ...seen ) > 170, `pixel ${ seen } at the air point is not light` );
			assert.notDeepEqual( seen, solid );
			assert.equal( state.velum.nasalPortAreaMm2 > 0, true, 'the velum at rest leaves the port open' );
			// The skull is not one tissue fill: the cranial cavity has its own colour.
			const cranial = state.cranialProbe;
			assert.equal( cranial.visible, true );
			const inside = await pixel( page, cranial.x, cranial.y );
			const brain = rgb( cranial.brainColor );
			assert.ok( distance( inside, brain ) < 12, `pixel ${ inside } in the cranial cavity at ${ cranial.point } is not the brain colour ${ brain }` );
			assert.ok( distance( inside, tissue ) > 40 && distance( inside, rgb( cranial.boneColor ) ) > 40, `pixel ${ inside } in the cranial cavity looks like tissue or bone` );
			// The kept eye lies behind the section, in its socket: its centre shows the cut tissue.
			const kept = state.eyes.centres.find( ( eye ) => eye.point[ 2 ] > 0 );
			const atEye = await pixel( page, kept.x, kept.y );
			assert.ok( distance( atEye, tissue ) < 25, `pixel ${ atEye } over the eyeball at ${ kept.point } is not the cut tissue ${ tissue }` );
			await saveScreenshot( page, `cutaway-air-${ device }` );
			assert.deepEqual( page.problems, [] );
			await page.context().close();

		} );

	}

	test( 'lowering the velum on the workbench opens the nasal port', async () => {

		const page = await openPage( browser, { width: 1920, height: 1080 } );
		await page.goto( `${ server.baseUrl }/#/workbench` );
		await waitForLoaded( page );
		const slider = page.getByRole( 'slider', { name: 'Velum opening', exact: true } );
		await slider.fill( '0' );
		await settle( page );
		let state = await readDebug( page );
		assert.equal( state.params.velum_opening, 0 );
		assert.deepEqual( state.velum, { opening: 0, nasalPortAreaMm2: 0 } );
		await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
		await settle( page );
		await saveScreenshot( page, 'velum-raised' );
		await slider.fill( '1' );
		await settle( page );
		state = await readDebug( page );
		assert.equal( state.velum.opening, 1 );
		assert.ok( state.velum.nasalPortAreaMm2 > 0, `the port is ${ state.velum.nasalPortAreaMm2 } mm² with the velum lowered` );
		await saveScreenshot( page, 'velum-lowered' );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

} );
