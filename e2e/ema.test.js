// End-to-end test of an EMA recording beside the head in Debian's Chromium: a clinician chooses a
// real HPRC recording ("The birch canoe slid on the smooth planks", speaker F01) and its phone
// labels on #/clinician, the head in profile says it with the speaker's sensors drawn on it, the
// tracks and scores show, and playing runs to the last frame with the head's jaw following.
// Screenshots: e2e/screenshots/ema-*.png.

import assert from 'node:assert/strict';
import { join, resolve } from 'node:path';
import { describe, test } from 'node:test';
import { createAccounts, signIn } from './accounts.js';
import { axeViolations } from './axe.js';
import { openPage, readDebug, REPO, saveScreenshot, serverAndBrowser } from './harness.js';

const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( REPO, '..', 'shared', 'data' );
const NAME = 'F01_B01_S01_R01_N';
const SENSORS = join( DATA_DIR, 'ema', 'hprc', `${ NAME }_ema.csv` );
const LABELS = join( DATA_DIR, 'ema', 'hprc', `${ NAME }_phones.tsv` );

describe( 'an EMA recording beside the head', { timeout: 600_000 }, () => {

	let server, browser;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		await createAccounts( server, [ 'clinician' ] );

	} );

	async function openClinician( size ) {

		const page = await openPage( browser, size );
		await signIn( page, server, 'clinician' );
		await page.goto( `${ server.baseUrl }/#/clinician` );
		await page.waitForFunction( () => window.glasshead?.clinician?.loaded === true, null, { timeout: 90_000, polling: 200 } );
		const card = page.getByRole( 'figure', { name: 'EMA recording beside the head' } );
		await card.getByLabel( 'Sensor file' ).setInputFiles( SENSORS );
		await card.getByLabel( 'Phone labels' ).setInputFiles( LABELS );
		await card.getByRole( 'button', { name: 'Compare with the head' } ).click();
		await page.waitForFunction( () => window.glasshead.ema?.loaded === true && window.glasshead.ema.head !== 'loading', null, { timeout: 120_000, polling: 200 } );
		return { page, card };

	}

	test( 'a clinician compares a real recording, sees the sensors on the head and plays it', async () => {

		const { page, card } = await openClinician( { width: 1366, height: 768 } );
		let ema = ( await readDebug( page ) ).ema;
		assert.equal( ema.name, NAME );
		assert.equal( ema.frames, 262 );
		assert.equal( ema.head, 'ready', 'the head in profile is shown' );
		assert.equal( ema.markers, 12, 'six sensors of the speaker and six points of the head' );
		assert.match( await card.getByRole( 'status' ).textContent(), /speaker F01, 262 frames at 100 Hz \(2\.61 s\), 27 phones/ );
		const rows = await card.getByRole( 'table', { name: 'How closely the head follows the speaker' } ).locator( 'tbody tr' ).allTextContents();
		assert.equal( rows.length, 6 );
		assert.match( rows[ 0 ], /^tongue tip/ );
		const signals = await card.getByRole( 'list', { name: 'Signals' } ).textContent();
		assert.match( signals, /jaw opening: r 0\.\d\d, range \d+\.\d of \d+\.\d mm/ );
		assert.ok( ema.draws >= 1, 'the tracks are drawn' );

		const jawAtStart = ema.jaw;
		await card.getByRole( 'button', { name: 'Play' } ).click();
		await page.waitForFunction( () => window.glasshead.ema.playing === false && window.glasshead.ema.frame === 261, null, { timeout: 60_000, polling: 100 } );
		ema = ( await readDebug( page ) ).ema;
		assert.ok( ema.draws > 10, `the tracks follow the playing: ${ ema.draws } draws` );
		assert.notEqual( ema.jaw, jawAtStart, 'the head moved its jaw' );

		await card.getByLabel( 'EMA frame' ).fill( '120' );
		await page.waitForFunction( () => window.glasshead.ema.frame === 120, null, { timeout: 10_000 } );
		await card.locator( '.cv-ema-views' ).evaluate( ( element ) => element.scrollIntoView( { block: 'start' } ) );
		await page.waitForFunction( () => window.glasshead.ema.frame === 120, null, { timeout: 10_000 } );
		await saveScreenshot( page, 'ema-1366x768' );
		await card.locator( '.cv-ema-tracks' ).scrollIntoViewIfNeeded();
		await saveScreenshot( page, 'ema-tracks-1366x768' );
		assert.deepEqual( await axeViolations( page, { include: '.cv-ema' } ), [], 'the EMA card' );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

	test( 'on a tablet the card fits the screen', async () => {

		const { page, card } = await openClinician( { width: 768, height: 1024 } );
		await card.scrollIntoViewIfNeeded();
		const box = await card.boundingBox();
		assert.ok( box.width <= 768, `the card is ${ box.width } px wide` );
		await saveScreenshot( page, 'ema-tablet-768x1024' );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

} );
