// The sign-in view (#/signin?next=…): an adult's username and password for a bearer token
// (POST /auth/sessions), kept by session.js, then back to where the person came from. Failures
// are said in plain words (signIn.js): a wrong password, too many attempts and when to try
// again (the Retry-After of a 429), a server that cannot be reached. Someone already signed in
// sees who, a way on, and Sign out.
//
// window.glasshead.signIn: { ready, busy, message, next } for the end-to-end tests.

import { registerDebug } from '../../debug.js';
import { currentSession, onSessionChange } from '../../session.js';
import { h } from '../shared/dom.js';
import { nextFromHash, signIn, signOut, whoLabel } from '../shared/signIn.js';
import '../shared/signin.css';

export function mountSignInView( container, { win = globalThis.window } = {} ) {

	// Where to go once signed in: read from the address each time, which may change under the view.
	const next = () => nextFromHash( win.location.hash );
	const debug = { ready: false, busy: false, message: null, next: next() };

	const username = h( 'input', { id: 'signin-username', name: 'username', type: 'text', autocomplete: 'username', autocapitalize: 'none', spellcheck: 'false', required: '' } );
	const password = h( 'input', { id: 'signin-password', name: 'password', type: 'password', autocomplete: 'current-password', required: '' } );
	const submit = h( 'button', { type: 'submit', className: 'signin-submit' }, 'Sign in' );
	const message = h( 'p', { className: 'error signin-message', role: 'alert', hidden: '' } );
	const form = h( 'form', { className: 'signin-form', 'aria-labelledby': 'signin-title', novalidate: '' },
		h( 'label', { className: 'field-label', for: 'signin-username' }, 'Username' ),
		username,
		h( 'label', { className: 'field-label', for: 'signin-password' }, 'Password' ),
		password,
		submit,
		message,
	);

	const signedIn = h( 'div', { className: 'signin-signed-in' } );
	const card = h( 'section', { className: 'signin-card', 'aria-labelledby': 'signin-title' },
		h( 'h1', { id: 'signin-title', className: 'signin-title' }, 'Sign in' ),
		h( 'p', { className: 'signin-intro' }, 'Authors, teachers and clinicians sign in to save poses, read recordings and run lessons. The head works without signing in.' ),
		form,
		signedIn,
	);
	const root = h( 'div', { className: 'signin-view' }, card );
	container.append( root );

	function show( text ) {

		debug.message = text;
		message.textContent = text ?? '';
		message.hidden = ! text;

	}

	function render() {

		const session = currentSession( { win } );
		form.hidden = Boolean( session );
		signedIn.replaceChildren();
		if ( ! session ) return;
		const signOutButton = h( 'button', { type: 'button', onClick: () => signOut( { win } ) }, 'Sign out' );
		signedIn.append(
			h( 'p', { role: 'status' }, `You are signed in as ${ whoLabel( session ) }.` ),
			h( 'div', { className: 'signin-actions' }, h( 'a', { className: 'signin-continue', href: next() }, 'Continue' ), signOutButton ),
		);

	}

	form.addEventListener( 'submit', async ( event ) => {

		event.preventDefault();
		if ( debug.busy ) return;
		if ( username.value.trim() === '' || password.value === '' ) {

			show( 'Enter your username and your password.' );
			( username.value.trim() === '' ? username : password ).focus();
			return;

		}

		debug.busy = true;
		submit.disabled = true;
		show( null );
		try {

			await signIn( username.value, password.value, { win } );
			password.value = '';
			debug.next = next();
			win.location.hash = debug.next;

		} catch ( error ) {

			show( error.message );
			password.select();
			password.focus();

		} finally {

			debug.busy = false;
			submit.disabled = false;

		}

	} );

	const unsubscribe = onSessionChange( render );
	const unregister = registerDebug( 'signIn', () => ( { ...debug } ) );
	render();
	if ( ! form.hidden ) username.focus();
	debug.ready = true;

	return {
		unmount() {

			unsubscribe();
			unregister();
			root.remove();

		},
	};

}
