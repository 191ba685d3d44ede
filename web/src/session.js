// Who is signed in on this browser: an adult (author, teacher, clinician, admin) with a token from
// POST /auth/sessions, or a child with a token from POST /auth/child-sessions. The session is kept
// in localStorage so that a reload keeps it, and every request of the page's API client sends its
// token (api.js asks `currentToken()`). A token past its `expires_at` is forgotten on read, so the
// page never sends one the server would refuse anyway.
//
//   import { currentSession, saveSession, clearSession, onSessionChange } from '../session.js';
//   saveSession( { kind: 'user', token, expires_at, user } );   // after POST /auth/sessions
//   saveSession( { kind: 'child', token, expires_at, child } ); // after POST /auth/child-sessions

/** The localStorage key of the session. */
export const SESSION_KEY = 'glasshead.session';

const listeners = new Set();

function storage( win ) {

	try {

		return win?.localStorage ?? null;

	} catch {

		// A browser with storage turned off: nobody stays signed in across reloads.
		return null;

	}

}

/** Whether `value` looks like a stored session: a kind, a token and who it belongs to. */
export function isSession( value ) {

	if ( ! value || typeof value !== 'object' ) return false;
	if ( typeof value.token !== 'string' || value.token === '' ) return false;
	if ( value.kind === 'user' ) return typeof value.user === 'object' && value.user !== null;
	if ( value.kind === 'child' ) return typeof value.child === 'object' && value.child !== null;
	return false;

}

/** The signed-in session, or null (none, unreadable, or expired at `now`). */
export function currentSession( { win = globalThis.window, now = Date.now() } = {} ) {

	const store = storage( win );
	if ( ! store ) return null;
	let session;
	try {

		session = JSON.parse( store.getItem( SESSION_KEY ) ?? 'null' );

	} catch {

		session = null;

	}

	if ( ! isSession( session ) ) return null;
	const expires = Date.parse( session.expires_at ?? '' );
	if ( Number.isFinite( expires ) && expires <= now ) {

		store.removeItem( SESSION_KEY );
		return null;

	}

	return session;

}

/** The bearer token to send, or null when nobody is signed in. */
export function currentToken( options ) {

	return currentSession( options )?.token ?? null;

}

/** Keep `session` ({ kind: 'user'|'child', token, expires_at, user|child }) and tell listeners. */
export function saveSession( session, { win = globalThis.window } = {} ) {

	if ( ! isSession( session ) ) throw new TypeError( 'a session needs kind "user" or "child", a token, and the user or child it belongs to' );
	storage( win )?.setItem( SESSION_KEY, JSON.stringify( session ) );
	notify( session );

}

/** Forget the session (after signing out, or when the server says the token is no longer good). */
export function clearSession( { win = globalThis.window } = {} ) {

	storage( win )?.removeItem( SESSION_KEY );
	notify( null );

}

/** Call `listener( session|null )` whenever this page signs in or out; returns an unsubscribe. */
export function onSessionChange( listener ) {

	listeners.add( listener );
	return () => listeners.delete( listener );

}

function notify( session ) {

	for ( const listener of listeners ) listener( session );

}
