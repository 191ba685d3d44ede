// End-to-end tests of the head view in Debian's Chromium (SwiftShader WebGL2). One server, one
// browser and one page for the whole file: the tests run in order and share the page's state.
// Assertions read `window.glasshead`; screenshots in e2e/screenshots/ are for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { decodePng, compareImages } from './png.js';
import { openLoaded, openPage, readDebug, saveScreenshot, serverAndBrowser, settle } from './harness.js';

describe( 'the head view', { timeout: 240_000 }, () => {

	let server, browser, page, anatomy;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		const response = await fetch( `${ server.baseUrl }/api/v1/anatomy` );
		const body = await response.text();
		assert.equal( response.status, 200, `GET /api/v1/anatomy answered ${ response.status }: ${ body }` );
		anatomy = JSON.parse( body );
		page = await openLoaded( browser, `${ server.baseUrl }/#/` );

	} );

	const slider = () => page.getByRole( 'slider', { name: 'Skin transparency' } );
	const cutaway = () => page.getByRole( 'button', { name: 'Cutaway' } );
	const viewButton = ( name ) => page.getByRole( 'button', { name, exact: true } );

	async function setTransparency( percent ) {

		await slider().fill( String( percent ) );
		await settle( page );

	}

	async function setCutaway( on ) {

		if ( ( await cutaway().getAttribute( 'aria-pressed' ) ) !== String( on ) ) await cutaway().click();
		await settle( page );

	}

	async function showView( label ) {

		await viewButton( label ).click();
		await settle( page );

	}

	test( 'the page loads with no console errors', async () => {

		assert.deepEqual( page.problems, [] );
		assert.equal( await page.title(), 'Glasshead' );
		await assert.doesNotReject( slider().waitFor( { state: 'visible' } ) );

	} );

	test( 'the scene draws frames into a WebGL2 context', async () => {

		// Frames are drawn while something moves: a camera flight gives a frame time.
		await showView( 'Front' );
		await showView( 'Three-quarter' );
		const state = await readDebug( page );
		assert.equal( state.webgl2, true );
		const context = await page.evaluate( () => {

			const canvas = document.querySelector( 'canvas' );
			const probe = document.createElement( 'canvas' ).getContext( 'webgl2' );
			return { canvas: canvas !== null, probe: probe !== null && typeof probe.createVertexArray === 'function' };

		} );
		assert.deepEqual( context, { canvas: true, probe: true } );
		// Chromium here renders in software (SwiftShader): the Viewer leaves multisampling off.
		assert.match( state.renderer.name, /SwiftShader/i );
		assert.equal( state.renderer.antialias, false );
		assert.equal( await page.evaluate( () => document.querySelector( 'canvas' ).getContext( 'webgl2' ).getContextAttributes().antialias ), false );
		assert.ok( state.frames >= 3, `only ${ state.frames } frames drawn` );
		assert.ok( state.frameTimeMs > 0 && Number.isFinite( state.frameTimeMs ), `frame time ${ state.frameTimeMs }` );

	} );

	test( 'every scene mesh of the anatomy reports as loaded with its triangle count', async () => {

		const state = await readDebug( page );
		const expected = anatomy.meshes.filter( ( mesh ) => mesh.scene ).map( ( mesh ) => ( { name: mesh.name, triangles: mesh.triangles } ) );
		assert.ok( expected.length >= 5, `the anatomy lists only ${ expected.length } scene meshes` );
		assert.equal( state.loaded, true );
		assert.deepEqual(
			[ ...state.meshes ].sort( ( a, b ) => a.name.localeCompare( b.name ) ),
			expected.sort( ( a, b ) => a.name.localeCompare( b.name ) ),
		);
		for ( const name of [ 'face_skin', 'maxilla', 'mandible', 'tongue_rest', 'upper_lip', 'lower_lip' ] ) {

			assert.ok( state.meshes.some( ( mesh ) => mesh.name === name ), `${ name } is not loaded` );

		}

	} );

	test( 'the debug object cannot be changed from the page', async () => {

		const result = await page.evaluate( () => {

			const before = window.glasshead.transparency;
			const outcomes = {};
			outcomes.strictWriteThrows = ( () => {

				'use strict';
				try {

					window.glasshead.transparency = 55;
					return false;

				} catch ( error ) {

					return error instanceof TypeError;

				}

			} )();
			try {

				window.glasshead = {};

			} catch {
				// a strict-mode write to a getter-only property throws; either way it must not stick
			}

			outcomes.replaced = Object.keys( window.glasshead ).length === 0;
			outcomes.frozen = Object.isFrozen( window.glasshead ) && Object.isFrozen( window.glasshead.meshes );
			outcomes.unchanged = window.glasshead.transparency === before;
			return outcomes;

		} );
		assert.deepEqual( result, { strictWriteThrows: true, replaced: false, frozen: true, unchanged: true } );

	} );

	test( 'the default view is saved as a screenshot', async () => {

		const state = await readDebug( page );
		assert.deepEqual( [ state.view, state.transparency, state.cutaway ], [ 'three-quarter', 0, false ] );
		await saveScreenshot( page, 'default' );

	} );

	test( 'the transparency slider sets the skin transparency', async () => {

		await setTransparency( 70 );
		assert.equal( ( await readDebug( page ) ).transparency, 70 );
		assert.equal( await slider().inputValue(), '70' );
		await saveScreenshot( page, 'transparent' );
		await setTransparency( 0 );
		assert.equal( ( await readDebug( page ) ).transparency, 0 );

	} );

	test( 'transparent skin changes the pixels of the mouth region', async () => {

		await showView( 'Front' );
		const rect = ( await readDebug( page ) ).mouthRect;
		assert.ok( rect && rect.width > 20 && rect.height > 20, `mouth region ${ JSON.stringify( rect ) }` );
		const viewport = page.viewportSize();
		const clip = {
			x: Math.max( 0, Math.floor( rect.x ) ),
			y: Math.max( 0, Math.floor( rect.y ) ),
		};
		clip.width = Math.min( viewport.width - clip.x, Math.ceil( rect.width ) );
		clip.height = Math.min( viewport.height - clip.y, Math.ceil( rect.height ) );

		const opaque = decodePng( await page.screenshot( { clip } ) );
		await setTransparency( 100 );
		const transparent = decodePng( await page.screenshot( { clip } ) );
		await setTransparency( 0 );
		const opaqueAgain = decodePng( await page.screenshot( { clip } ) );

		const change = compareImages( opaque, transparent );
		assert.ok( change.changedFraction > 0.2 && change.meanDifference > 10, `transparent skin barely changed the mouth: ${ JSON.stringify( change ) }` );
		// Going back to opaque restores the picture: the change came from the skin, not from noise.
		const back = compareImages( opaque, opaqueAgain );
		assert.ok( back.changedFraction < 0.01, `opaque skin did not restore the mouth: ${ JSON.stringify( back ) }` );

	} );

	test( 'the cutaway toggle switches the cutaway and its pressed state', async () => {

		await showView( 'Profile' );
		await saveScreenshot( page, 'profile' );
		assert.equal( ( await readDebug( page ) ).view, 'profile' );

		await setCutaway( true );
		assert.equal( ( await readDebug( page ) ).cutaway, true );
		assert.equal( await cutaway().getAttribute( 'aria-pressed' ), 'true' );
		await saveScreenshot( page, 'cutaway' );

		await showView( 'Three-quarter' );
		await saveScreenshot( page, 'cutaway-three-quarter' );

		await setCutaway( false );
		assert.equal( ( await readDebug( page ) ).cutaway, false );
		assert.equal( await cutaway().getAttribute( 'aria-pressed' ), 'false' );

	} );

	test( 'the view buttons mark the chosen view as pressed', async () => {

		for ( const [ label, name ] of [ [ 'Front', 'front' ], [ 'Profile', 'profile' ], [ 'Three-quarter', 'three-quarter' ] ] ) {

			await viewButton( label ).click();
			assert.equal( ( await readDebug( page ) ).view, name );
			assert.equal( await viewButton( label ).getAttribute( 'aria-pressed' ), 'true' );

		}

		await settle( page );

	} );

	test( 'no console errors appeared while using the controls', () => {

		assert.deepEqual( page.problems, [] );

	} );

	test( 'a failing anatomy request shows a clear error instead of a blank page', async () => {

		const failing = await openPage( browser, { width: 800, height: 600 } );
		try {

			await failing.route( '**/api/v1/anatomy', ( route ) => route.fulfill( {
				status: 503, contentType: 'application/json',
				body: JSON.stringify( { detail: 'anatomy not built: run `glasshead build`' } ),
			} ) );
			await failing.goto( `${ server.baseUrl }/#/` );
			const alert = failing.getByRole( 'alert' );
			await alert.waitFor( { state: 'visible', timeout: 30_000 } );
			assert.match( await alert.textContent(), /HTTP 503: anatomy not built: run `glasshead build`/ );
			const state = await readDebug( failing );
			assert.equal( state.loaded, false );
			assert.match( state.error, /anatomy not built/ );
			assert.equal( await failing.getByRole( 'button', { name: 'Cutaway' } ).isDisabled(), true );

		} finally {

			await failing.context().close();

		}

	} );

	test( 'a mesh that fails to load is named in the error message', async () => {

		const failing = await openPage( browser, { width: 800, height: 600 } );
		const broken = anatomy.meshes.find( ( mesh ) => mesh.scene );
		try {

			await failing.route( ( url ) => url.pathname === new URL( broken.url, server.baseUrl ).pathname, ( route ) => route.fulfill( { status: 404, body: 'gone' } ) );
			await failing.goto( `${ server.baseUrl }/#/` );
			const alert = failing.getByRole( 'alert' );
			await alert.waitFor( { state: 'visible', timeout: 60_000 } );
			const text = await alert.textContent();
			assert.ok( text.includes( `"${ broken.name }"` ), `the error does not name ${ broken.name }: ${ text }` );
			assert.equal( ( await readDebug( failing ) ).loaded, false );

		} finally {

			await failing.context().close();

		}

	} );

} );
