// Downloads of files the API makes (a CSV of practice, an EPG recording, a lesson's JSON): a link
// cannot send the bearer token, so the page fetches the file with it and hands the browser the
// bytes to save under the name the server gave (Content-Disposition).
//
//   await downloadFile( 'children/3/practice.csv', 'child-3-practice.csv' );
//   saveAs( text, 'lesson-3.json', 'application/json' );

import { ApiError, API_BASE, describeDetail, resolveUrl } from '../../api.js';
import { currentToken } from '../../session.js';

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
 * GET `path` (resolved as api.js resolves it) with the signed-in token and save the answer;
 * resolves to the name it was saved under. A failure is an ApiError, as the API client's.
 */
export async function downloadFile( path, fallback, { fetchImpl = null, tokenSource = () => currentToken(), save = saveAs } = {} ) {

	const url = resolveUrl( path, API_BASE );
	const token = tokenSource?.() ?? null;
	const headers = token ? { Authorization: `Bearer ${ token }` } : {};
	let response;
	try {

		response = await ( fetchImpl ?? globalThis.fetch )( url, { headers } );

	} catch ( error ) {

		throw new ApiError( `Could not reach the server for GET ${ url }: ${ error?.message ?? error }`, { url, cause: error } );

	}

	if ( ! response.ok ) {

		const detail = await response.json().then( ( body ) => body?.detail ?? null, () => null );
		const said = describeDetail( detail ) || response.statusText || '';
		throw new ApiError( `GET ${ url } failed with HTTP ${ response.status }${ said ? `: ${ said }` : '' }`, { url, status: response.status, detail } );

	}

	const filename = attachmentName( response.headers.get( 'Content-Disposition' ), fallback );
	save( await response.blob(), filename );
	return filename;

}
