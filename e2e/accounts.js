// People for an end-to-end run: one user per role in the test server's own database, made with
// the command line as an admin would (`glasshead user create --password-stdin`), and signing a
// page in as one of them through the API, the session stored where the web app keeps it
// (session.js's SESSION_KEY in localStorage).
//
//   const server = await startServer();
//   const page = await openPage( browser );
//   await signIn( page, server, 'clinician' );          // then go to the view
//   await page.goto( `${ server.baseUrl }/#/clinician` );
//   const author = await openSignedIn( browser, server, 'author', `${ server.baseUrl }/#/workbench` );
//   const { token } = await apiSession( server, 'author' ); // for requests made by the test itself
//
// Users are made once per server and role and kept for the run; each has a fresh random password.

import { spawn } from 'node:child_process';
import { randomBytes } from 'node:crypto';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { REPO, openPage, settle, waitForLoaded } from './harness.js';
import { SESSION_KEY } from '../web/src/session.js';

/** The roles of adults, as the server names them. */
export const ROLES = Object.freeze( [ 'author', 'teacher', 'clinician', 'admin' ] );

/** Made users, by database URL and role: Promise<{ username, password, role, display_name }>. */
const made = new Map();

/** Database URLs of servers seen, by base URL, so that signIn( page, baseUrl, role ) also works. */
const databases = new Map();

function databaseOf( server ) {

	if ( typeof server === 'string' ) {

		const databaseUrl = databases.get( server.replace( /\/+$/, '' ) ) ?? process.env.GLASSHEAD_E2E_DATABASE_URL ?? null;
		return { baseUrl: server.replace( /\/+$/, '' ), databaseUrl };

	}

	if ( server?.baseUrl && server.databaseUrl ) databases.set( server.baseUrl, server.databaseUrl );
	return { baseUrl: server?.baseUrl, databaseUrl: server?.databaseUrl ?? null };

}

/** Run `glasshead user create` against `databaseUrl`; resolves when it has stored the user. */
function createUser( databaseUrl, { username, password, role, displayName } ) {

	const cli = join( REPO, '.venv', 'bin', 'glasshead' );
	if ( ! existsSync( cli ) ) throw new Error( `No glasshead command at ${ cli }: run node scripts/setup.mjs test first` );
	return new Promise( ( resolve, reject ) => {

		const child = spawn( cli, [ 'user', 'create', '--role', role, '--display-name', displayName, '--password-stdin', username ], {
			cwd: REPO,
			stdio: [ 'pipe', 'pipe', 'pipe' ],
			env: { ...process.env, GLASSHEAD_DATABASE_URL: databaseUrl },
		} );
		let output = '';
		child.stdout.on( 'data', ( chunk ) => ( output += chunk ) );
		child.stderr.on( 'data', ( chunk ) => ( output += chunk ) );
		const timer = setTimeout( () => child.kill( 'SIGKILL' ), 120_000 );
		child.on( 'error', reject );
		child.on( 'exit', ( code, signal ) => {

			clearTimeout( timer );
			if ( code === 0 ) resolve();
			else reject( new Error( `glasshead user create --role ${ role } ${ username } failed (${ code ?? signal }): ${ output.trim() }` ) );

		} );
		child.stdin.end( `${ password }\n` );

	} );

}

/**
 * The user of `role` on `server` ({ baseUrl, databaseUrl } from startServer, or a base URL seen
 * before), made on first use: { username, password, role, display_name }.
 */
export function account( server, role ) {

	if ( ! ROLES.includes( role ) ) throw new Error( `no role "${ role }": one of ${ ROLES.join( ', ' ) }` );
	const { databaseUrl } = databaseOf( server );
	if ( ! databaseUrl ) {

		throw new Error( 'The test server\'s database is not known: pass the server from startServer(), or set GLASSHEAD_E2E_DATABASE_URL with GLASSHEAD_E2E_BASE_URL' );

	}

	const key = `${ databaseUrl } ${ role }`;
	const shared = sharedAccounts( databaseUrl );
	if ( shared?.[ role ] && ! made.has( key ) ) made.set( key, Promise.resolve( shared[ role ] ) );
	if ( ! made.has( key ) ) {

		const user = {
			username: `e2e-${ role }@glasshead.test`,
			password: randomBytes( 18 ).toString( 'base64url' ),
			role,
			display_name: `E2E ${ role.charAt( 0 ).toUpperCase() }${ role.slice( 1 ) }`,
		};
		const promise = createUser( databaseUrl, { ...user, displayName: user.display_name } ).then( () => user );
		promise.catch( () => made.delete( key ) );
		made.set( key, promise );

	}

	return made.get( key );

}

/**
 * The users made once for a run's shared server (scripts/test.mjs), passed to every test file as
 * GLASSHEAD_E2E_ACCOUNTS: { databaseUrl, users: { role: user } }; null for another database.
 */
function sharedAccounts( databaseUrl ) {

	const text = process.env.GLASSHEAD_E2E_ACCOUNTS;
	if ( ! text ) return null;
	const { databaseUrl: sharedUrl, users } = JSON.parse( text );
	return sharedUrl === databaseUrl ? users : null;

}

/** Make every user of `roles` on `server` now (each costs a password hash: do it in before()). */
export async function createAccounts( server, roles = ROLES ) {

	const users = {};
	for ( const role of roles ) users[ role ] = await account( server, role );
	return users;

}

/**
 * Sign in as the user of `role` through the API (POST /auth/sessions): the session as the web app
 * keeps it, { kind: 'user', token, expires_at, user }.
 */
export async function apiSession( server, role ) {

	const { baseUrl } = databaseOf( server );
	const user = await account( server, role );
	const response = await fetch( `${ baseUrl }/api/v1/auth/sessions`, {
		method: 'POST',
		headers: { 'Content-Type': 'application/json', Accept: 'application/json' },
		body: JSON.stringify( { username: user.username, password: user.password } ),
	} );
	const body = await response.json().catch( () => null );
	if ( response.status !== 201 ) throw new Error( `Signing in as ${ user.username } answered HTTP ${ response.status }: ${ JSON.stringify( body ) }` );
	return { kind: 'user', token: body.token, expires_at: body.expires_at, user: body.user };

}

/** Headers for a request of the test itself made as the signed-in `session`. */
export function authHeaders( session, headers = {} ) {

	return { ...headers, Authorization: `Bearer ${ session.token }` };

}

/**
 * Sign `page` in as the user of `role`: the session goes into the page's localStorage for the
 * server's origin. A page not on that origin yet opens the app's sign-in view there (the one view
 * that loads no head) to write it, and is left at about:blank, so the next `page.goto` of a view
 * loads the app afresh, signed in; a page already on the app is reloaded. Returns the session.
 */
export async function signIn( page, server, role ) {

	const { baseUrl } = databaseOf( server );
	const session = await apiSession( server, role );
	const onApp = page.url().startsWith( `${ baseUrl }/` );
	if ( ! onApp ) await page.goto( `${ baseUrl }/#/signin` );
	await page.evaluate( ( [ key, value ] ) => window.localStorage.setItem( key, value ), [ SESSION_KEY, JSON.stringify( session ) ] );
	if ( onApp ) await page.reload();
	else await page.goto( 'about:blank' );
	return session;

}

/**
 * A new page signed in as the user of `role`, at `url` (a view of the served app) once it has
 * loaded and settled: openLoaded's, signed in. `size` as openPage's.
 */
export async function openSignedIn( browser, server, role, url, size ) {

	const page = await openPage( browser, size );
	await signIn( page, server, role );
	await page.goto( url );
	await waitForLoaded( page );
	await settle( page );
	return page;

}

/** Forget the page's session (as a token that expired would leave it: no sign-out on the server). */
export async function forgetSession( page ) {

	await page.evaluate( ( key ) => window.localStorage.removeItem( key ), SESSION_KEY );

}
