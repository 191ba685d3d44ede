// The one HTTP client of the browser app (web/src/api.js) against a stand-in fetch.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { ApiError, createApi, describeDetail, getAnatomy, parseAnatomy, resolveUrl } from '../../web/src/api.js';

const respond = ( status, body, statusText = '' ) => async () => ( {
	ok: status >= 200 && status < 300,
	status,
	statusText,
	json: async () => ( typeof body === 'string' ? JSON.parse( body ) : body ),
	arrayBuffer: async () => new Uint8Array( [ 1, 2, 3 ] ).buffer,
} );

/** A client whose fetch records every request and answers with `answer`. */
function recording( answer = respond( 200, {} ) ) {

	const requests = [];
	const api = createApi( { fetchImpl: async ( url, init ) => {

		requests.push( { url, init } );
		return answer( url, init );

	} } );
	return { api, requests };

}

test( 'relative paths are requested under /api/v1; paths from the site root and full URLs as they are', async () => {

	const { api, requests } = recording();
	await api.get( 'health' );
	await api.get( 'epg/layout?grid=reading62' );
	await api.getBinary( '/assets/build/maxilla.glb?v=1' );
	await api.get( 'https://example.org/x' );
	assert.deepEqual( requests.map( ( r ) => r.url ), [ '/api/v1/health', '/api/v1/epg/layout?grid=reading62', '/assets/build/maxilla.glb?v=1', 'https://example.org/x' ] );
	assert.equal( resolveUrl( 'poses/3', '/base' ), '/base/poses/3' );
	assert.throws( () => resolveUrl( '' ), TypeError );

} );

test( 'every verb sends its method, and a body as JSON', async () => {

	const { api, requests } = recording();
	await api.post( 'poses', { name: 'a' } );
	await api.put( 'poses/1', { name: 'b' } );
	await api.patch( 'poses/1', { description: 'c' } );
	await api.delete( 'poses/1' );
	assert.deepEqual( requests.map( ( r ) => r.init.method ), [ 'POST', 'PUT', 'PATCH', 'DELETE' ] );
	assert.equal( requests[ 0 ].init.headers[ 'Content-Type' ], 'application/json' );
	assert.deepEqual( JSON.parse( requests[ 1 ].init.body ), { name: 'b' } );
	assert.equal( requests[ 3 ].init.body, undefined );

} );

test( 'an exchange adds headers, sends FormData as it is, reads the answer as asked and gives its headers, also with a refusal', async () => {

	const answered = ( status, headers, body ) => async () => ( {
		ok: status >= 200 && status < 300, status, statusText: '',
		headers: { get: ( name ) => headers[ name.toLowerCase() ] ?? null },
		json: async () => body, text: async () => JSON.stringify( body ), blob: async () => new Blob( [ 'b' ] ),
	} );
	const { api, requests } = recording( answered( 200, { etag: '"v2"' }, { id: 3 } ) );
	const json = await api.exchange( 'PUT', 'lessons/3', { body: { title: 't' }, headers: { 'If-Match': '"v1"' } } );
	assert.deepEqual( json.body, { id: 3 } );
	assert.equal( json.status, 200 );
	assert.equal( json.headers.get( 'ETag' ), '"v2"' );
	assert.equal( requests[ 0 ].init.headers[ 'If-Match' ], '"v1"' );
	assert.equal( requests[ 0 ].init.headers.Accept, 'application/json' );
	assert.equal( ( await api.exchange( 'GET', 'lessons/3/export', { read: 'text' } ) ).body, '{"id":3}' );
	assert.equal( requests[ 1 ].init.headers.Accept, '*/*' );
	assert.ok( ( await api.exchange( 'GET', 'children/3/export', { read: 'blob' } ) ).body instanceof Blob );
	const form = new FormData();
	form.append( 'file', new Blob( [ 'x' ] ), 'take.csv' );
	await api.exchange( 'POST', 'epg/recordings', { body: form } );
	assert.equal( requests[ 3 ].init.body, form );
	assert.equal( requests[ 3 ].init.headers[ 'Content-Type' ], undefined, 'the browser writes the multipart type' );
	await assert.rejects( api.exchange( 'GET', 'x', { read: 'formData' } ), TypeError );

	const stale = createApi( { fetchImpl: answered( 412, { etag: '"v3"' }, { detail: 'lesson 3 changed' } ) } );
	const error = await stale.put( 'lessons/3', {} ).catch( ( e ) => e );
	assert.ok( error instanceof ApiError );
	assert.equal( error.status, 412 );
	assert.equal( error.headers.get( 'ETag' ), '"v3"' );

} );

test( 'raw bytes are PUT as they are, under the Content-Type given, never as JSON', async () => {

	const { api, requests } = recording();
	const wav = new Uint8Array( [ 0x52, 0x49, 0x46, 0x46 ] );
	await api.putBytes( 'practice/7/audio', wav, 'audio/wav' );
	await api.putBytes( 'practice/8/audio', wav.buffer, 'audio/wav', { headers: { 'If-Match': '"1"' } } );
	assert.deepEqual( requests.map( ( r ) => [ r.url, r.init.method, r.init.headers[ 'Content-Type' ] ] ),
		[ [ '/api/v1/practice/7/audio', 'PUT', 'audio/wav' ], [ '/api/v1/practice/8/audio', 'PUT', 'audio/wav' ] ] );
	assert.equal( requests[ 0 ].init.body, wav, 'the very bytes, not a JSON text of them' );
	assert.equal( requests[ 1 ].init.body, wav.buffer );
	assert.equal( requests[ 1 ].init.headers[ 'If-Match' ], '"1"' );

} );

test( 'a binary GET resolves to the bytes; an empty answer (204) to null', async () => {

	const { api } = recording( respond( 200, null ) );
	assert.deepEqual( Array.from( new Uint8Array( await api.getBinary( 'collision/tables.bin' ) ) ), [ 1, 2, 3 ] );
	const empty = createApi( { fetchImpl: respond( 204, null ) } );
	assert.equal( await empty.delete( 'poses/1' ), null );

} );

test( 'an HTTP error becomes an ApiError naming the method, URL and status, and quoting the server\'s detail', async () => {

	const api = createApi( { fetchImpl: respond( 503, { detail: 'anatomy not built: run `glasshead build`' } ) } );
	await assert.rejects( api.get( 'anatomy' ), ( error ) => {

		assert.ok( error instanceof ApiError );
		assert.equal( error.status, 503 );
		assert.equal( error.method, 'GET' );
		assert.equal( error.url, '/api/v1/anatomy' );
		assert.equal( error.detail, 'anatomy not built: run `glasshead build`' );
		assert.equal( error.message, 'GET /api/v1/anatomy failed with HTTP 503: anatomy not built: run `glasshead build`' );
		return true;

	} );
	const refused = createApi( { fetchImpl: respond( 422, { detail: [ { loc: [ 'body', 'params', 'tip_height' ], msg: 'Input should be a finite number' } ] } ) } );
	await assert.rejects( refused.post( 'poses', {} ), { message: 'POST /api/v1/poses failed with HTTP 422: params.tip_height: Input should be a finite number' } );
	const plain = createApi( { fetchImpl: respond( 500, '<html>', 'Internal Server Error' ) } );
	await assert.rejects( plain.put( 'poses/1', {} ), { message: 'PUT /api/v1/poses/1 failed with HTTP 500: Internal Server Error' } );

} );

test( 'a network failure and invalid JSON are ApiErrors too; an abort passes through', async () => {

	const offline = createApi( { fetchImpl: async () => {

		throw new TypeError( 'Failed to fetch' );

	} } );
	await assert.rejects( offline.patch( 'poses/1', {} ), ( error ) => error instanceof ApiError && error.status === null &&
		error.message === 'Could not reach the server for PATCH /api/v1/poses/1: Failed to fetch' );
	await assert.rejects( createApi( { fetchImpl: respond( 200, '{oops' ) } ).get( 'anatomy' ), ( error ) => error instanceof ApiError && /GET \/api\/v1\/anatomy returned invalid JSON/.test( error.message ) );
	const aborted = createApi( { fetchImpl: async () => {

		throw new DOMException( 'The operation was aborted.', 'AbortError' );

	} } );
	await assert.rejects( aborted.get( 'anatomy' ), { name: 'AbortError' } );

} );

test( 'the server\'s detail reads as one line whatever its shape', () => {

	assert.equal( describeDetail( 'plain words' ), 'plain words' );
	assert.equal( describeDetail( undefined ), '' );
	assert.equal( describeDetail( [ { loc: [ 'body', 'name' ], msg: 'too long' }, { msg: 'and this' } ] ), 'name: too long; and this' );
	assert.equal( describeDetail( { message: 'the tongue rig is not built', asset: 'tongue-rig.json' } ), 'the tongue rig is not built' );
	assert.equal( describeDetail( { asset: 'x' } ), '{"asset":"x"}' );

} );

test( 'only meshes marked for the scene are kept from the anatomy', async () => {

	const body = { frame: { units: 'mm' }, meshes: [
		{ name: 'maxilla', url: '/a/maxilla.glb', scene: true, triangles: 3 },
		{ name: 'maxilla_full', url: '/a/full.glb', scene: false, triangles: 9 },
	] };
	const anatomy = await getAnatomy( createApi( { fetchImpl: respond( 200, body ) } ) );
	assert.deepEqual( anatomy.meshes.map( ( mesh ) => mesh.name ), [ 'maxilla' ] );
	assert.deepEqual( anatomy.frame, { units: 'mm' } );

} );

test( 'an anatomy answer without meshes, or a mesh without a url, is refused', () => {

	assert.throws( () => parseAnatomy( {} ), /no "meshes" list/ );
	assert.throws( () => parseAnatomy( { meshes: [] } ), /no meshes to show/ );
	assert.throws( () => parseAnatomy( { meshes: [ { name: 'x', scene: true } ] } ), /lacks a name or url/ );

} );
