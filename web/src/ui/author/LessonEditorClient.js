// The lesson requests of the author's editor, through the page's API client (api.js) with what
// the editor needs besides: the ETag of every read and write, If-Match on every change, and an
// export as a file. A stale save is an ApiError with status 412 and the lesson's current `etag`,
// so that the editor can offer to overwrite it knowingly (a write with that ETag) without losing
// the draft.
//
//   const lessons = createLessonClient();
//   const { lesson, etag } = await lessons.get( 3 );
//   const saved = await lessons.replace( 3, body, etag );   // { lesson, etag }; 412 when stale

import { api as pageApi, ApiError } from '../../api.js';
import { attachmentName } from '../shared/download.js';

/** @param {{ api?: object }} options the HTTP client (api.js's createApi) the lessons go through */
export function createLessonClient( { api = pageApi } = {} ) {

	/** The answer's { body, headers, etag }; a failure's ApiError carries the lesson's `etag` too. */
	async function request( method, path, { body, ifMatch = null, read = 'json' } = {} ) {

		try {

			const answer = await api.exchange( method, path, { body, read, headers: ifMatch ? { 'If-Match': ifMatch } : null } );
			return { ...answer, etag: answer.headers?.get( 'ETag' ) ?? null };

		} catch ( error ) {

			if ( error instanceof ApiError && error.status !== null ) error.etag = error.headers?.get( 'ETag' ) ?? null;
			throw error;

		}

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

			const { body, headers } = await request( 'GET', `lessons/${ id }/export`, { read: 'text' } );
			return { text: body, filename: attachmentName( headers?.get( 'Content-Disposition' ), `lesson-${ id }.json` ) };

		},
	} );

}
