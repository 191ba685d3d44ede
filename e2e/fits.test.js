// End-to-end test of the fit page in Debian's Chromium: a clinician chooses JD3's /a/ contour and
// one frame of sensors (the lower incisor and lips of a jaw opened 6 degrees) on #/fits, weighs the
// sensors twice, starts the fit, follows its progress to the end, reads each measurement's error,
// and opens the result among the clinician's targets. A surface with another file is refused in
// words before anything is sent. Screenshots: e2e/screenshots/fits-*.png.

import assert from 'node:assert/strict';
import { readFile, mkdtemp, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, test } from 'node:test';
import { createAccounts, signIn } from './accounts.js';
import { axeViolations } from './axe.js';
import { openPage, readDebug, REPO, saveScreenshot, serverAndBrowser } from './harness.js';

/** The lower incisor and the lips of the head with its jaw open 6 degrees (docs/fits.md). */
const SENSORS = 'point,x_mm,y_mm,z_mm\nlower_incisor,22.9,-14.0,0\nupper_lip,37.1,-2.6,0\nlower_lip,31.4,-13.6,0\n';

describe( 'fitting a target from the browser', { timeout: 600_000 }, () => {

	let server, browser, files;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		await createAccounts( server, [ 'clinician', 'author' ] );
		const shapes = JSON.parse( await readFile( join( REPO, 'assets', 'build', 'vtl-observations.json' ), 'utf8' ) ).shapes;
		const outline = shapes.find( ( shape ) => shape.name === 'a' ).tongue_outline;
		const dir = await mkdtemp( join( tmpdir(), 'glasshead-fits-' ) );
		files = { contour: join( dir, 'jd3-a.csv' ), ema: join( dir, 'sensors.csv' ), surface: join( dir, 'tongue.obj' ) };
		await writeFile( files.contour, 'x_mm,y_mm\n' + outline.map( ( [ x, y ] ) => `${ x },${ y }` ).join( '\n' ) + '\n' );
		await writeFile( files.ema, SENSORS );
		await writeFile( files.surface, 'v 0 0 0\n' );

	} );

	/** A page signed in as `role` on #/fits, and its form once shown. */
	async function openFitPage( role, size ) {

		const page = await openPage( browser, size );
		await signIn( page, server, role );
		await page.goto( `${ server.baseUrl }/#/fits` );
		const form = page.getByRole( 'form', { name: 'Fit a target' } );
		await form.waitFor();
		return { page, form };

	}

	test( 'a clinician fits a contour and sensors together, follows it, and opens the target', async () => {

		const { page, form } = await openFitPage( 'clinician', { width: 1366, height: 768 } );
		assert.equal( await page.getByRole( 'link', { name: 'Fit', exact: true } ).count(), 1, 'the bar links to the page for a clinician' );

		const start = form.getByRole( 'button', { name: 'Start the fit' } );
		assert.equal( await start.isDisabled(), true, 'nothing to fit yet' );
		await form.getByLabel( 'Tongue surface' ).setInputFiles( files.surface );
		await form.getByLabel( 'Sensors (EMA)' ).setInputFiles( files.ema );
		assert.match( ( await readDebug( page ) ).fits.message, /surface is fitted alone/ );
		assert.equal( await start.isDisabled(), true );
		await form.getByLabel( 'Tongue surface' ).setInputFiles( [] );
		await form.getByLabel( 'Tongue contour' ).setInputFiles( files.contour );
		assert.equal( ( await readDebug( page ) ).fits.kind, 'combined' );
		const weight = form.locator( '#fit-weight-ema' );
		assert.equal( await weight.isVisible(), true, 'a combined fit shows the weights' );
		await weight.fill( '2' );
		await form.getByLabel( 'Target name' ).fill( 'JD3 /a/ with an open jaw' );
		await start.click();

		await page.waitForFunction( () => [ 'running', 'done' ].includes( window.glasshead.fits?.fit?.state ), null, { timeout: 60_000, polling: 100 } );
		const progress = page.locator( '.fits-progress' );
		assert.match( await progress.textContent(), /JD3 \/a\/ with an open jaw \(combined\)/ );
		await page.waitForFunction( () => [ 'done', 'failed' ].includes( window.glasshead.fits.fit.state ), null, { timeout: 120_000, polling: 200 } );
		const { fit } = ( await readDebug( page ) ).fits;
		assert.equal( fit.state, 'done', fit.message );
		assert.deepEqual( Object.keys( fit.report.terms ), [ 'contour', 'ema' ] );
		assert.equal( fit.report.terms.ema.weight, 20, 'the weight went with the upload' );
		assert.ok( fit.report.terms.ema.rms_mm < 1, `the sensors are met: ${ fit.report.terms.ema.rms_mm } mm` );
		assert.ok( Math.abs( fit.params.jaw_opening - 6 ) < 0.5, `the jaw the sensors ask for: ${ fit.params.jaw_opening }` );
		const result = page.getByRole( 'list', { name: 'How closely the target matches' } );
		assert.match( await result.textContent(), /^contour \d\.\d\d mm RMS \(weight 1\)sensors \d\.\d\d mm RMS \(weight 20\)$/ );
		assert.match( await page.getByRole( 'status' ).first().textContent(), /The fit is done: contour/ );
		await page.waitForFunction( ( id ) => window.glasshead.fits.recent.some( ( f ) => f.id === id && f.state === 'done' ), fit.id, { timeout: 10_000 } );
		await saveScreenshot( page, 'fits-done-1366x768' );
		assert.deepEqual( await axeViolations( page, { include: '.fits-view' } ), [], 'the fit page with a finished fit' );

		await page.getByRole( 'link', { name: 'Open it among the clinician’s targets' } ).click();
		await page.waitForFunction( () => window.glasshead.clinician?.loaded === true && window.glasshead.clinician.target !== null, null, { timeout: 90_000, polling: 200 } );
		const { clinician } = await readDebug( page );
		assert.equal( clinician.target.name, `fit:${ fit.id }` );
		assert.equal( clinician.target.label, 'JD3 /a/ with an open jaw' );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

	test( 'on a tablet the form fits the screen, and an author may fit too', async () => {

		const { page, form } = await openFitPage( 'author', { width: 768, height: 1024 } );
		await form.getByLabel( 'Sensors (EMA)' ).setInputFiles( files.ema );
		assert.equal( ( await readDebug( page ) ).fits.kind, 'ema' );
		assert.equal( await form.locator( '#fit-weight-ema' ).isVisible(), false, 'one file has no weights' );
		const overflow = await page.evaluate( () => document.documentElement.scrollWidth - document.documentElement.clientWidth );
		assert.equal( overflow, 0, 'nothing runs off the side' );
		assert.equal( ( await readDebug( page ) ).fits.message, 'A fit to the sensors.' );
		await page.waitForFunction( () => window.glasshead.fits.recent.length > 0, null, { timeout: 10_000 } );
		await page.locator( '.fits-view' ).evaluate( ( element ) => element.scrollTo( 0, 0 ) );
		await saveScreenshot( page, 'fits-tablet-768x1024' );
		assert.deepEqual( await axeViolations( page, { include: '.fits-view' } ), [], 'the fit page on a tablet' );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

} );
