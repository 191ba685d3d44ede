// Fetch helpers for the Glasshead HTTP API (`/api/v1`). Every failure becomes an ApiError whose
// message names the request and what went wrong, so the page can show it as it is.

export const API_BASE = '/api/v1';

export class ApiError extends Error {

	constructor( message, { url = null, status = null } = {} ) {

		super( message );
		this.name = 'ApiError';
		this.url = url;
		this.status = status;

	}

}

/** GET `path` under the API base and parse JSON; rejects with an ApiError. */
export async function fetchJson( path, { fetchImpl = globalThis.fetch, signal } = {} ) {

	const url = path.startsWith( '/' ) && ! path.startsWith( API_BASE ) ? API_BASE + path : path;
	let response;
	try {

		response = await fetchImpl( url, { signal, headers: { Accept: 'application/json' } } );

	} catch ( error ) {

		if ( error?.name === 'AbortError' ) throw error;
		throw new ApiError( `Could not reach the server for ${ url }: ${ error.message }`, { url } );

	}

	if ( ! response.ok ) {

		let detail;
		try {

			const body = await response.json();
			detail = typeof body?.detail === 'string' ? body.detail : JSON.stringify( body?.detail ?? body );

		} catch {

			detail = response.statusText;

		}

		throw new ApiError( `GET ${ url } failed with HTTP ${ response.status }${ detail ? `: ${ detail }` : '' }`, { url, status: response.status } );

	}

	try {

		return await response.json();

	} catch ( error ) {

		throw new ApiError( `GET ${ url } returned invalid JSON: ${ error.message }`, { url, status: response.status } );

	}

}

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
export async function getAnatomy( options ) {

	return parseAnatomy( await fetchJson( '/anatomy', options ) );

}
