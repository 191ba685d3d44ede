// The workbench's pose box: reset, copy the parameters as JSON, paste JSON back (a bad paste is
// explained inline and changes nothing), and save the parameters as a named pose
// (POST /api/v1/poses).

import { api as pageApi, ApiError } from '../api.js';
import { h } from './Controls.js';

/**
 * Save `params` as the pose `name` (POST /poses). Resolves to the created pose; rejects with an
 * ApiError whose message can be shown as it is (a duplicate name, a refused value, an unreachable
 * server), or an Error when there is no name.
 */
export async function savePose( name, params, { api = pageApi } = {} ) {

	const trimmed = ( name ?? '' ).trim();
	if ( trimmed === '' ) throw new Error( 'Give the pose a name first.' );
	try {

		return await api.post( 'poses', { name: trimmed, params } );

	} catch ( error ) {

		if ( error instanceof ApiError && error.status === 409 ) {

			const { method, url, status, detail } = error;
			throw new ApiError( `A pose named "${ trimmed }" already exists. Choose another name.`, { method, url, status, detail, cause: error } );

		}

		throw error;

	}

}

export class PoseBox {

	/**
	 * @param {import('../core/paramState.js').ParamState} state
	 * @param {{ api?: object, clipboard?: { writeText( text: string ): Promise<void> } | null }} options
	 *   `api`: the HTTP client poses are saved through
	 */
	constructor( state, { api = pageApi, clipboard = globalThis.navigator?.clipboard ?? null } = {} ) {

		this.state = state;
		this.api = api;
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

			const pose = await savePose( this.name.value, this.state.toObject(), { api: this.api } );
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
