// The lesson runner's sharing of the chosen class: its owner shares it with a clinician or another
// teacher by username (POST /classes/{id}/staff), sees whom it is shared with (GET
// /classes/{id}/staff) and stops sharing with one (DELETE /classes/{id}/staff/{user_id}). Whoever
// it is shared with reaches the class and its children as the owner does (a clinician follows the
// same child's practice and recordings); they see who shared it, without the form, since only the
// owner (or an admin) changes who it is shared with.

import { h } from '../shared/dom.js';
import { currentSession } from '../../session.js';

/** Longest username (docs/auth.md). */
const MAX_USERNAME = 254;

/** How a member is named in the list: "Cleo (clinician)". */
export function memberLabel( member ) {

	return `${ member.display_name || member.username } (${ member.role })`;

}

/** Whether `user` ({ id, role }) changes who the class of `staff` ({ owner }) is shared with. */
export function changesStaff( user, staff ) {

	return Boolean( user ) && ( user.role === 'admin' || staff?.owner?.user_id === user.id );

}

export class LessonRunnerStaff {

	/** @param {{ api: object, user?: () => object|null }} options the API client and who is signed in */
	constructor( { api, user = () => currentSession()?.user ?? null } ) {

		this.api = api;
		this.user = user;
		this.classId = null;
		this.staff = null;
		this.loads = 0;
		this.username = h( 'input', { id: 'lr-share', className: 'lr-input', type: 'text', maxlength: String( MAX_USERNAME ), autocomplete: 'off', autocapitalize: 'none', spellcheck: 'false' } );
		this.list = h( 'ul', { className: 'lr-staff', 'aria-label': 'Shared with' } );
		this.status = h( 'p', { className: 'lr-note', role: 'status', 'aria-live': 'polite' } );
		this.form = h( 'form', { className: 'lr-form', 'aria-label': 'Share this class', onSubmit: ( event ) => this.submit( event ) },
			h( 'label', { className: 'field-label', for: 'lr-share' }, 'Share this class with a clinician or teacher' ), this.username,
			h( 'button', { type: 'submit' }, 'Share' ) );
		this.element = h( 'details', { className: 'lr-roster lr-sharing' },
			h( 'summary', {}, 'Sharing' ), this.form, this.list, this.status );
		this.show( null );

	}

	/** Show whom class `classId` is shared with (nothing for null). */
	async load( classId ) {

		this.classId = classId;
		const load = ++ this.loads;
		this.status.textContent = '';
		if ( classId === null ) return this.show( null );
		try {

			const staff = await this.api.get( `classes/${ classId }/staff` );
			if ( load === this.loads ) this.show( staff );

		} catch ( error ) {

			if ( load !== this.loads ) return;
			this.show( null );
			this.status.textContent = `Who this class is shared with could not be loaded: ${ error.message }`;

		}

	}

	show( staff ) {

		this.staff = staff;
		const mine = staff !== null && changesStaff( this.user(), staff );
		this.element.hidden = this.classId === null;
		this.form.hidden = ! mine;
		const members = staff?.staff ?? [];
		const items = members.map( ( member ) => h( 'li', { className: 'lr-staff-member' },
			h( 'span', {}, memberLabel( member ) ),
			...( mine ? [ h( 'button', { type: 'button', 'aria-label': `Stop sharing with ${ member.display_name || member.username }`, onClick: () => this.remove( member ) }, 'Remove' ) ] : [] ),
		) );
		if ( staff && ! mine && staff.owner ) items.unshift( h( 'li', { className: 'lr-note' }, `Shared with you by ${ memberLabel( staff.owner ) }.` ) );
		if ( staff && members.length === 0 ) items.push( h( 'li', { className: 'lr-note' }, 'Not shared with anyone.' ) );
		this.list.replaceChildren( ...items );

	}

	async submit( event ) {

		event.preventDefault();
		const username = this.username.value.trim();
		if ( this.classId === null ) return;
		if ( ! username ) return void ( this.status.textContent = 'Type the username of a clinician or teacher.' );
		await this.act( async () => {

			const added = await this.api.post( `classes/${ this.classId }/staff`, { username } );
			this.username.value = '';
			return `Shared with ${ memberLabel( added ) }.`;

		} );

	}

	async remove( member ) {

		await this.act( async () => {

			await this.api.delete( `classes/${ this.classId }/staff/${ member.user_id }` );
			return `No longer shared with ${ memberLabel( member ) }.`;

		} );

	}

	/** Run `action` with the buttons off, then reload the list and say what happened. */
	async act( action ) {

		const buttons = this.element.querySelectorAll( 'button' );
		for ( const button of buttons ) button.disabled = true;
		let said;
		try {

			said = await action();

		} catch ( error ) {

			// The server's own words for a username it refuses (422) or one already shared with (409).
			const detail = typeof error.detail === 'string' ? error.detail.replace( /^body\.username: /, '' ) : null;
			said = detail && error.status === 422 ? `Not shared: ${ detail }.` : error.status === 409 ? 'This class is already shared with them.' : error.message;

		} finally {

			for ( const button of buttons ) button.disabled = false;

		}

		await this.load( this.classId );
		this.status.textContent = said;

	}

	/** What window.glasshead.runner.panel reports of the sharing. */
	report() {

		return { owner: this.staff?.owner?.username ?? null, staff: ( this.staff?.staff ?? [] ).map( ( member ) => member.username ), canShare: ! this.form.hidden };

	}

}
