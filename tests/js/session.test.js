import { test } from 'node:test';
import assert from 'node:assert/strict';
import { SESSION_KEY, clearSession, currentSession, currentToken, onSessionChange, saveSession } from '../../web/src/session.js';
import { createApi } from '../../web/src/api.js';

function fakeWindow() {

	const items = new Map();
	return { localStorage: {
		getItem: ( key ) => ( items.has( key ) ? items.get( key ) : null ),
		setItem: ( key, value ) => items.set( key, String( value ) ),
		removeItem: ( key ) => items.delete( key ),
	} };

}

const user = { id: 3, username: 'ms.reed', role: 'teacher', display_name: 'Ms Reed' };

test( 'a saved session is read back with its token until it expires', () => {

	const win = fakeWindow();
	assert.equal( currentSession( { win } ), null );
	saveSession( { kind: 'user', token: 'tok-1', expires_at: '2030-01-01T00:00:00Z', user }, { win } );
	assert.equal( currentToken( { win, now: Date.parse( '2029-12-31T23:59:00Z' ) } ), 'tok-1' );
	assert.equal( currentSession( { win, now: Date.parse( '2030-01-01T00:00:01Z' ) } ), null );
	assert.equal( win.localStorage.getItem( SESSION_KEY ), null, 'an expired session is forgotten' );

} );

test( 'a session without a token or owner is refused, and a corrupt stored one reads as none', () => {

	const win = fakeWindow();
	assert.throws( () => saveSession( { kind: 'user', token: '', user }, { win } ), /token/ );
	assert.throws( () => saveSession( { kind: 'child', token: 't' }, { win } ), /child/ );
	win.localStorage.setItem( SESSION_KEY, '{not json' );
	assert.equal( currentSession( { win } ), null );

} );

test( 'signing in and out tells the listeners', () => {

	const win = fakeWindow();
	const seen = [];
	const stop = onSessionChange( ( session ) => seen.push( session?.kind ?? null ) );
	saveSession( { kind: 'child', token: 'c', expires_at: '2030-01-01T00:00:00Z', child: { id: 1 } }, { win } );
	clearSession( { win } );
	stop();
	clearSession( { win } );
	assert.deepEqual( seen, [ 'child', null ] );

} );

test( 'the API client sends the bearer token when there is one, and no header when there is none', async () => {

	const sent = [];
	const fetchImpl = async ( url, init ) => {

		sent.push( init.headers.Authorization ?? null );
		return new Response( '{}', { status: 200, headers: { 'Content-Type': 'application/json' } } );

	};
	let token = 'abc';
	const client = createApi( { fetchImpl, tokenSource: () => token } );
	await client.get( 'auth/me' );
	token = null;
	await client.get( 'anatomy' );
	assert.deepEqual( sent, [ 'Bearer abc', null ] );

} );
