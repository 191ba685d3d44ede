// Importing a client's EPG recording from the clinician view: choose a file or drop it on the
// import box; it is sent as a multipart upload to POST /api/v1/epg/recordings (emuR JSON, CSV or
// SSFF, told apart by the server from the name and the content), and what went wrong is said in
// plain words beside the box, where the user is looking. The server checks a file whole before it
// stores anything, so a refused file leaves the stored recordings as they were.
//
// A recording is of a child of the clinician's caseload (the form field `child_id`, chosen in the
// box from GET /children) or a reference recording (no child). The upload carries the signed-in
// session's token, as every request of the API client does.

import { api as pageApi, ApiError, describeDetail } from '../../api.js';
import { h } from '../shared/dom.js';

/** The child chooser's value for a reference recording (no child). */
export const REFERENCE = '';

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
	if ( status === 401 ) return 'Please sign in to import recordings.';
	if ( status === 403 ) return 'Only clinicians and admins can import recordings.';
	if ( status === 404 ) return 'That child is not in your caseload: nothing was imported.';
	return `The import failed (HTTP ${ status })${ said ? `: ${ said }` : '' }.`;

}

/**
 * Send `file` (a File or Blob with a name) to POST /epg/recordings, as a recording of the child
 * `childId` (a reference recording when it is REFERENCE or null). Resolves to the server's
 * { recordings, total }; rejects with an ApiError (status, detail) whose message can be shown as
 * it is, or an Error before sending.
 * @param {{ childId?: string|number|null, api?: object }} options `api`: the HTTP client (api.js)
 */
export async function importRecordingFile( file, { childId = null, api = pageApi } = {} ) {

	if ( ! file ) throw new Error( 'Choose a file to import.' );
	if ( file.size === 0 ) throw new Error( `"${ file.name }" is empty: nothing was imported.` );
	if ( file.size > MAX_IMPORT_BYTES ) throw new Error( importErrorMessage( 413 ) );
	const form = new FormData();
	form.append( 'file', file, file.name );
	if ( childId !== null && childId !== REFERENCE ) form.append( 'child_id', String( childId ) );
	let body;
	try {

		( { body } = await api.exchange( 'POST', 'epg/recordings', { body: form } ) );

	} catch ( error ) {

		if ( ! ( error instanceof ApiError ) ) throw error;
		const { status } = error;
		if ( status === null ) throw new Error( `Could not reach the server to import "${ file.name }": ${ error.cause?.message ?? error.cause }`, { cause: error } );
		if ( status < 200 || status >= 300 ) throw new ApiError( importErrorMessage( status, error.detail ), { method: 'POST', url: error.url, status, detail: error.detail } );
		body = null; // an answer that is not JSON

	}

	if ( ! Array.isArray( body?.recordings ) ) throw new Error( 'The server answered the import with something that is not a list of recordings.' );
	return body;

}

/**
 * The import box: a file button and a drop zone, with its own status and error lines.
 * `onImported( body )` gets the server's answer once a file is stored.
 */
export class RecordingImport {

	/**
	 * @param {{ onImported: ( body: object ) => any, onError?: ( error: Error ) => any,
	 *   send?: ( file: File, options: { childId: string } ) => Promise<object> }} options
	 *   `onError` sees a failed import first (the view turns a 401 into a sign-in prompt)
	 */
	constructor( { onImported, onError = () => {}, send = ( file, options ) => importRecordingFile( file, options ) } ) {

		this.onImported = onImported;
		this.onError = onError;
		this.send = send;
		this.busy = false;
		/** The last outcome, for window.glasshead: { ok, message } or null. */
		this.outcome = null;
		this.input = h( 'input', { type: 'file', accept: IMPORT_ACCEPT, className: 'cv-file', 'aria-label': 'Import a recording file', onChange: () => this.importFiles( this.input.files ) } );
		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' } );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
		this.childSelect = h( 'select', { id: 'cv-import-child', className: 'cv-import-child' }, h( 'option', { value: REFERENCE }, 'Reference recording (no child)' ) );
		this.element = h( 'div', { className: 'cv-import', 'aria-label': 'Import a recording' },
			h( 'label', { className: 'cv-import-child-label', for: 'cv-import-child' }, 'Recorded from' ),
			this.childSelect,
			h( 'label', { className: 'cv-import-button' }, 'Import a recording…', this.input ),
			h( 'span', { className: 'cv-import-hint' }, 'or drop a file here (emuR JSON, CSV or SSFF)' ),
			this.status, this.error );
		for ( const type of [ 'dragenter', 'dragover' ] ) this.element.addEventListener( type, ( event ) => this.dragOver( event ) );
		this.element.addEventListener( 'dragleave', () => this.element.classList.remove( 'cv-drop' ) );
		this.element.addEventListener( 'drop', ( event ) => this.drop( event ) );

	}

	/** Offer `children` ([{ id, display_name }], the caseload) in the chooser, after the reference. */
	setChildren( children ) {

		const chosen = this.childSelect.value;
		this.childSelect.replaceChildren( h( 'option', { value: REFERENCE }, 'Reference recording (no child)' ),
			...children.map( ( child ) => h( 'option', { value: String( child.id ) }, child.display_name ) ) );
		this.childSelect.value = children.some( ( child ) => String( child.id ) === chosen ) ? chosen : REFERENCE;
		this.children = children.length;

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

			const body = await this.send( file, { childId: this.childSelect.value } );
			const count = body.recordings.length;
			this.show( `Imported "${ file.name }": ${ count } recording${ count === 1 ? '' : 's' }.`, null );
			this.outcome = { ok: true, message: this.status.textContent, ids: body.recordings.map( ( r ) => r.id ) };
			await this.onImported( body );
			return body;

		} catch ( error ) {

			this.show( '', error.message );
			this.outcome = { ok: false, message: error.message };
			this.onError( error );
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
