// End-to-end tests of signing in, in Debian's Chromium: an adult signs in through the form and is
// taken back where they came from, the bar names them and signs them out (the token revoked on the
// server), a wrong password is said in plain words and keeps nothing, and a token the server no
// longer takes turns into "Please sign in". Screenshots: e2e/screenshots/signin-*.png.

import assert from 'node:assert/strict';
import { after, before, describe, test } from 'node:test';
import { account, apiSession, signIn } from './accounts.js';
import { launchBrowser, openPage, saveScreenshot, startServer } from './harness.js';

/** Smallest touch target, CSS pixels. */
const TOUCH_PX = 44;
const SIZES = [ [ 1366, 768 ], [ 768, 1024 ] ];

describe( 'signing in', { timeout: 600_000 }, () => {

	let server, browser;

	before( async () => {

		server = await startServer();
		browser = await launchBrowser();
		await account( server, 'teacher' );

	} );

	after( async () => {

		await browser?.close();
		await server?.stop();

	} );

	const nav = ( page ) => page.getByRole( 'navigation', { name: 'Views' } );
	const storedSession = ( page ) => page.evaluate( () => JSON.parse( window.localStorage.getItem( 'glasshead.session' ) ?? 'null' ) );

	async function openSignIn( size, next = '#/speak' ) {

		const page = await openPage( browser, { width: size[ 0 ], height: size[ 1 ] } );
		await page.goto( `${ server.baseUrl }/#/signin?next=${ encodeURIComponent( next ) }` );
		await page.waitForFunction( () => window.glasshead?.signIn?.ready === true, null, { timeout: 30_000 } );
		return page;

	}

	/** Sizes of the sign-in view's controls and the bar's sign-in link: [{ name, width, height }]. */
	function controlSizes( page ) {

		return page.evaluate( () => [ ...document.querySelectorAll( '.signin-view input, .signin-view button, .signin-view a, nav[aria-label="Views"] a, nav[aria-label="Views"] button' ) ]
			.filter( ( element ) => element.getClientRects().length > 0 )
			.map( ( element ) => {

				const box = element.getBoundingClientRect();
				return { name: element.getAttribute( 'aria-label' ) ?? element.id ?? element.textContent.trim(), text: element.textContent.trim(), width: box.width, height: box.height };

			} ) );

	}

	test( 'a teacher signs in through the form with the keyboard and is taken back to where they came from', async () => {

		const teacher = await account( server, 'teacher' );
		for ( const size of SIZES ) {

			const page = await openSignIn( size );
			assert.equal( await page.evaluate( () => document.activeElement?.id ), 'signin-username', 'the username has the focus' );
			for ( const control of await controlSizes( page ) ) {

				assert.ok( control.height >= TOUCH_PX && control.width >= TOUCH_PX, `${ control.name || control.text } is ${ control.width } x ${ control.height } px at ${ size.join( 'x' ) }` );

			}

			await saveScreenshot( page, `signin-form-${ size.join( 'x' ) }` );
			await page.keyboard.type( teacher.username );
			await page.keyboard.press( 'Tab' );
			await page.keyboard.type( teacher.password );
			await page.keyboard.press( 'Enter' );
			await page.waitForFunction( () => window.glasshead?.route === '/speak', null, { timeout: 30_000 } );
			const session = await storedSession( page );
			assert.equal( session.kind, 'user' );
			assert.equal( session.user.username, teacher.username );
			assert.equal( session.user.role, 'teacher' );
			const me = await fetch( `${ server.baseUrl }/api/v1/auth/me`, { headers: { Authorization: `Bearer ${ session.token }` } } );
			assert.equal( me.status, 200, 'the stored token is good on the server' );
			const who = nav( page ).getByText( 'E2E Teacher (teacher)' );
			await who.waitFor( { timeout: 10_000 } );
			await saveScreenshot( page, `signin-nav-${ size.join( 'x' ) }` );
			assert.deepEqual( page.problems, [] );
			await page.context().close();

		}

	} );

	test( 'a wrong password is said in plain words next to the form and keeps no session', async () => {

		const teacher = await account( server, 'teacher' );
		const page = await openSignIn( SIZES[ 0 ] );
		await page.getByLabel( 'Username' ).fill( teacher.username );
		await page.getByLabel( 'Password' ).fill( 'not the password' );
		await page.getByRole( 'button', { name: 'Sign in' } ).click();
		const alert = page.getByRole( 'alert' ).filter( { hasText: 'do not match' } );
		await alert.waitFor( { timeout: 30_000 } );
		assert.equal( await alert.textContent(), 'That username and password do not match. Check them and try again.' );
		assert.equal( await storedSession( page ), null );
		assert.equal( await page.evaluate( () => window.glasshead.route ), '/signin', 'still on the sign-in view' );
		await saveScreenshot( page, 'signin-wrong-password' );
		// The browser logs the refused request itself; nothing else may go wrong.
		assert.deepEqual( page.problems.filter( ( problem ) => ! problem.includes( '401' ) ), [] );
		await page.context().close();

	} );

	test( 'Sign out in the bar revokes the token on the server and the bar offers Sign in again', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		const session = await signIn( page, server, 'teacher' );
		await page.goto( `${ server.baseUrl }/#/signin` );
		await page.waitForFunction( () => window.glasshead?.signIn?.ready === true, null, { timeout: 30_000 } );
		const bar = nav( page );
		await bar.getByText( 'E2E Teacher (teacher)' ).waitFor( { timeout: 10_000 } );
		await bar.getByRole( 'button', { name: 'Sign out' } ).click();
		await bar.getByRole( 'link', { name: 'Sign in' } ).waitFor( { timeout: 10_000 } );
		assert.equal( await storedSession( page ), null );
		const me = await fetch( `${ server.baseUrl }/api/v1/auth/me`, { headers: { Authorization: `Bearer ${ session.token }` } } );
		assert.equal( me.status, 401, 'the token is revoked' );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

	test( 'the sign-in view of someone signed in names them and continues to where they came from', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		await apiSession( server, 'teacher' );
		await signIn( page, server, 'teacher' );
		await page.goto( `${ server.baseUrl }/#/signin?next=${ encodeURIComponent( '#/speak' ) }` );
		await page.waitForFunction( () => window.glasshead?.signIn?.ready === true, null, { timeout: 30_000 } );
		const view = page.locator( '.signin-view' );
		assert.match( await view.getByRole( 'status' ).textContent(), /You are signed in as E2E Teacher \(teacher\)\./ );
		assert.equal( await view.getByRole( 'link', { name: 'Continue' } ).getAttribute( 'href' ), '#/speak' );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

} );
