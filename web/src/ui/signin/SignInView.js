// The sign-in view (#/signin?next=…): an adult's username and password for a bearer token
// (POST /auth/sessions), kept by session.js, then back to where the person came from. Failures
// are said in plain words (signIn.js): a wrong password, too many attempts and when to try
// again (the Retry-After of a 429), a server that cannot be reached. Someone already signed in
// sees who, a way on, and Sign out.
//
// window.glasshead.signIn: { ready, busy, message, next } for the end-to-end tests.

import { currentSession, onSessionChange } from '../../session.js';
import { h } from '../shared/dom.js';
import { landingFor, nextFromHash, signIn, signOut, whoLabel } from '../shared/signIn.js';
import { View } from '../shared/View.js';
import '../shared/signin.css';

export class SignInView extends View {

	/** @param {{ win?: Window }} options */
	constructor( options ) {

		super( options );
		this.debug = { ready: false, busy: false, message: null, next: this.next() };

	}

	/** Where to go once signed in: read from the address each time, which may change under the view. */
	next() {

		return nextFromHash( this.window.location.hash );

	}

	mount( container ) {

		this.username = h( 'input', { id: 'signin-username', name: 'username', type: 'text', autocomplete: 'username', autocapitalize: 'none', spellcheck: 'false', required: '' } );
		this.password = h( 'input', { id: 'signin-password', name: 'password', type: 'password', autocomplete: 'current-password', required: '' } );
		this.submit = h( 'button', { type: 'submit', className: 'signin-submit' }, 'Sign in' );
		this.message = h( 'p', { className: 'error signin-message', role: 'alert', hidden: '' } );
		this.form = h( 'form', { className: 'signin-form', 'aria-labelledby': 'signin-title', novalidate: '' },
			h( 'label', { className: 'field-label', for: 'signin-username' }, 'Username' ),
			this.username,
			h( 'label', { className: 'field-label', for: 'signin-password' }, 'Password' ),
			this.password,
			this.submit,
			this.message,
		);

		this.signedIn = h( 'div', { className: 'signin-signed-in' } );
		const card = h( 'section', { className: 'signin-card', 'aria-labelledby': 'signin-title' },
			h( 'h1', { id: 'signin-title', className: 'signin-title' }, 'Sign in' ),
			h( 'p', { className: 'signin-intro' }, 'Authors, teachers and clinicians sign in to save poses, read recordings and run lessons. The head works without signing in.' ),
			this.form,
			this.signedIn,
		);
		this.attach( container, h( 'div', { className: 'signin-view' }, card ) );
		this.form.addEventListener( 'submit', ( event ) => this.submitted( event ) );
		this.onUnmount( onSessionChange( () => this.render() ) );
		this.debugFields( { signIn: () => ( { ...this.debug } ) } );
		this.render();
		if ( ! this.form.hidden ) this.username.focus();
		this.debug.ready = true;
		return this;

	}

	show( text ) {

		this.debug.message = text;
		this.message.textContent = text ?? '';
		this.message.hidden = ! text;

	}

	render() {

		const win = this.window;
		const session = currentSession( { win } );
		this.form.hidden = Boolean( session );
		this.signedIn.replaceChildren();
		if ( ! session ) return;
		const signOutButton = h( 'button', { type: 'button', onClick: () => signOut( { win } ) }, 'Sign out' );
		this.signedIn.append(
			h( 'p', { role: 'status' }, `You are signed in as ${ whoLabel( session ) }.` ),
			h( 'div', { className: 'signin-actions' }, h( 'a', { className: 'signin-continue', href: landingFor( this.next(), session.user?.role ) }, 'Continue' ), signOutButton ),
		);

	}

	async submitted( event ) {

		event.preventDefault();
		const { debug, username, password, submit } = this;
		if ( debug.busy ) return;
		if ( username.value.trim() === '' || password.value === '' ) {

			this.show( 'Enter your username and your password.' );
			( username.value.trim() === '' ? username : password ).focus();
			return;

		}

		debug.busy = true;
		submit.disabled = true;
		this.show( null );
		try {

			const session = await signIn( username.value, password.value, { win: this.window } );
			password.value = '';
			debug.next = landingFor( this.next(), session.user?.role );
			this.window.location.hash = debug.next;

		} catch ( error ) {

			this.show( error.message );
			password.select();
			password.focus();

		} finally {

			debug.busy = false;
			submit.disabled = false;

		}

	}

}

/** Route entry for the view registry. */
export function mountSignInView( container, { win } = {} ) {

	return new SignInView( { win } ).mount( container );

}
