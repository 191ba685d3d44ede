// The navigation between the views: one bar above every view, mounted once by main.js outside the
// router's container (a view that unmounts never takes it along). Its links are ordinary `#/...`
// links, so the router does the rest; the link of the view on screen carries aria-current="page".
//
//   const nav = new NavBar( { win: window } );
//   document.body.prepend( nav.element );   // before the views' container
//   nav.start();                            // follows hashchange
//
// navItems( path ) is the pure part (what is listed, which one is current) and is what the unit
// tests read; the class only turns it into elements. Its look is nav.css, which main.js imports.

import { routePath } from './router.js';

/** The views, in the bar's order: route path and the link's words. */
export const NAV_VIEWS = Object.freeze( [
	Object.freeze( { path: '/', label: 'Head' } ),
	Object.freeze( { path: '/workbench', label: 'Workbench' } ),
	Object.freeze( { path: '/clinician', label: 'Clinician' } ),
	Object.freeze( { path: '/speak', label: 'Speak' } ),
] );

/**
 * The bar's links for the view at route `path` ('/workbench'): [{ path, label, href, current }],
 * exactly one current when `path` is a view, none for an unknown path.
 */
export function navItems( path, views = NAV_VIEWS ) {

	return views.map( ( view ) => ( { ...view, href: `#${ view.path }`, current: view.path === path } ) );

}

export class NavBar {

	/** @param {{ win?: Window, views?: Array<{ path: string, label: string }> }} options */
	constructor( { win = globalThis.window, views = NAV_VIEWS } = {} ) {

		this.window = win;
		this.views = views;
		const document = win.document;
		this.links = views.map( ( view ) => {

			const link = document.createElement( 'a' );
			link.className = 'nav-link';
			link.href = `#${ view.path }`;
			link.textContent = view.label;
			return link;

		} );
		const list = document.createElement( 'ul' );
		list.className = 'nav-list';
		for ( const link of this.links ) {

			const item = document.createElement( 'li' );
			item.append( link );
			list.append( item );

		}

		const brand = document.createElement( 'span' );
		brand.className = 'nav-brand';
		brand.textContent = 'Glasshead';
		this.element = document.createElement( 'nav' );
		this.element.className = 'nav-bar';
		this.element.setAttribute( 'aria-label', 'Views' );
		this.element.append( brand, list );
		this.onHashChange = () => this.mark( routePath( this.window.location.hash ) );

	}

	/** Mark the link of the view at route `path` as the current page. */
	mark( path ) {

		this.path = path;
		navItems( path, this.views ).forEach( ( item, k ) => {

			if ( item.current ) this.links[ k ].setAttribute( 'aria-current', 'page' );
			else this.links[ k ].removeAttribute( 'aria-current' );

		} );

	}

	/** Follow the address: mark the current view now and on every hash change. */
	start() {

		this.window.addEventListener( 'hashchange', this.onHashChange );
		this.onHashChange();
		return this;

	}

	dispose() {

		this.window.removeEventListener( 'hashchange', this.onHashChange );
		this.element.remove();

	}

}
