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

import { registerDebug } from '../../debug.js';
import { clearSession, currentSession, onSessionChange } from '../../session.js';
import { h } from './dom.js';
import { hasRole, isSignedOut, rolesWords, signInHref } from './signIn.js';

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

/**
 * Mount a view that needs an adult of one of `roles` signed in: `mount( container )` when one is,
 * else a page-sized "Please sign in <reason>" (or, for someone whose role may not, who they are
 * and a link to sign in as someone else). Follows the session: signing out swaps the view for the
 * prompt, signing in the prompt for the view. `debugName` names the window.glasshead field that
 * reports { loaded: false, signIn: 'needed'|'role' } while the prompt shows.
 * Returns { unmount() } as the router wants.
 */
export async function mountForRoles( container, { roles, reason, mount, debugName, win = globalThis.window, title = 'This view' } ) {

	let view = null;
	let prompt = null;
	let unregister = null;
	let showing = null;

	function showPrompt( session ) {

		const role = session?.kind === 'user' ? session.user?.role : null;
		prompt = role
			? h( 'div', { className: 'signin-prompt signin-page', role: 'status' },
				h( 'span', {}, `${ title } is for ${ rolesWords( roles ) }. You are signed in as ${ session.user.display_name || session.user.username } (${ role }).` ),
				h( 'a', { className: 'signin-link', href: signInHref( win.location.hash ) }, 'Sign in as someone else' ) )
			: signInPrompt( { reason, win, className: 'signin-page' } );
		container.append( prompt );
		unregister = debugName ? registerDebug( debugName, () => ( { loaded: false, signIn: role ? 'role' : 'needed' } ) ) : null;

	}

	function hidePrompt() {

		prompt?.remove();
		prompt = null;
		unregister?.();
		unregister = null;

	}

	async function show( session ) {

		// The view, or the prompt for nobody or for this person: made again only when that changes.
		const allowed = hasRole( session, roles );
		const state = allowed ? 'view' : `prompt ${ session?.kind === 'user' ? session.user?.id : '' }`;
		if ( state === showing ) return;
		showing = state;
		hidePrompt();
		if ( allowed ) {

			view = await mount( container );

		} else {

			view?.unmount?.();
			view = null;
			showPrompt( session );

		}

	}

	const stop = onSessionChange( ( session ) => show( session ) );
	await show( currentSession( { win } ) );
	return {
		unmount() {

			stop();
			view?.unmount?.();
			hidePrompt();

		},
	};

}
