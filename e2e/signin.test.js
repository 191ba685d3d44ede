// End-to-end tests of signing in, in Debian's Chromium: an adult signs in through the form and is
// taken back where they came from, the bar names them and signs them out (the token revoked on the
// server), a wrong password is said in plain words and keeps nothing, and a token the server no
// longer takes turns into "Please sign in". Screenshots: e2e/screenshots/signin-*.png.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { account, apiSession, signIn } from './accounts.js';
import { axeViolations } from './axe.js';
import { openLoaded, openPage, readDebug, saveScreenshot, serverAndBrowser, waitForLoaded } from './harness.js';

/** Smallest touch target, CSS pixels. */
const TOUCH_PX = 44;
const SIZES = [ [ 1366, 768 ], [ 768, 1024 ] ];

describe( 'signing in', { timeout: 600_000 }, () => {

	let server, browser;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		await account( server, 'teacher' );

	}, { ownServer: true } ); // its admin is refused for 15 minutes after five wrong passwords

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

			assert.deepEqual( await axeViolations( page ), [], `the sign-in view at ${ size.join( 'x' ) }` );
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
			await who.waitFor( { timeout: 60_000 } );
			assert.deepEqual( await axeViolations( page, { include: 'nav' } ), [], `the bar signed in at ${ size.join( 'x' ) }` );
			const signOut = await nav( page ).getByRole( 'button', { name: 'Sign out' } ).boundingBox();
			assert.ok( signOut.height >= TOUCH_PX && signOut.width >= TOUCH_PX, `Sign out is ${ signOut.width } x ${ signOut.height } px` );
			const bar = await nav( page ).boundingBox();
			assert.ok( bar.height <= 60, `the bar signed in is ${ bar.height } px tall at ${ size.join( 'x' ) }: one row` );
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
		assert.deepEqual( await axeViolations( page ), [], 'the sign-in view with its message' );
		await saveScreenshot( page, 'signin-wrong-password' );
		// The browser logs the refused request itself; nothing else may go wrong.
		assert.deepEqual( page.problems.filter( ( problem ) => ! problem.includes( '401' ) ), [] );
		await page.context().close();

	} );

	test( 'after five wrong passwords the form says too many attempts and when to try again, even for the right one', async () => {

		// The admin's account, which no other test here signs in with: it stays refused for 15 minutes.
		const admin = await account( server, 'admin' );
		const page = await openSignIn( SIZES[ 0 ] );
		const submit = async ( password ) => {

			await page.getByLabel( 'Username' ).fill( admin.username );
			await page.getByLabel( 'Password' ).fill( password );
			await page.getByRole( 'button', { name: 'Sign in' } ).click();
			await page.waitForFunction( () => window.glasshead.signIn.busy === false && window.glasshead.signIn.message !== null, null, { timeout: 60_000 } );
			return page.evaluate( () => window.glasshead.signIn.message );

		};
		for ( let k = 0; k < 5; k ++ ) assert.equal( await submit( `wrong ${ k }` ), 'That username and password do not match. Check them and try again.' );
		// The wait is counted from the first failure, so it is said in the minutes the 429's
		// Retry-After leaves (15 unless the six tries took the machine more than a minute).
		const refused = page.waitForResponse( ( response ) => response.url().endsWith( '/api/v1/auth/sessions' ) && response.status() === 429, { timeout: 60_000 } );
		const message = await submit( admin.password );
		const retryAfter = Number( ( await refused ).headers()[ 'retry-after' ] );
		assert.ok( retryAfter > 0 && retryAfter <= 15 * 60 + 1, `Retry-After ${ retryAfter } s` );
		const minutes = Math.ceil( retryAfter / 60 );
		assert.equal( message, `Too many attempts to sign in. Try again in ${ minutes } minute${ minutes === 1 ? '' : 's' }.` );
		assert.equal( await page.getByRole( 'alert' ).filter( { hasText: 'Too many attempts' } ).isVisible(), true );
		assert.equal( await storedSession( page ), null );
		await saveScreenshot( page, 'signin-too-many' );
		assert.deepEqual( page.problems.filter( ( problem ) => ! /401|429/.test( problem ) ), [] );
		await page.context().close();

	} );

	test( 'Sign out in the bar revokes the token on the server and the bar offers Sign in again', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		const session = await signIn( page, server, 'teacher' );
		await page.goto( `${ server.baseUrl }/#/signin` );
		await page.waitForFunction( () => window.glasshead?.signIn?.ready === true, null, { timeout: 30_000 } );
		const bar = nav( page );
		await bar.getByText( 'E2E Teacher (teacher)' ).waitFor( { timeout: 60_000 } );
		await bar.getByRole( 'button', { name: 'Sign out' } ).click();
		await bar.getByRole( 'link', { name: 'Sign in' } ).waitFor( { timeout: 60_000 } );
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

	test( 'signed out, the clinician view asks to sign in and comes back after; a teacher is told whose view it is', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		await page.goto( `${ server.baseUrl }/#/clinician` );
		await page.waitForFunction( () => window.glasshead?.clinician?.signIn === 'needed', null, { timeout: 30_000 } );
		const prompt = page.locator( '#app .signin-prompt' );
		assert.equal( await prompt.textContent(), 'Please sign in as a clinician to read EPG recordings.Sign in' );
		assert.equal( await page.locator( '#app [role="alert"]' ).count(), 0, 'no error shown' );
		assert.deepEqual( await axeViolations( page ), [], 'the clinician view signed out' );
		await saveScreenshot( page, 'signin-clinician-prompt' );
		await prompt.getByRole( 'link', { name: 'Sign in' } ).click();
		await page.waitForFunction( () => window.glasshead?.signIn?.ready === true, null, { timeout: 30_000 } );
		assert.equal( await page.evaluate( () => window.glasshead.signIn.next ), '#/clinician' );

		const teacher = await account( server, 'teacher' );
		await page.getByLabel( 'Username' ).fill( teacher.username );
		await page.getByLabel( 'Password' ).fill( teacher.password );
		await page.getByRole( 'button', { name: 'Sign in' } ).click();
		await page.waitForFunction( () => window.glasshead?.clinician?.signIn === 'role', null, { timeout: 30_000 } );
		assert.match( await page.locator( '#app .signin-prompt' ).textContent(), /^The clinician view is for clinicians and admins\. You are signed in as E2E Teacher \(teacher\)\./ );

		// Signing in as a clinician from there shows the view itself.
		await nav( page ).getByRole( 'button', { name: 'Sign out' } ).click();
		await page.waitForFunction( () => window.glasshead?.clinician?.signIn === 'needed', null, { timeout: 30_000 } );
		await signIn( page, server, 'clinician' );
		await page.waitForFunction( () => window.glasshead?.clinician?.loaded === true, null, { timeout: 90_000, polling: 200 } );
		assert.equal( ( await readDebug( page ) ).clinician.error, null );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

	test( 'a token the server refuses (401) turns the clinician view into "Please sign in" and is forgotten', async () => {

		const page = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( page, server, 'clinician' );
		// The server answers as it does for an expired or revoked token.
		await page.route( '**/api/v1/epg/recordings?limit=1000', ( route ) => route.fulfill( {
			status: 401, contentType: 'application/json', headers: { 'WWW-Authenticate': 'Bearer' },
			body: JSON.stringify( { detail: 'the token is missing, unknown, expired or revoked' } ),
		} ) );
		await page.goto( `${ server.baseUrl }/#/clinician?recording=3` );
		await page.waitForFunction( () => window.glasshead?.clinician?.signIn === 'needed', null, { timeout: 60_000 } );
		const prompt = page.locator( '#app .signin-prompt' );
		assert.equal( await prompt.count(), 1, 'one prompt, in place of the view' );
		assert.match( await prompt.textContent(), /^Please sign in as a clinician to read EPG recordings\./ );
		assert.equal( await storedSession( page ), null, 'the session is forgotten' );
		assert.equal( await prompt.getByRole( 'link', { name: 'Sign in' } ).getAttribute( 'href' ), `#/signin?next=${ encodeURIComponent( '#/clinician?recording=3' ) }` );
		await nav( page ).getByRole( 'link', { name: 'Sign in' } ).waitFor( { timeout: 60_000 } );
		assert.deepEqual( page.problems.filter( ( problem ) => ! problem.includes( '401' ) ), [] );
		await page.context().close();

	} );

	test( 'signed out, the workbench offers signing in instead of Save, and the head lists phoneme targets but no saved poses', async () => {

		const page = await openLoaded( browser, `${ server.baseUrl }/#/workbench`, { width: 1366, height: 768 } );
		assert.equal( ( await readDebug( page ) ).workbench.poseSaving, 'signIn' );
		assert.equal( await page.getByRole( 'button', { name: 'Save pose' } ).isVisible(), false );
		const prompt = page.locator( '.wb-pose .signin-prompt' );
		assert.equal( await prompt.textContent(), 'Please sign in to save poses.Sign in' );
		await saveScreenshot( page, 'signin-workbench-signed-out' );

		await page.goto( `${ server.baseUrl }/#/` );
		await waitForLoaded( page );
		await page.waitForFunction( () => document.querySelector( '#head-target option[value="phoneme:T"]' ) !== null, null, { timeout: 30_000 } );
		const groups = await page.locator( '#head-target optgroup' ).evaluateAll( ( nodes ) => nodes.map( ( node ) => node.label ) );
		assert.deepEqual( groups, [ 'Phoneme targets' ] );
		assert.deepEqual( page.problems, [] );
		await page.context().close();

	} );

} );
