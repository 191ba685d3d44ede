// Importing a client's EPG recording from the clinician view: choose a file or drop it on the
// import box; it is sent as a multipart upload to POST /api/v1/epg/recordings (emuR JSON, CSV or
// SSFF, told apart by the server from the name and the content), and what went wrong is said in
// plain words beside the box, where the user is looking. The server checks a file whole before it
// stores anything, so a refused file leaves the stored recordings as they were.

import { API_BASE, describeDetail } from '../api.js';
import { h } from './Controls.js';

/** Largest file sent, bytes: the server's limit (MAX_UPLOAD_BYTES in api/routes/recordings.py). */
export const MAX_IMPORT_BYTES = 32 * 1024 * 1024;
/** What the file chooser offers: emuR JSON, CSV, SSFF. */
export const IMPORT_ACCEPT = '.json,.csv,.ssff,.epg';

/**
 * Plain words for a refused import: the HTTP `status` and the server's `detail`.
 * @returns {string}
 */
export function importErrorMessage( status, detail ) {

	const said = describeDetail( detail );
	if ( status === 413 ) return `The file is too large: recordings can be at most ${ MAX_IMPORT_BYTES / 1024 / 1024 } MB.`;
	if ( status === 422 ) return `The file could not be imported, nothing was stored: ${ said || 'it is not an EPG recording' }.`;
	if ( status === 415 ) return 'The file could not be sent as a file upload.';
	return `The import failed (HTTP ${ status })${ said ? `: ${ said }` : '' }.`;

}

/**
 * Send `file` (a File or Blob with a name) to POST /epg/recordings. Resolves to the server's
 * { recordings, total }; rejects with an Error whose message can be shown as it is.
 * @param {{ fetchImpl?: Function, base?: string }} options
 */
export async function importRecordingFile( file, { fetchImpl = null, base = API_BASE } = {} ) {

	if ( ! file ) throw new Error( 'Choose a file to import.' );
	if ( file.size === 0 ) throw new Error( `"${ file.name }" is empty: nothing was imported.` );
	if ( file.size > MAX_IMPORT_BYTES ) throw new Error( importErrorMessage( 413 ) );
	const form = new FormData();
	form.append( 'file', file, file.name );
	const fetch = fetchImpl ?? globalThis.fetch;
	let response;
	try {

		response = await fetch( `${ base }/epg/recordings`, { method: 'POST', body: form, headers: { Accept: 'application/json' } } );

	} catch ( error ) {

		throw new Error( `Could not reach the server to import "${ file.name }": ${ error?.message ?? error }`, { cause: error } );

	}

	let body = null;
	try {

		body = await response.json();

	} catch {
		// Not JSON: the status says what there is to say.
	}

	if ( ! response.ok ) throw new Error( importErrorMessage( response.status, body?.detail ) );
	if ( ! Array.isArray( body?.recordings ) ) throw new Error( 'The server answered the import with something that is not a list of recordings.' );
	return body;

}

/**
 * The import box: a file button and a drop zone, with its own status and error lines.
 * `onImported( body )` gets the server's answer once a file is stored.
 */
export class RecordingImport {

	/** @param {{ onImported: ( body: object ) => any, send?: ( file: File ) => Promise<object> }} options */
	constructor( { onImported, send = ( file ) => importRecordingFile( file ) } ) {

		this.onImported = onImported;
		this.send = send;
		this.busy = false;
		/** The last outcome, for window.glasshead: { ok, message } or null. */
		this.outcome = null;
		this.input = h( 'input', { type: 'file', accept: IMPORT_ACCEPT, className: 'cv-file', 'aria-label': 'Import a recording file', onChange: () => this.importFiles( this.input.files ) } );
		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' } );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
		this.element = h( 'div', { className: 'cv-import', 'aria-label': 'Import a recording' },
			h( 'label', { className: 'cv-import-button' }, 'Import a recording…', this.input ),
			h( 'span', { className: 'cv-import-hint' }, 'or drop a file here (emuR JSON, CSV or SSFF)' ),
			this.status, this.error );
		for ( const type of [ 'dragenter', 'dragover' ] ) this.element.addEventListener( type, ( event ) => this.dragOver( event ) );
		this.element.addEventListener( 'dragleave', () => this.element.classList.remove( 'cv-drop' ) );
		this.element.addEventListener( 'drop', ( event ) => this.drop( event ) );

	}

	dragOver( event ) {

		event.preventDefault();
		this.element.classList.add( 'cv-drop' );

	}

	drop( event ) {

		event.preventDefault();
		this.element.classList.remove( 'cv-drop' );
		return this.importFiles( event.dataTransfer?.files );

	}

	/** Import the first of `files` (one file at a time). */
	async importFiles( files ) {

		const file = files?.[ 0 ];
		if ( ! file || this.busy ) return null;
		this.busy = true;
		this.show( `Importing "${ file.name }"…`, null );
		try {

			const body = await this.send( file );
			const count = body.recordings.length;
			this.show( `Imported "${ file.name }": ${ count } recording${ count === 1 ? '' : 's' }.`, null );
			this.outcome = { ok: true, message: this.status.textContent, ids: body.recordings.map( ( r ) => r.id ) };
			await this.onImported( body );
			return body;

		} catch ( error ) {

			this.show( '', error.message );
			this.outcome = { ok: false, message: error.message };
			return null;

		} finally {

			this.busy = false;
			this.input.value = '';

		}

	}

	show( status, error ) {

		this.status.textContent = status;
		this.error.textContent = error ?? '';
		this.error.hidden = ! error;

	}

}
