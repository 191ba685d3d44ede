// The workbench's pose box: reset, copy the parameters as JSON, paste JSON back (a bad paste is
// explained inline and changes nothing), and save the parameters as a named pose
// (POST /api/v1/poses).

import { API_BASE } from '../api.js';
import { h } from './Controls.js';

/**
 * Save `params` as the pose `name`. Resolves to the created pose; rejects with an Error whose
 * message can be shown as it is (a duplicate name, a refused value, an unreachable server).
 */
export async function savePose( name, params, { fetchImpl = globalThis.fetch } = {} ) {

	const trimmed = ( name ?? '' ).trim();
	if ( trimmed === '' ) throw new Error( 'Give the pose a name first.' );
	let response;
	try {

		response = await fetchImpl( `${ API_BASE }/poses`, {
			method: 'POST',
			headers: { 'Content-Type': 'application/json', Accept: 'application/json' },
			body: JSON.stringify( { name: trimmed, params } ),
		} );

	} catch ( error ) {

		throw new Error( `Could not reach the server to save the pose: ${ error.message }`, { cause: error } );

	}

	const body = await response.json().catch( () => null );

	if ( response.status === 409 ) throw new Error( `A pose named "${ trimmed }" already exists. Choose another name.` );
	if ( ! response.ok ) throw new Error( `The pose was not saved (HTTP ${ response.status }): ${ describeDetail( body?.detail ) || response.statusText }` );
	return body;

}

/** FastAPI's error detail as one line: a string as it is, validation errors as "where: what". */
export function describeDetail( detail ) {

	if ( typeof detail === 'string' ) return detail;
	if ( Array.isArray( detail ) ) {

		return detail.map( ( entry ) => {

			const where = Array.isArray( entry?.loc ) ? entry.loc.filter( ( part ) => part !== 'body' ).join( '.' ) : '';
			return where ? `${ where }: ${ entry?.msg }` : String( entry?.msg ?? JSON.stringify( entry ) );

		} ).join( '; ' );

	}

	return detail === undefined || detail === null ? '' : JSON.stringify( detail );

}

export class PoseBox {

	/**
	 * @param {import('../core/paramState.js').ParamState} state
	 * @param {{ fetchImpl?: Function, clipboard?: { writeText( text: string ): Promise<void> } | null }} options
	 */
	constructor( state, { fetchImpl = globalThis.fetch, clipboard = globalThis.navigator?.clipboard ?? null } = {} ) {

		this.state = state;
		this.fetchImpl = fetchImpl;
		this.clipboard = clipboard;
		this.pasteError = null;
		this.poseStatus = null;

		this.text = h( 'textarea', {
			className: 'wb-json', id: 'wb-json', rows: '4', spellcheck: 'false',
			'aria-label': 'Parameters as JSON', placeholder: '{"tip_height": 5, "jaw_opening": 10}',
		} );
		this.error = h( 'p', { className: 'error wb-inline', role: 'alert', hidden: '' } );
		this.copyButton = h( 'button', { type: 'button', onClick: () => this.copy() }, 'Copy JSON' );
		this.pasteButton = h( 'button', { type: 'button', onClick: () => this.paste() }, 'Apply JSON' );
		this.resetButton = h( 'button', { type: 'button', onClick: () => this.reset() }, 'Reset' );
		this.name = h( 'input', { type: 'text', className: 'wb-name', 'aria-label': 'Pose name', placeholder: 'Pose name, e.g. alveolar stop' } );
		this.saveButton = h( 'button', { type: 'button', onClick: () => this.save() }, 'Save pose' );
		this.status = h( 'p', { className: 'status wb-inline', role: 'status', 'aria-live': 'polite' } );
		this.saveError = h( 'p', { className: 'error wb-inline', role: 'alert', hidden: '' } );

		this.element = h( 'section', { className: 'wb-pose', 'aria-label': 'Pose' },
			h( 'div', { className: 'wb-buttons' }, this.resetButton, this.copyButton, this.pasteButton ),
			this.text,
			this.error,
			h( 'div', { className: 'wb-buttons' }, this.name, this.saveButton ),
			this.status,
			this.saveError,
		);

	}

	reset() {

		this.state.reset();
		this.showPasteError( null );

	}

	/** Put every parameter into the box as JSON, and on the clipboard when the browser lets us. */
	async copy() {

		const json = this.state.toJSON();
		this.text.value = json;
		this.text.select();
		this.showPasteError( null );
		try {

			await this.clipboard?.writeText( json );

		} catch {
			// No clipboard permission: the JSON is selected in the box, ready for Ctrl+C.
		}

		return json;

	}

	/** Apply the JSON in the box; a bad paste shows why and leaves every parameter as it was. */
	paste() {

		const result = this.state.paste( this.text.value );
		this.showPasteError( result.ok ? null : result.error );
		return result;

	}

	showPasteError( message ) {

		this.pasteError = message;
		this.error.textContent = message ?? '';
		this.error.hidden = ! message;
		this.text.setAttribute( 'aria-invalid', String( Boolean( message ) ) );

	}

	async save() {

		this.saveButton.disabled = true;
		this.showSave( null, null );
		try {

			const pose = await savePose( this.name.value, this.state.toObject(), { fetchImpl: this.fetchImpl } );
			this.showSave( `Saved the pose "${ pose.name }".`, null );

		} catch ( error ) {

			this.showSave( null, error.message );

		} finally {

			this.saveButton.disabled = false;

		}

	}

	showSave( status, error ) {

		this.poseStatus = error ? { ok: false, message: error } : status ? { ok: true, message: status } : null;
		this.status.textContent = status ?? '';
		this.saveError.textContent = error ?? '';
		this.saveError.hidden = ! error;

	}

	setEnabled( enabled ) {

		for ( const control of [ this.copyButton, this.pasteButton, this.resetButton, this.saveButton, this.text, this.name ] ) control.disabled = ! enabled;

	}

}
