// End-to-end test of what the head view `/` downloads, in Debian's Chromium: the bytes on the wire
// of a first visit with the cache disabled (as the DevTools protocol counts them), compressed and
// without the collision tables, then a second visit that downloads no asset again. Bytes only: the
// time of the load is measured by bench/first_load.bench.mjs, on a throttled network.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { serverAndBrowser } from './harness.js';

/** The most `/` may transfer. The goal is 1.5 MB; the meshes, gzipped but not quantised, are
 * 1.15 MB of the 1.58 MB measured, so the bound stands a little above that until they shrink. */
const MOST_BYTES = 1.7e6;

describe( 'the first load of the head view', { timeout: 240_000 }, () => {

	let server, browser, context;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		context = await browser.newContext( { viewport: { width: 1366, height: 768 } } );

	} );

	/** Visit `/` until it has loaded; every response: { path, status, bytes, encoding, cached }. */
	async function visit( { cache } ) {

		const page = await context.newPage();
		const problems = [];
		page.on( 'console', ( message ) => message.type() === 'error' && problems.push( message.text() ) );
		page.on( 'pageerror', ( error ) => problems.push( error.message ) );
		const cdp = await context.newCDPSession( page );
		await cdp.send( 'Network.enable' );
		await cdp.send( 'Network.setCacheDisabled', { cacheDisabled: ! cache } );
		const responses = new Map();
		const finished = [];
		cdp.on( 'Network.responseReceived', ( { requestId, response } ) => responses.set( requestId, response ) );
		cdp.on( 'Network.loadingFinished', ( { requestId, encodedDataLength } ) => {

			const response = responses.get( requestId );
			if ( ! response ) return;
			const headers = Object.fromEntries( Object.entries( response.headers ).map( ( [ k, v ] ) => [ k.toLowerCase(), v ] ) );
			finished.push( {
				path: new URL( response.url ).pathname,
				status: response.status,
				bytes: encodedDataLength,
				encoding: headers[ 'content-encoding' ] ?? null,
				cached: response.fromDiskCache || response.fromMemoryCache || response.status === 304,
			} );

		} );
		await page.goto( `${ server.baseUrl }/#/` );
		await page.waitForFunction( () => window.glasshead?.loaded === true || Boolean( window.glasshead?.error ), null, { timeout: 120_000, polling: 200 } );
		assert.equal( await page.evaluate( () => window.glasshead.error ), null );
		await page.waitForTimeout( 500 );
		await page.close();
		assert.deepEqual( problems, [] );
		return finished;

	}

	let first;

	test( 'a first visit transfers compressed files and no collision tables', async () => {

		first = await visit( { cache: false } );
		const total = first.reduce( ( sum, r ) => sum + r.bytes, 0 );
		const paths = first.map( ( r ) => r.path );
		assert.ok( paths.some( ( p ) => p.endsWith( '.glb' ) ), `meshes were loaded: ${ paths.join( ', ' ) }` );
		assert.ok( ! paths.some( ( p ) => p.includes( 'collision' ) ), `the head view at rest needs no collision tables: ${ paths.filter( ( p ) => p.includes( 'collision' ) ) }` );
		const plainText = first.filter( ( r ) => /\.(glb|js|css)$/.test( r.path ) && r.bytes > 2048 && r.encoding !== 'gzip' );
		assert.deepEqual( plainText.map( ( r ) => r.path ), [], 'every mesh, script and style sheet over 2 kB comes gzipped' );
		assert.ok( total < MOST_BYTES, `/ transferred ${ ( total / 1e6 ).toFixed( 2 ) } MB in ${ first.length } responses, more than ${ MOST_BYTES / 1e6 } MB` );

	} );

	test( 'a second visit downloads no asset again', async () => {

		assert.ok( first, 'the first visit ran' );
		const second = await visit( { cache: true } );
		const again = second.filter( ( r ) => r.path.startsWith( '/assets/' ) && ! r.cached );
		assert.deepEqual( again.map( ( r ) => r.path ), [] );
		assert.ok( second.some( ( r ) => r.path.endsWith( '.glb' ) && r.cached ), 'the meshes came from the cache' );

	} );

} );
