// The child's way in to practice, methods of ChildPractice (mixed into its prototype) kept here
// so that the view itself holds the practice: the class code (an adult may type it), the class's
// roster to tap their own picture and name in (POST /auth/class-roster, POST /auth/child-sessions,
// the session kept by session.js), and "Not me" to sign out. Also the big button every screen
// of the view is built with.

import { clearSession, saveSession } from '../../session.js';
import { h } from '../shared/dom.js';
import { normaliseJoinCode } from './ChildPracticeFlow.js';
import { codeMessage, NO_CLASS } from './practiceMessages.js';
import { picture } from '../shared/ChildPracticePictures.js';

/** A big button: a picture, and words under it when given (the name is always there for a screen reader). */
export function bigButton( icon, label, onClick, { words = null, className = 'cp-button' } = {} ) {

	return h( 'button', { type: 'button', className, 'aria-label': label, onClick }, picture( icon ), ...( words ? [ h( 'span', { className: 'cp-words' }, words ) ] : [] ) );

}

export const signInMethods = {

	showCode() {

		this.roster = null;
		const input = h( 'input', {
			id: 'cp-code', className: 'cp-code', type: 'text', autocomplete: 'off', autocapitalize: 'characters', spellcheck: 'false',
			maxlength: '12', 'aria-label': 'Class code', placeholder: 'A B C 3 4 7',
		} );
		const form = h( 'form', { className: 'cp-code-form', 'aria-label': 'Class code', onSubmit: ( event ) => {

			event.preventDefault();
			this.findClass( input.value );

		} }, h( 'label', { className: 'cp-label', for: 'cp-code' }, 'Class code' ), input,
		h( 'button', { type: 'submit', className: 'cp-button cp-go', 'aria-label': 'Go' }, picture( 'next' ) ) );
		this.setScreen( 'code', form );
		input.focus();

	},

	/** POST /auth/class-roster: the class's children to pick from. */
	async findClass( typed ) {

		const code = normaliseJoinCode( typed );
		const wrong = codeMessage( typed );
		if ( wrong ) return this.showError( wrong );
		this.showError( '' );
		try {

			this.roster = await this.api.post( 'auth/class-roster', { join_code: code } );

		} catch ( error ) {

			return this.showError( error.status === 404 || error.status === 401 ? NO_CLASS : error.message );

		}

		this.joinCode = code;
		this.showRoster();

	},

	showRoster() {

		const children = this.roster.children ?? [];
		const grid = h( 'div', { className: 'cp-roster', role: 'group', 'aria-label': 'Who are you?' },
			...children.map( ( child ) => h( 'button', { type: 'button', className: 'cp-person', 'aria-label': child.display_name, onClick: () => this.signIn( child ) },
				picture( child.avatar ), h( 'span', { className: 'cp-words' }, child.display_name ) ) ) );
		this.setScreen( 'roster', h( 'div', { className: 'cp-heading' }, bigButton( 'back', 'Back to the class code', () => this.showCode(), { className: 'cp-button cp-small' } ),
			h( 'h1', { className: 'cp-title' }, this.roster.class_name ) ), grid );

	},

	/** POST /auth/child-sessions for the picked child; the session is kept (session.js). */
	async signIn( child ) {

		try {

			const issued = await this.api.post( 'auth/child-sessions', { join_code: this.joinCode, child_id: child.id } );
			saveSession( { kind: 'child', token: issued.token, expires_at: issued.expires_at, child: issued.child }, { win: this.window } );

		} catch ( error ) {

			return this.showError( error.message );

		}

		this.showLessons();

	},

	async signOut() {

		try {

			await this.api.delete( 'auth/child-sessions/current' );

		} catch {
			// Already expired or revoked: forgetting it here is all there is to do.
		}

		clearSession( { win: this.window } );
		this.audio.reset();
		this.round = null;
		this.lessons = null;
		this.showCode();

	},

};
