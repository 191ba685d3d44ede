// The workbench's pose box: reset, copy the parameters as JSON, paste JSON back (a bad paste is
// explained inline and changes nothing), and save the parameters as a named pose
// (POST /api/v1/poses). What saving says appears right under the Save button and is scrolled
// into view, in plain words (poseMessages.js), so that a click on Save never seems to do nothing.
//
// Saving needs an author, clinician or admin signed in: for anyone else the name and Save give
// way to a sign-in link (SignInPrompt.js), following the session as it changes; a token the
// server no longer takes (401) on saving turns into the same link.

import { api as pageApi, ApiError } from '../../api.js';
import { currentSession, onSessionChange } from '../../session.js';
import { h } from '../shared/dom.js';
import { poseSaveMessage } from './poseMessages.js';
import { hasRole, isForbidden, rolesWords } from '../shared/signIn.js';
import { signedOutPrompt, signInPrompt } from '../shared/SignInPrompt.js';

/** Who may save poses. */
export const POSE_ROLES = Object.freeze( [ 'author', 'clinician', 'admin' ] );

/**
 * Save `params` as the pose `name` (POST /poses). Resolves to the created pose; rejects with an
 * ApiError whose message is a plain sentence to show as it is (a duplicate name, a refused value,
 * an unreachable server; the request and status stay on the error), or an Error when there is no
 * name.
 */
export async function savePose( name, params, { api = pageApi } = {} ) {

	const trimmed = ( name ?? '' ).trim();
	if ( trimmed === '' ) throw new Error( 'Give the pose a name first.' );
	try {

		return await api.post( 'poses', { name: trimmed, params } );

	} catch ( error ) {

		if ( ! ( error instanceof ApiError ) ) throw error;
		const { method, url, status, detail } = error;
		throw new ApiError( poseSaveMessage( error, trimmed ), { method, url, status, detail, cause: error } );

	}

}

export class PoseBox {

	/**
	 * @param {import('../../core/paramState.js').ParamState} state
	 * @param {{ api?: object, clipboard?: { writeText( text: string ): Promise<void> } | null }} options
	 *   `api`: the HTTP client poses are saved through
	 */
	constructor( state, { api = pageApi, clipboard = globalThis.navigator?.clipboard ?? null, win = globalThis.window } = {} ) {

		this.state = state;
		this.window = win;
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
		this.saveRow = h( 'div', { className: 'wb-buttons' }, this.name, this.saveButton );
		this.access = h( 'div', { className: 'wb-save-access', hidden: '' } );

		this.element = h( 'section', { className: 'wb-pose', 'aria-label': 'Pose' },
			h( 'div', { className: 'wb-buttons' }, this.resetButton, this.copyButton, this.pasteButton ),
			this.text,
			this.error,
			this.saveRow,
			this.access,
			this.status,
			this.saveError,
		);
		this.stopSession = onSessionChange( ( session ) => this.showAccess( session ) );
		this.showAccess( currentSession( { win } ) );

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

	/**
	 * Offer the name and Save to `session` when its role may save poses; else say how to: sign in
	 * (nobody signed in), or which roles may (someone else signed in). `saving` says which.
	 */
	showAccess( session ) {

		this.saving = hasRole( session, POSE_ROLES ) ? 'allowed' : session ? 'role' : 'signIn';
		this.saveRow.hidden = this.saving !== 'allowed';
		this.access.hidden = this.saving === 'allowed';
		if ( this.saving === 'signIn' ) this.access.replaceChildren( signInPrompt( { reason: 'to save poses', win: this.window } ) );
		else if ( this.saving === 'role' ) this.access.replaceChildren( h( 'p', { className: 'status wb-inline' }, `Only ${ rolesWords( POSE_ROLES ) } can save poses.` ) );
		else this.access.replaceChildren();

	}

	async save() {

		this.saveButton.disabled = true;
		this.showSave( null, null );
		try {

			const pose = await savePose( this.name.value, this.state.toObject(), { api: this.api } );
			this.showSave( `Saved the pose "${ pose.name }".`, null );

		} catch ( error ) {

			// A token the server no longer takes: the session is forgotten, and the box offers
			// signing in again instead of an error.
			if ( signedOutPrompt( error, { win: this.window } ) ) return;
			this.showSave( null, isForbidden( error ) ? `Only ${ rolesWords( POSE_ROLES ) } can save poses.` : error.message );

		} finally {

			this.saveButton.disabled = false;

		}

	}

	showSave( status, error ) {

		this.poseStatus = error ? { ok: false, message: error } : status ? { ok: true, message: status } : null;
		this.status.textContent = status ?? '';
		this.saveError.textContent = error ?? '';
		this.saveError.hidden = ! error;
		this.name.setAttribute( 'aria-invalid', String( Boolean( error ) && /name/i.test( error ) ) );
		// Where the person is looking: the message sits under the button and is brought on screen.
		const shown = error ? this.saveError : status ? this.status : null;
		shown?.scrollIntoView?.( { block: 'nearest' } );

	}

	dispose() {

		this.stopSession();

	}

	setEnabled( enabled ) {

		for ( const control of [ this.copyButton, this.pasteButton, this.resetButton, this.saveButton, this.text, this.name ] ) control.disabled = ! enabled;

	}

}
