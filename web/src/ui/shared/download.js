// Downloads of files the API makes (a CSV of practice, an EPG recording, a lesson's JSON): a link
// cannot send the bearer token, so the page fetches the file with it and hands the browser the
// bytes to save under the name the server gave (Content-Disposition).
//
//   await downloadFile( 'children/3/practice.csv', 'child-3-practice.csv' );
//   saveAs( text, 'lesson-3.json', 'application/json' );

import { api as pageApi } from '../../api.js';

/** The file name in a Content-Disposition header, or `fallback`. */
export function attachmentName( header, fallback ) {

	const match = /filename\*?=(?:UTF-8'')?"?([^";]+)"?/i.exec( header ?? '' );
	return match ? decodeURIComponent( match[ 1 ] ) : fallback;

}

/** Let the browser save `content` (text or a Blob) as `filename`. */
export function saveAs( content, filename, type = 'application/octet-stream', doc = globalThis.document ) {

	const blob = content instanceof Blob ? content : new Blob( [ content ], { type } );
	const url = URL.createObjectURL( blob );
	const link = doc.createElement( 'a' );
	link.href = url;
	link.download = filename;
	link.hidden = true;
	doc.body.append( link );
	link.click();
	link.remove();
	setTimeout( () => URL.revokeObjectURL( url ), 10_000 );

}

/**
 * GET `path` through the API client `api` (with its token) and save the answer; resolves to the
 * name it was saved under. A failure is the client's ApiError.
 */
export async function downloadFile( path, fallback, { api = pageApi, save = saveAs } = {} ) {

	const { body, headers } = await api.exchange( 'GET', path, { read: 'blob' } );
	const filename = attachmentName( headers?.get( 'Content-Disposition' ), fallback );
	save( body, filename );
	return filename;

}
