// The one HTTP client of the web app, for the Glasshead API (`/api/v1`). Every view loads through
// it; scene objects and core kernels never fetch. Every failure is an ApiError whose message names
// the method, the URL, the HTTP status and the server's `detail`, so the page can show it as it is.
//
//   import { api } from '../api.js';
//   const anatomy = await api.get( 'anatomy' );                  // GET /api/v1/anatomy
//   await api.post( 'poses', { name, params } );                 // POST /api/v1/poses
//   const bytes = await api.getBinary( info.url );               // an asset URL from an answer
//   await api.putBytes( 'practice/7/audio', wavBytes, 'audio/wav' ); // raw bytes, not JSON
//   const { body, headers } = await api.exchange( 'PUT', 'lessons/3', { body, headers: { 'If-Match': etag } } );
//
// Paths resolve as links do against the API base `/api/v1/`: 'anatomy' is /api/v1/anatomy, while
// a path from the site root ('/assets/build/maxilla.glb', as answers give them) or a full URL is
// used as it is. Tests make their own client with createApi( { fetchImpl } ).

import { currentToken } from './session.js';

/** Where the API lives. */
export const API_BASE = '/api/v1';

/** A request that failed: no answer, an HTTP error, or an answer that is not what was asked for. */
export class ApiError extends Error {

	/**
	 * @param {string} message says what failed, naming the request
	 * @param {{ method?: string, url?: string|null, status?: number|null, detail?: any, cause?: any }} fields
	 *   `status` is null when no answer came; `detail` is the server's error detail as it sent it
	 * @param {{ headers?: Headers|null }} [fields] the answer's headers (an ETag, a Retry-After), null without one
	 */
	constructor( message, { method = 'GET', url = null, status = null, detail = null, headers = null, cause } = {} ) {

		super( message, cause === undefined ? undefined : { cause } );
		this.name = 'ApiError';
		this.method = method;
		this.url = url;
		this.status = status;
		this.detail = detail;
		this.headers = headers;

	}

}

/**
 * The server's error detail as one line: a string as it is, FastAPI's validation errors as
 * "where: what", an object by its message when it has one.
 */
export function describeDetail( detail ) {

	if ( typeof detail === 'string' ) return detail;
	if ( Array.isArray( detail ) ) {

		return detail.map( ( entry ) => {

			const where = Array.isArray( entry?.loc ) ? entry.loc.filter( ( part ) => part !== 'body' ).join( '.' ) : '';
			return where ? `${ where }: ${ entry?.msg }` : String( entry?.msg ?? JSON.stringify( entry ) );

		} ).join( '; ' );

	}

	if ( detail === undefined || detail === null ) return '';
	if ( typeof detail.message === 'string' ) return detail.message;
	return JSON.stringify( detail );

}

/** Whether a request body is raw bytes, sent as they are (a WAV file). */
function isBytes( body ) {

	return body instanceof ArrayBuffer || ArrayBuffer.isView( body ) || ( typeof Blob !== 'undefined' && body instanceof Blob );

}

/** What exchange() can read an answer as (the Response method of each name). */
const READS = new Set( [ 'json', 'arrayBuffer', 'blob', 'text' ] );

/** The URL of `path` against `base`: relative paths go under it; '/…' and full URLs stay. */
export function resolveUrl( path, base = API_BASE ) {

	if ( typeof path !== 'string' || path === '' ) throw new TypeError( `a request needs a path, got ${ path }` );
	if ( path.startsWith( '/' ) || /^[a-z][a-z0-9+.-]*:/i.test( path ) ) return path;
	return `${ base }/${ path }`;

}

/**
 * A client of the API.
 * @param {{ base?: string, fetchImpl?: Function, tokenSource?: Function }} options `fetchImpl`
 *   stands in for the browser's fetch (tests); the default is the global fetch at the time of each
 *   request. `tokenSource()` gives the bearer token to send with each request, or null for none
 * @returns {{ base: string, url: Function, get: Function, post: Function, put: Function,
 *   patch: Function, delete: Function, getBinary: Function, putBytes: Function, exchange: Function }}
 *   every method returns a Promise and takes a last `{ signal }` option; get/post/put/patch/delete
 *   and putBytes resolve to the parsed JSON answer (null for an empty one), getBinary to an
 *   ArrayBuffer, and exchange to the whole answer (see below)
 */
export function createApi( { base = API_BASE, fetchImpl = null, tokenSource = null } = {} ) {

	/**
	 * One request, and the whole answer: { body, status, headers }.
	 * @param {{ body?: any, headers?: Object<string, string>, read?: 'json'|'arrayBuffer'|'blob'|'text',
	 *   signal?: AbortSignal }} options `body` is sent as JSON, or as it is when it is FormData (a
	 *   multipart upload) or bytes (a Blob, an ArrayBuffer or a typed array, with their
	 *   Content-Type in `headers`); `headers` are added to the request's (If-Match); `read` says what `body`
	 *   of the answer is: parsed JSON (null for 204, the default), an ArrayBuffer, a Blob or text
	 */
	async function exchange( method, path, { body, headers: extra = null, read = 'json', signal } = {} ) {

		if ( ! READS.has( read ) ) throw new TypeError( `an answer is read as ${ [ ...READS ].join( ', ' ) }, not ${ read }` );
		const url = resolveUrl( path, base );
		const headers = { Accept: read === 'json' ? 'application/json' : '*/*' };
		const token = tokenSource?.() ?? null;
		if ( token ) headers.Authorization = `Bearer ${ token }`;
		Object.assign( headers, extra );
		const init = { method, headers, signal };
		if ( body instanceof FormData ) init.body = body; // the browser writes its Content-Type
		else if ( isBytes( body ) ) init.body = body; // raw bytes: their Content-Type is the caller's header
		else if ( body !== undefined ) {

			headers[ 'Content-Type' ] = 'application/json';
			init.body = JSON.stringify( body );

		}

		const fetch = fetchImpl ?? globalThis.fetch;
		let response;
		try {

			response = await fetch( url, init );

		} catch ( error ) {

			if ( error?.name === 'AbortError' ) throw error;
			throw new ApiError( `Could not reach the server for ${ method } ${ url }: ${ error?.message ?? error }`, { method, url, cause: error } );

		}

		const { status } = response;
		if ( ! response.ok ) {

			let detail = null;
			try {

				detail = ( await response.json() )?.detail ?? null;

			} catch {
				// Not JSON (a proxy's page, a crash): the status text says what there is to say.
			}

			const said = describeDetail( detail ) || response.statusText || '';
			throw new ApiError( `${ method } ${ url } failed with HTTP ${ status }${ said ? `: ${ said }` : '' }`, { method, url, status, detail, headers: response.headers ?? null } );

		}

		const answer = { body: null, status, headers: response.headers ?? null };
		if ( read !== 'json' ) answer.body = await response[ read ]();
		else if ( status !== 204 ) {

			try {

				answer.body = await response.json();

			} catch ( error ) {

				throw new ApiError( `${ method } ${ url } returned invalid JSON: ${ error.message }`, { method, url, status, headers: answer.headers, cause: error } );

			}

		}

		return answer;

	}

	const request = async ( method, path, options ) => ( await exchange( method, path, options ) ).body;

	return Object.freeze( {
		base,
		/** The URL a path is requested at. */
		url: ( path ) => resolveUrl( path, base ),
		get: ( path, options ) => request( 'GET', path, options ),
		post: ( path, body, options ) => request( 'POST', path, { ...options, body } ),
		put: ( path, body, options ) => request( 'PUT', path, { ...options, body } ),
		patch: ( path, body, options ) => request( 'PATCH', path, { ...options, body } ),
		delete: ( path, options ) => request( 'DELETE', path, options ),
		getBinary: ( path, options ) => request( 'GET', path, { ...options, read: 'arrayBuffer' } ),
		/** PUT raw `bytes` (a Blob, an ArrayBuffer or a typed array) of `contentType`; resolves to the JSON answer. */
		putBytes: ( path, bytes, contentType, options ) => request( 'PUT', path, { ...options, body: bytes, headers: { ...options?.headers, 'Content-Type': contentType } } ),
		exchange,
	} );

}

/** The page's client: it sends the signed-in session's token (session.js) with every request. */
export const api = createApi( { tokenSource: () => currentToken() } );

/**
 * Check the shape of a `GET /anatomy` answer and return the meshes to put in the scene.
 * Returns { frame, meshes: [{ name, url, triangles, role, ... }] } with only `scene: true` meshes.
 */
export function parseAnatomy( body ) {

	if ( ! body || ! Array.isArray( body.meshes ) ) {

		throw new ApiError( 'The anatomy answer has no "meshes" list' );

	}

	const meshes = body.meshes.filter( ( mesh ) => mesh && mesh.scene === true );
	for ( const mesh of meshes ) {

		if ( typeof mesh.name !== 'string' || typeof mesh.url !== 'string' ) {

			throw new ApiError( `An anatomy mesh lacks a name or url: ${ JSON.stringify( mesh ) }` );

		}

	}

	if ( meshes.length === 0 ) throw new ApiError( 'The anatomy answer lists no meshes to show' );

	return { frame: body.frame ?? null, meshes };

}

/** GET /anatomy, checked. */
export async function getAnatomy( client = api ) {

	return parseAnatomy( await client.get( 'anatomy' ) );

}
