// "Please sign in", with a link to the sign-in view that comes back here: what a view shows where
// it needs someone signed in and nobody is, or where the server refused the page's token (401).
// One place does it for every view:
//
//   import { signedOutPrompt, signInPrompt } from './SignInPrompt.js';
//   try { … await api.get( 'recordings' ) … } catch ( error ) {
//   	const prompt = signedOutPrompt( error );          // a 401: the session is forgotten
//   	if ( prompt ) box.replaceChildren( prompt ); else showError( error.message );
//   }
//   box.replaceChildren( signInPrompt( { reason: 'to save poses' } ) );  // nobody signed in

import { clearSession } from '../session.js';
import { h } from './Controls.js';
import { isSignedOut, signInHref } from './signIn.js';

/**
 * An element saying "Please sign in <reason>." with a link to `#/signin?next=<here>`; `here` is
 * the page's hash when the link is followed (read at click time, so a view whose address
 * changed comes back where it is now).
 */
export function signInPrompt( { reason = '', win = globalThis.window, className = '' } = {} ) {

	const link = h( 'a', { className: 'signin-link', href: signInHref( win?.location?.hash || '#/' ) }, 'Sign in' );
	link.addEventListener( 'focus', () => link.setAttribute( 'href', signInHref( win?.location?.hash || '#/' ) ) );
	link.addEventListener( 'pointerdown', () => link.setAttribute( 'href', signInHref( win?.location?.hash || '#/' ) ) );
	return h( 'div', { className: `signin-prompt ${ className }`.trim(), role: 'status' },
		h( 'span', {}, `Please sign in${ reason ? ` ${ reason }` : '' }.` ),
		link,
	);

}

/**
 * When `error` is a 401 (the token is missing, expired or revoked): forget the session and return
 * the prompt to show instead of the error; otherwise null, and the caller shows its error.
 */
export function signedOutPrompt( error, options = {} ) {

	if ( ! isSignedOut( error ) ) return null;
	clearSession( { win: options.win ?? globalThis.window } );
	return signInPrompt( options );

}
