// The lesson requests of the author's editor, with what the page's API client (api.js) leaves
// out: the ETag of every read and write, If-Match on every change, and an export as a file. A
// stale save is an ApiError with status 412 and the lesson's current `etag`, so that the editor
// can offer to overwrite it knowingly (a write with that ETag) without losing the draft.
//
//   const lessons = createLessonClient();
//   const { lesson, etag } = await lessons.get( 3 );
//   const saved = await lessons.replace( 3, body, etag );   // { lesson, etag }; 412 when stale

import { ApiError, API_BASE, describeDetail, resolveUrl } from '../../api.js';
import { currentToken } from '../../session.js';
import { attachmentName } from '../shared/download.js';

/**
 * @param {{ base?: string, fetchImpl?: Function, tokenSource?: Function }} options as createApi's
 */
export function createLessonClient( { base = API_BASE, fetchImpl = null, tokenSource = () => currentToken() } = {} ) {

	async function request( method, path, { body, ifMatch = null, raw = false } = {} ) {

		const url = resolveUrl( path, base );
		const headers = { Accept: raw ? '*/*' : 'application/json' };
		const token = tokenSource?.() ?? null;
		if ( token ) headers.Authorization = `Bearer ${ token }`;
		if ( ifMatch ) headers[ 'If-Match' ] = ifMatch;
		const init = { method, headers };
		if ( body !== undefined ) {

			headers[ 'Content-Type' ] = 'application/json';
			init.body = JSON.stringify( body );

		}

		let response;
		try {

			response = await ( fetchImpl ?? globalThis.fetch )( url, init );

		} catch ( error ) {

			throw new ApiError( `Could not reach the server for ${ method } ${ url }: ${ error?.message ?? error }`, { method, url, cause: error } );

		}

		const etag = response.headers.get( 'ETag' );
		if ( ! response.ok ) {

			let detail = null;
			try {

				detail = ( await response.json() )?.detail ?? null;

			} catch {
				// Not JSON: the status says it.
			}

			const said = describeDetail( detail ) || response.statusText || '';
			const error = new ApiError( `${ method } ${ url } failed with HTTP ${ response.status }${ said ? `: ${ said }` : '' }`, { method, url, status: response.status, detail } );
			error.etag = etag;
			throw error;

		}

		if ( raw ) return { response, etag };
		return { body: response.status === 204 ? null : await response.json(), etag };

	}

	const lessonOf = ( { body, etag } ) => ( { lesson: body, etag } );

	return Object.freeze( {
		/** GET /lessons: summaries in id order. */
		list: async () => ( await request( 'GET', 'lessons?limit=1000' ) ).body.lessons ?? [],
		/** GET /lessons/{id}: { lesson, etag }. */
		get: async ( id ) => lessonOf( await request( 'GET', `lessons/${ id }` ) ),
		/** POST /lessons: { lesson, etag }. */
		create: async ( body ) => lessonOf( await request( 'POST', 'lessons', { body } ) ),
		/** PUT /lessons/{id} with If-Match `etag` (none: overwrite): { lesson, etag }. */
		replace: async ( id, body, etag ) => lessonOf( await request( 'PUT', `lessons/${ id }`, { body, ifMatch: etag } ) ),
		/** DELETE /lessons/{id} with If-Match `etag`. */
		remove: async ( id, etag ) => {

			await request( 'DELETE', `lessons/${ id }`, { ifMatch: etag } );

		},
		/** POST /lessons/import of a lesson file's content: { lesson, etag }. */
		importLesson: async ( content ) => lessonOf( await request( 'POST', 'lessons/import', { body: content } ) ),
		/** GET /lessons/{id}/export: { text, filename } of the file to download. */
		exportFile: async ( id ) => {

			const { response } = await request( 'GET', `lessons/${ id }/export`, { raw: true } );
			return { text: await response.text(), filename: attachmentName( response.headers.get( 'Content-Disposition' ), `lesson-${ id }.json` ) };

		},
	} );

}
