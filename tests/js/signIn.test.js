// Signing in without a browser: where the sign-in page goes back to (never off the site), what a
// person reads when signing in fails, who the bar names, and the requests with a stand-in fetch.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { SESSION_KEY, currentSession } from '../../web/src/session.js';
import { ApiError } from '../../web/src/api.js';
import {
	hasRole, isForbidden, isSignedOut, landingFor, nextFromHash, ROLE_HOMES, retryAfterSeconds, rolesWords, safeNext, signIn, signInHref,
	signInMessage, signOut, waitWords, whoLabel,
} from '../../web/src/ui/shared/signIn.js';

function fakeWindow() {

	const items = new Map();
	return { localStorage: {
		getItem: ( key ) => ( items.has( key ) ? items.get( key ) : null ),
		setItem: ( key, value ) => items.set( key, String( value ) ),
		removeItem: ( key ) => items.delete( key ),
	} };

}

/** A fetch that answers `status` with `body` and `headers`, and records what it was asked. */
function fakeFetch( status, body, headers = {} ) {

	const calls = [];
	const fetch = async ( url, init ) => {

		calls.push( { url, init } );
		return {
			ok: status >= 200 && status < 300,
			status,
			statusText: '',
			headers: { get: ( name ) => headers[ name ] ?? null },
			json: async () => body,
		};

	};
	return { fetch, calls };

}

const ann = { id: 4, username: 'ann@school.example', display_name: 'Ann Reed', role: 'clinician' };

test( 'the sign-in address carries where to come back to, and reads it back', () => {

	assert.equal( signInHref( '#/clinician?recording=3' ), '#/signin?next=%23%2Fclinician%3Frecording%3D3' );
	assert.equal( nextFromHash( signInHref( '#/clinician?recording=3' ) ), '#/clinician?recording=3' );
	assert.equal( signInHref( '#/' ), '#/signin' );
	assert.equal( nextFromHash( '#/signin' ), '#/' );
	assert.equal( nextFromHash( '#/signin?next=%2Fworkbench' ), '#/workbench', 'a route without its # is taken' );

} );

test( 'after signing in a person is never sent off the site, nor back to the sign-in page', () => {

	for ( const next of [ 'https://evil.example/', '//evil.example', '#//evil.example', 'javascript:alert(1)', '#/a b', '#/signin', '#/signin?next=%23%2F', '/signin/', null, 42 ] ) {

		assert.equal( safeNext( next ), '#/', String( next ) );

	}

	assert.equal( safeNext( '#/speak' ), '#/speak' );

} );

test( 'Retry-After is read as seconds or as an HTTP date, and said in words', () => {

	assert.equal( retryAfterSeconds( '120' ), 120 );
	assert.equal( retryAfterSeconds( 'Wed, 25 Nov 2026 12:01:30 GMT', Date.parse( '2026-11-25T12:00:00Z' ) ), 90 );
	assert.equal( retryAfterSeconds( null ), null );
	assert.equal( retryAfterSeconds( 'soon' ), null );
	assert.equal( waitWords( 1 ), 'in 1 second' );
	assert.equal( waitWords( 40 ), 'in 40 seconds' );
	assert.equal( waitWords( 61 ), 'in 2 minutes' );
	assert.equal( waitWords( 0 ), 'in a moment' );

} );

test( 'a failed sign-in is said in plain words: wrong password, too many attempts with when, no server', () => {

	const failed = ( status ) => new ApiError( `POST /api/v1/auth/sessions failed with HTTP ${ status }`, { method: 'POST', status } );
	assert.equal( signInMessage( failed( 401 ) ), 'That username and password do not match. Check them and try again.' );
	assert.equal( signInMessage( failed( 429 ), { retryAfter: 300 } ), 'Too many attempts to sign in. Try again in 5 minutes.' );
	assert.equal( signInMessage( failed( 429 ) ), 'Too many attempts to sign in. Wait a few minutes, then try again.' );
	assert.equal( signInMessage( failed( null ) ), 'Could not reach the server. Check the connection and try again.' );
	assert.equal( signInMessage( failed( 503 ) ), 'The server failed while signing in. Try again in a moment.' );
	for ( const status of [ 401, 429, null, 422, 500 ] ) assert.doesNotMatch( signInMessage( failed( status ) ), /HTTP|\/api/, `status ${ status }` );

} );

test( 'a 401 means signed out and a 403 a role that may not; other errors mean neither', () => {

	assert.equal( isSignedOut( new ApiError( 'x', { status: 401 } ) ), true );
	assert.equal( isSignedOut( new ApiError( 'x', { status: 403 } ) ), false );
	assert.equal( isSignedOut( Object.assign( new Error( 'x' ), { status: 401 } ) ), false, 'only the API client\'s errors' );
	assert.equal( isForbidden( new ApiError( 'x', { status: 403 } ) ), true );
	assert.equal( isForbidden( new ApiError( 'x', { status: null } ) ), false );

} );

test( 'roles are checked on adults only, and the bar names the person and their role', () => {

	const session = { kind: 'user', token: 't', user: ann };
	assert.equal( hasRole( session, [ 'clinician', 'admin' ] ), true );
	assert.equal( hasRole( session, [ 'author' ] ), false );
	assert.equal( hasRole( session ), true );
	assert.equal( hasRole( { kind: 'child', token: 't', child: { id: 1 } } ), false );
	assert.equal( hasRole( null ), false );
	assert.equal( whoLabel( session ), 'Ann Reed (clinician)' );
	assert.equal( whoLabel( { kind: 'child', token: 't', child: { id: 1, display_name: 'Fox' } } ), 'Fox' );
	assert.equal( whoLabel( null ), null );
	assert.equal( rolesWords( [ 'clinician', 'admin' ] ), 'clinicians and admins' );
	assert.equal( rolesWords( [ 'author', 'clinician', 'admin' ] ), 'authors, clinicians and admins' );
	assert.equal( rolesWords( [ 'admin' ] ), 'admins' );

} );

test( 'signing in posts the username trimmed, sends no old token, and keeps the session', async () => {

	const win = fakeWindow();
	const { fetch, calls } = fakeFetch( 201, { token: 'tok-9', token_type: 'bearer', expires_at: '2099-01-01T00:00:00Z', user: ann } );
	const session = await signIn( '  ann@school.example ', 'pw-12345678', { fetchImpl: fetch, win } );
	assert.equal( calls.length, 1 );
	assert.equal( calls[ 0 ].url, '/api/v1/auth/sessions' );
	assert.equal( calls[ 0 ].init.method, 'POST' );
	assert.deepEqual( JSON.parse( calls[ 0 ].init.body ), { username: 'ann@school.example', password: 'pw-12345678' } );
	assert.equal( calls[ 0 ].init.headers.Authorization, undefined );
	assert.deepEqual( session, { kind: 'user', token: 'tok-9', expires_at: '2099-01-01T00:00:00Z', user: ann } );
	assert.deepEqual( currentSession( { win } ), session );

} );

test( 'a refused sign-in keeps nothing and says when to try again from Retry-After', async () => {

	const win = fakeWindow();
	const { fetch } = fakeFetch( 429, { detail: 'too many attempts' }, { 'Retry-After': '45' } );
	await assert.rejects( signIn( 'ann', 'wrong', { fetchImpl: fetch, win } ), { message: 'Too many attempts to sign in. Try again in 45 seconds.', status: 429 } );
	assert.equal( win.localStorage.getItem( SESSION_KEY ), null );
	const away = async () => {

		throw new TypeError( 'Failed to fetch' );

	};
	await assert.rejects( signIn( 'ann', 'pw', { fetchImpl: away, win } ), { message: 'Could not reach the server. Check the connection and try again.', status: null } );

} );

test( 'signing out revokes the token on the server and forgets it, even when the server refuses', async () => {

	const win = fakeWindow();
	win.localStorage.setItem( SESSION_KEY, JSON.stringify( { kind: 'user', token: 'tok-9', expires_at: '2099-01-01T00:00:00Z', user: ann } ) );
	const { fetch, calls } = fakeFetch( 204, null );
	await signOut( { fetchImpl: fetch, win } );
	assert.equal( calls[ 0 ].url, '/api/v1/auth/sessions/current' );
	assert.equal( calls[ 0 ].init.method, 'DELETE' );
	assert.equal( calls[ 0 ].init.headers.Authorization, 'Bearer tok-9' );
	assert.equal( currentSession( { win } ), null );

	win.localStorage.setItem( SESSION_KEY, JSON.stringify( { kind: 'child', token: 'c-1', expires_at: '2099-01-01T00:00:00Z', child: { id: 2 } } ) );
	const refused = fakeFetch( 401, { detail: 'gone' } );
	const warn = console.warn;
	console.warn = () => {};
	try {

		await signOut( { fetchImpl: refused.fetch, win } );

	} finally {

		console.warn = warn;

	}

	assert.equal( refused.calls[ 0 ].url, '/api/v1/auth/child-sessions/current' );
	assert.equal( currentSession( { win } ), null );

} );

test( 'a sign-in from the start page lands on the role\'s own home; one asked from a view goes back to it', () => {

	assert.deepEqual( Object.fromEntries( [ 'teacher', 'clinician', 'author', 'admin' ].map( ( role ) => [ role, landingFor( '#/', role ) ] ) ),
		{ teacher: '#/teach', clinician: '#/clinician', author: '#/author', admin: '#/admin' } );
	assert.equal( landingFor( null, 'teacher' ), ROLE_HOMES.teacher );
	assert.equal( landingFor( '#/workbench', 'teacher' ), '#/workbench' );
	assert.equal( landingFor( 'https://elsewhere.example/', 'clinician' ), '#/clinician', 'never another site' );
	assert.equal( landingFor( '#/', 'someone' ), '#/', 'a role without a home starts on the head' );

} );
