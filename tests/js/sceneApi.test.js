// Fetch helpers of the browser app (web/src/api.js) against a stand-in fetch.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { ApiError, fetchJson, getAnatomy, parseAnatomy } from '../../web/src/api.js';

const respond = ( status, body, statusText = '' ) => async () => ( {
	ok: status >= 200 && status < 300,
	status,
	statusText,
	json: async () => ( typeof body === 'string' ? JSON.parse( body ) : body ),
} );

test( 'paths are requested under /api/v1', async () => {

	const urls = [];
	await fetchJson( '/health', { fetchImpl: async ( url ) => {

		urls.push( url );
		return respond( 200, { status: 'ok' } )();

	} } );
	await fetchJson( '/api/v1/anatomy', { fetchImpl: async ( url ) => {

		urls.push( url );
		return respond( 200, {} )();

	} } );
	assert.deepEqual( urls, [ '/api/v1/health', '/api/v1/anatomy' ] );

} );

test( 'an HTTP error becomes an ApiError that quotes the server\'s detail', async () => {

	await assert.rejects( fetchJson( '/anatomy', { fetchImpl: respond( 503, { detail: 'anatomy not built: run `glasshead build`' } ) } ), ( error ) => {

		assert.ok( error instanceof ApiError );
		assert.equal( error.status, 503 );
		assert.match( error.message, /GET \/api\/v1\/anatomy failed with HTTP 503: anatomy not built/ );
		return true;

	} );

} );

test( 'a network failure and invalid JSON are reported as such', async () => {

	await assert.rejects( fetchJson( '/anatomy', { fetchImpl: async () => {

		throw new TypeError( 'Failed to fetch' );

	} } ), /Could not reach the server for \/api\/v1\/anatomy: Failed to fetch/ );
	await assert.rejects( fetchJson( '/anatomy', { fetchImpl: respond( 200, '{oops' ) } ), /returned invalid JSON/ );

} );

test( 'only meshes marked for the scene are kept from the anatomy', async () => {

	const body = { frame: { units: 'mm' }, meshes: [
		{ name: 'maxilla', url: '/a/maxilla.glb', scene: true, triangles: 3 },
		{ name: 'maxilla_full', url: '/a/full.glb', scene: false, triangles: 9 },
	] };
	const anatomy = await getAnatomy( { fetchImpl: respond( 200, body ) } );
	assert.deepEqual( anatomy.meshes.map( ( mesh ) => mesh.name ), [ 'maxilla' ] );
	assert.deepEqual( anatomy.frame, { units: 'mm' } );

} );

test( 'an anatomy answer without meshes, or a mesh without a url, is refused', () => {

	assert.throws( () => parseAnatomy( {} ), /no "meshes" list/ );
	assert.throws( () => parseAnatomy( { meshes: [] } ), /no meshes to show/ );
	assert.throws( () => parseAnatomy( { meshes: [ { name: 'x', scene: true } ] } ), /lacks a name or url/ );

} );
