// The navigation between the views: one bar above every view, mounted once by main.js outside the
// router's container (a view that unmounts never takes it along). Its links are ordinary `#/...`
// links, so the router does the rest; the link of the view on screen carries aria-current="page".
//
//   const nav = new NavBar( { win: window } );
//   document.body.prepend( nav.element );   // before the views' container
//   nav.start();                            // follows hashchange
//
// At its end the bar names who is signed in, with a Sign out button (the token revoked on the
// server, then forgotten), or offers a "Sign in" link that comes back to the view on screen.
//
// navItems( path ) and accountItem( session, hash ) are the pure parts (what is listed, which one
// is current, who is named) and are what the unit tests read; the class only turns them into
// elements. Its look is nav.css, which main.js imports.

import { currentSession, onSessionChange } from '../../session.js';
import { routePath } from './router.js';
import { hasRole, signInHref, signOut, whoLabel } from './signIn.js';

/** The views, in the bar's order: route path and the link's words. */
export const NAV_VIEWS = Object.freeze( [
	Object.freeze( { path: '/', label: 'Head' } ),
	Object.freeze( { path: '/workbench', label: 'Workbench' } ),
	Object.freeze( { path: '/clinician', label: 'Clinician' } ),
	Object.freeze( { path: '/speak', label: 'Speak' } ),
	Object.freeze( { path: '/listen', label: 'Listen' } ),
] );

/**
 * Views listed after those only while someone who uses them is signed in: the lesson editor for
 * authors (and admins), the fit page for authors and clinicians (and admins), the privacy page for admins, the lesson runner for teachers (and admins).
 * Children reach their practice (#/practice) at the address their teacher gives them.
 */
export const ROLE_VIEWS = Object.freeze( [
	Object.freeze( { path: '/author', label: 'Write', roles: Object.freeze( [ 'author', 'admin' ] ) } ),
	Object.freeze( { path: '/fits', label: 'Fit', roles: Object.freeze( [ 'author', 'clinician', 'admin' ] ) } ),
	Object.freeze( { path: '/admin', label: 'Admin', roles: Object.freeze( [ 'admin' ] ) } ),
	Object.freeze( { path: '/teach', label: 'Teach', roles: Object.freeze( [ 'teacher', 'admin' ] ) } ),
] );

/**
 * The bar's links for the view at route `path` ('/workbench'): [{ path, label, href, current }],
 * exactly one current when `path` is a view, none for an unknown path.
 */
export function navItems( path, views = NAV_VIEWS ) {

	return views.map( ( view ) => ( { ...view, href: `#${ view.path }`, current: view.path === path } ) );

}

/**
 * The bar's account corner for `session` (session.js's, or null) on the page at `hash`:
 * { signedIn: true, label } names who is signed in; { signedIn: false, href } links to the
 * sign-in view, which comes back to `hash`.
 */
export function accountItem( session, hash ) {

	const label = whoLabel( session );
	if ( label ) return { signedIn: true, label };
	const path = routePath( hash );
	return { signedIn: false, href: path === '/signin' ? ( hash || '#/signin' ) : signInHref( hash || '#/' ) };

}

export class NavBar {

	/** @param {{ win?: Window, views?: Array<{ path: string, label: string }> }} options */
	constructor( { win = globalThis.window, views = NAV_VIEWS, roleViews = ROLE_VIEWS } = {} ) {

		this.window = win;
		this.views = views;
		this.roleViews = roleViews;
		const document = win.document;
		const makeLink = ( view ) => {

			const link = document.createElement( 'a' );
			link.className = 'nav-link';
			link.href = `#${ view.path }`;
			link.textContent = view.label;
			return link;

		};
		this.links = views.map( makeLink );
		this.roleLinks = roleViews.map( makeLink );
		const list = document.createElement( 'ul' );
		list.className = 'nav-list';
		const listItem = ( link ) => {

			const item = document.createElement( 'li' );
			item.append( link );
			return item;

		};
		for ( const link of this.links ) list.append( listItem( link ) );
		// Out of the list until someone of their roles signs in (showAccount).
		this.list = list;
		this.roleItems = this.roleLinks.map( listItem );
		for ( const item of this.roleItems ) item.hidden = true;

		const brand = document.createElement( 'span' );
		brand.className = 'nav-brand';
		brand.textContent = 'Glasshead';

		// Who is signed in and Sign out, or Sign in: both made once, one of them hidden.
		this.signInLink = document.createElement( 'a' );
		this.signInLink.className = 'nav-link nav-signin';
		this.signInLink.textContent = 'Sign in';
		this.who = document.createElement( 'span' );
		this.who.className = 'nav-who';
		this.signOutButton = document.createElement( 'button' );
		this.signOutButton.className = 'nav-signout';
		this.signOutButton.setAttribute( 'type', 'button' );
		this.signOutButton.textContent = 'Sign out';
		this.signOutButton.onclick = () => signOut( { win: this.window } );
		this.account = document.createElement( 'div' );
		this.account.className = 'nav-account';
		this.account.append( this.signInLink, this.who, this.signOutButton );

		this.element = document.createElement( 'nav' );
		this.element.className = 'nav-bar';
		this.element.setAttribute( 'aria-label', 'Views' );
		this.element.append( brand, list, this.account );
		this.onHashChange = () => {

			this.mark( routePath( this.window.location.hash ) );
			this.showAccount();

		};

	}

	/** Mark the link of the view at route `path` as the current page. */
	mark( path ) {

		this.path = path;
		navItems( path, this.views ).forEach( ( item, k ) => {

			if ( item.current ) this.links[ k ].setAttribute( 'aria-current', 'page' );
			else this.links[ k ].removeAttribute( 'aria-current' );

		} );
		this.roleViews.forEach( ( view, k ) => {

			if ( view.path === path ) this.roleLinks[ k ].setAttribute( 'aria-current', 'page' );
			else this.roleLinks[ k ].removeAttribute( 'aria-current' );

		} );

	}

	/** Name who is signed in (from session.js, or `session` when given), or offer Sign in. */
	showAccount( session = currentSession( { win: this.window } ) ) {

		const item = accountItem( session, this.window.location.hash );
		this.accountState = item;
		this.roleViews.forEach( ( view, k ) => {

			const item = this.roleItems[ k ];
			item.hidden = ! hasRole( session, view.roles );
			if ( item.hidden ) item.remove();
			else this.list.append( item ); // in ROLE_VIEWS' order, after the views for everyone

		} );
		this.signInLink.hidden = item.signedIn;
		this.who.hidden = ! item.signedIn;
		this.signOutButton.hidden = ! item.signedIn;
		this.who.textContent = item.signedIn ? item.label : '';
		this.element.classList?.toggle( 'signed-in', item.signedIn );
		if ( item.signedIn ) this.who.setAttribute( 'title', `Signed in as ${ item.label }` );
		else this.signInLink.href = item.href;

	}

	/** Follow the address and the session: mark the current view and who is signed in, now and on every change. */
	start() {

		this.window.addEventListener( 'hashchange', this.onHashChange );
		this.stopSession = onSessionChange( ( session ) => this.showAccount( session ) );
		this.onHashChange();
		return this;

	}

	dispose() {

		this.window.removeEventListener( 'hashchange', this.onHashChange );
		this.stopSession?.();
		this.element.remove();

	}

}
