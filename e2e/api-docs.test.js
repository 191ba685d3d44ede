// End-to-end tests of the API's docs pages in Debian's Chromium: Swagger UI and ReDoc load their
// scripts and styles from this server (never a CDN) and run under its Content-Security-Policy
// with no violation (a violation is a console error, recorded in page.problems).

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { openPage, serverAndBrowser } from './harness.js';

describe( 'the API docs pages', { timeout: 120_000 }, () => {

	let server, browser;

	serverAndBrowser( ( running ) => ( { server, browser } = running ) );

	async function openDocs( path ) {

		const page = await openPage( browser );
		const foreign = [];
		page.on( 'request', ( request ) => {

			if ( ! request.url().startsWith( server.baseUrl ) && ! /^(data|blob):/.test( request.url() ) ) foreign.push( request.url() );

		} );
		const response = await page.goto( `${ server.baseUrl }${ path }` );
		assert.match( response.headers()[ 'content-security-policy' ], /frame-ancestors 'none'/ );
		return { page, foreign };

	}

	test( 'Swagger UI lists the operations with no CSP violation and no request elsewhere', async () => {

		const { page, foreign } = await openDocs( '/api/v1/docs' );
		await page.locator( '.opblock' ).first().waitFor( { timeout: 30_000 } );
		assert.ok( await page.locator( '.opblock' ).count() > 20 );
		assert.deepEqual( page.problems, [] );
		assert.deepEqual( foreign, [] );

	} );

	test( 'ReDoc shows the operations with no CSP violation and no request elsewhere', async () => {

		const { page, foreign } = await openDocs( '/api/v1/redoc' );
		await page.getByRole( 'heading', { name: /Glasshead/ } ).first().waitFor( { timeout: 30_000 } );
		assert.ok( await page.locator( '[data-section-id^="operation/"]' ).count() > 20 );
		assert.deepEqual( page.problems, [] );
		assert.deepEqual( foreign, [] );

	} );

} );
