// A child's recording switch in the clinician view: whether the sound of the child's attempts is
// kept (GET and PUT /children/{id}/audio-recording), who set it and when, and its history. Off by
// default, and then the sound never leaves the child's device. Clinicians and admins change it;
// anyone else sees it read-only, and a refusal by the server (a class that is not theirs) makes it
// read-only too, with the server's words.

import { api as pageApi } from '../../api.js';
import { currentSession } from '../../session.js';
import { h } from '../shared/dom.js';
import { RECORDING_SWITCH_ROLES, recordingHistoryLines, recordingSwitchWords } from './clinicianChildRows.js';

export const SWITCH_LABEL = 'Keep recordings of this child’s attempts';
const READ_ONLY_NOTE = 'Only a clinician of the child’s class can change this.';

export class RecordingSwitch {

	/**
	 * @param {{ api?: object, role?: string|null }} options the HTTP client, and the role of who is
	 *   signed in (by default the session's)
	 */
	constructor( { api = pageApi, role = currentSession()?.user?.role ?? null } = {} ) {

		this.api = api;
		this.state = { child: null, enabled: false, set_by_name: null, set_at: null, history: 0, canChange: RECORDING_SWITCH_ROLES.includes( role ), busy: false, error: null };
		this.input = h( 'input', {
			type: 'checkbox', role: 'switch', id: 'cc-keep-recordings', className: 'cc-switch-input', 'aria-describedby': 'cc-keep-state',
			onChange: () => this.set( this.input.checked ),
		} );
		this.words = h( 'p', { id: 'cc-keep-state', className: 'cc-switch-state', role: 'status', 'aria-live': 'polite' } );
		this.note = h( 'p', { className: 'cc-switch-note' }, READ_ONLY_NOTE );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
		this.historyList = h( 'ol', { className: 'cc-switch-history' } );
		this.history = h( 'details', { className: 'cc-switch-details', hidden: '' }, h( 'summary', {}, 'Who changed it, and when' ), this.historyList );
		this.element = h( 'section', { className: 'cc-switch', 'aria-label': 'Recordings of the child’s attempts', hidden: '' },
			h( 'label', { className: 'cc-switch-label', for: 'cc-keep-recordings' }, this.input, h( 'span', {}, SWITCH_LABEL ) ),
			this.words,
			h( 'p', { className: 'cc-switch-explain' }, 'When on, the sound of each attempt is kept with the child’s data (in its export, deleted with it). When off, it never leaves the child’s device.' ),
			this.note, this.error, this.history );
		this.showAccess();

	}

	/** What window.glasshead.clinicianChild.recording reports. */
	report() {

		return { ...this.state, checked: this.input.checked, disabled: this.input.disabled, words: this.words.textContent };

	}

	/** Show child `id`'s switch (null: hide it). */
	async load( id ) {

		this.state = { ...this.state, child: id, enabled: false, set_by_name: null, set_at: null, history: 0, error: null };
		this.element.hidden = id === null;
		this.showError( null );
		if ( id === null ) return;
		this.words.textContent = 'Reading the recording switch…';
		this.input.disabled = true;
		try {

			const answer = await this.api.get( `children/${ id }/audio-recording` );
			if ( this.state.child === id ) this.show( answer );

		} catch ( error ) {

			if ( this.state.child !== id ) return;
			this.words.textContent = 'Not known';
			this.showError( error.message );

		}

	}

	/** Switch keeping on or off (the checkbox was changed); the server's answer is what is shown. */
	async set( enabled ) {

		const id = this.state.child;
		if ( id === null || ! this.state.canChange ) return;
		this.state.busy = true;
		this.input.disabled = true;
		this.showError( null );
		try {

			const answer = await this.api.put( `children/${ id }/audio-recording`, { enabled } );
			if ( this.state.child === id ) this.show( answer );

		} catch ( error ) {

			if ( this.state.child !== id ) return;
			if ( error.status === 403 ) this.state.canChange = false;
			this.input.checked = this.state.enabled; // as it was: nothing changed
			this.showError( error.message );

		} finally {

			this.state.busy = false;
			this.showAccess();

		}

	}

	show( answer ) {

		const enabled = answer?.enabled === true;
		Object.assign( this.state, { enabled, set_by_name: answer?.set_by_name ?? null, set_at: answer?.set_at ?? null, history: answer?.history?.length ?? 0 } );
		this.input.checked = enabled;
		this.words.textContent = recordingSwitchWords( answer );
		const lines = recordingHistoryLines( answer?.history );
		this.historyList.replaceChildren( ...lines.map( ( line ) => h( 'li', {}, line ) ) );
		this.history.hidden = lines.length === 0;
		this.showAccess();

	}

	showAccess() {

		this.input.disabled = ! this.state.canChange || this.state.busy || this.state.child === null;
		this.note.hidden = this.state.canChange;

	}

	showError( message ) {

		this.state.error = message;
		this.error.textContent = message ?? '';
		this.error.hidden = ! message;

	}

}
