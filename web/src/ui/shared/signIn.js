// Signing in and out without the DOM: where the sign-in page sends a person back to, what it says
// when signing in fails, how a view tells that the server no longer takes the page's token, and
// the requests themselves (the fetch injectable). Unit-tested without a browser
// (tests/js/signIn.test.js); SignInView.js, SignInPrompt.js and NavBar.js make the elements.

import { createApi } from '../../api.js';
import { clearSession, currentSession, saveSession } from '../../session.js';

/** The route of the sign-in view. */
export const SIGN_IN_PATH = '/signin';

/** Where a person goes after signing in when the address names nowhere else. */
export const DEFAULT_NEXT = '#/';

/**
 * The address of the sign-in view that comes back to `here` (a location hash such as
 * '#/clinician?recording=3') once signed in: '#/signin?next=%23%2Fclinician%3Frecording%3D3'.
 */
export function signInHref( here = DEFAULT_NEXT ) {

	const next = safeNext( here );
	return next === DEFAULT_NEXT ? `#${ SIGN_IN_PATH }` : `#${ SIGN_IN_PATH }?next=${ encodeURIComponent( next ) }`;

}

/** Where each role starts its work: a teacher teaches, a clinician reads, an author writes. */
export const ROLE_HOMES = Object.freeze( {
	teacher: '#/teach', clinician: '#/clinician', author: '#/author', admin: '#/admin',
} );

/**
 * Where to go once signed in as `role`: the place the sign-in was asked from (`next`), or, when
 * it was asked from the start page or from nowhere, the role's own home.
 */
export function landingFor( next, role ) {

	const safe = safeNext( next );
	return safe === DEFAULT_NEXT ? ROLE_HOMES[ role ] ?? DEFAULT_NEXT : safe;

}

/**
 * A place to go back to, or DEFAULT_NEXT: only a view of this page ('#/…'), never another site
 * (an address in a link must not send a person who just signed in somewhere else) and never the
 * sign-in view itself.
 */
export function safeNext( next ) {

	if ( typeof next !== 'string' ) return DEFAULT_NEXT;
	const hash = next.startsWith( '/' ) ? `#${ next }` : next;
	if ( ! /^#\/[^\s\\]*$/.test( hash ) || hash.startsWith( '#//' ) ) return DEFAULT_NEXT;
	const path = hash.slice( 1 ).split( '?' )[ 0 ].replace( /\/+$/, '' );
	if ( path === SIGN_IN_PATH ) return DEFAULT_NEXT;
	return hash;

}

/** The `next` of a sign-in address ('#/signin?next=%23%2Fworkbench' -> '#/workbench'), made safe. */
export function nextFromHash( hash ) {

	const query = ( hash ?? '' ).split( '?' ).slice( 1 ).join( '?' );
	return safeNext( new URLSearchParams( query ).get( 'next' ) );

}

/**
 * Seconds to wait from a Retry-After header (RFC 9110 10.2.3: a number of seconds or an HTTP
 * date), or null when there is none or it cannot be read.
 */
export function retryAfterSeconds( header, now = Date.now() ) {

	if ( header === null || header === undefined || header === '' ) return null;
	const text = String( header ).trim();
	if ( /^\d+$/.test( text ) ) return Number( text );
	const when = Date.parse( text );
	if ( ! Number.isFinite( when ) ) return null;
	return Math.max( 0, Math.ceil( ( when - now ) / 1000 ) );

}

/** A wait in words: 'in 40 seconds', 'in 2 minutes', 'in a moment'. */
export function waitWords( seconds ) {

	if ( ! Number.isFinite( seconds ) || seconds <= 0 ) return 'in a moment';
	if ( seconds < 60 ) return `in ${ Math.ceil( seconds ) } second${ Math.ceil( seconds ) === 1 ? '' : 's' }`;
	const minutes = Math.ceil( seconds / 60 );
	return `in ${ minutes } minute${ minutes === 1 ? '' : 's' }`;

}

/**
 * What a person reads when signing in failed with `error` (an ApiError, or an Error), in plain
 * words and with what to do; `retryAfter` is the seconds the server asked to wait (429), if any.
 */
export function signInMessage( error, { retryAfter = null } = {} ) {

	const status = error?.status;
	if ( status === undefined ) return error?.message ?? String( error );
	if ( status === null ) return 'Could not reach the server. Check the connection and try again.';
	if ( status === 401 ) return 'That username and password do not match. Check them and try again.';
	if ( status === 429 ) {

		return retryAfter === null
			? 'Too many attempts to sign in. Wait a few minutes, then try again.'
			: `Too many attempts to sign in. Try again ${ waitWords( retryAfter ) }.`;

	}

	if ( status === 422 ) return 'Enter a username and a password (at most 1,024 characters).';
	if ( status >= 500 ) return 'The server failed while signing in. Try again in a moment.';
	return `Could not sign in: the server answered ${ status }.`;

}

/** Whether `error` says that the page's token is missing, expired or revoked (HTTP 401). */
export function isSignedOut( error ) {

	return error?.name === 'ApiError' && error.status === 401;

}

/** Whether `error` says that the signed-in person's role may not do this (HTTP 403). */
export function isForbidden( error ) {

	return error?.name === 'ApiError' && error.status === 403;

}

/** The roles of adults, as the server names them. */
export const ROLES = Object.freeze( [ 'author', 'teacher', 'clinician', 'admin' ] );

/**
 * Whether `session` (session.js's) is an adult whose role is one of `roles`; any adult when
 * `roles` is empty.
 */
export function hasRole( session, roles = [] ) {

	if ( session?.kind !== 'user' ) return false;
	return roles.length === 0 || roles.includes( session.user?.role );

}

/** Who is signed in, in words for the navigation bar: 'Ann (teacher)', a child's name, or null. */
export function whoLabel( session ) {

	if ( session?.kind === 'user' ) {

		const user = session.user ?? {};
		const name = user.display_name || user.username || 'Signed in';
		return user.role ? `${ name } (${ user.role })` : name;

	}

	if ( session?.kind === 'child' ) return session.child?.display_name || 'Signed in';
	return null;

}

/**
 * A client for signing in that sends no token (an old one means nothing here) and keeps the
 * last answer's Retry-After header, which an ApiError does not carry.
 */
export function signInClient( fetchImpl = null ) {

	const state = { retryAfter: null };
	const client = createApi( {
		fetchImpl: async ( url, init ) => {

			const response = await ( fetchImpl ?? globalThis.fetch )( url, init );
			state.retryAfter = response.headers?.get?.( 'Retry-After' ) ?? null;
			return response;

		},
	} );
	return { client, state };

}

/** Sign in as `username`; resolves to the saved session, rejects with a plain-worded Error. */
export async function signIn( username, password, { fetchImpl = null, win = globalThis.window } = {} ) {

	const { client, state } = signInClient( fetchImpl );
	let answer;
	try {

		answer = await client.post( 'auth/sessions', { username: username.trim(), password } );

	} catch ( error ) {

		const plain = new Error( signInMessage( error, { retryAfter: retryAfterSeconds( state.retryAfter ) } ), { cause: error } );
		plain.status = error?.status ?? null;
		throw plain;

	}

	const session = { kind: 'user', token: answer.token, expires_at: answer.expires_at, user: answer.user };
	saveSession( session, { win } );
	return session;

}

/** Sign out: revoke the token on the server (DELETE /auth/sessions/current), then forget it here. */
export async function signOut( { fetchImpl = null, win = globalThis.window } = {} ) {

	const session = currentSession( { win } );
	if ( ! session ) return;
	const path = session.kind === 'child' ? 'auth/child-sessions/current' : 'auth/sessions/current';
	try {

		const client = createApi( { fetchImpl, tokenSource: () => session.token } );
		await client.delete( path );

	} catch ( error ) {

		// Already revoked or expired (401), or the server is away: forgotten here all the same.
		console.warn( `Glasshead: signing out on the server failed: ${ error.message }` );

	} finally {

		clearSession( { win } );

	}

}

/** Roles in words, as people: [ 'clinician', 'admin' ] -> 'clinicians and admins'. */
export function rolesWords( roles ) {

	const people = roles.map( ( role ) => `${ role }s` );
	return people.length < 2 ? people.join( '' ) : `${ people.slice( 0, - 1 ).join( ', ' ) } and ${ people.at( - 1 ) }`;

}
