// A small hash router with a registry of views. A view is registered under a path ('/',
// '/workbench', ...) with a function that mounts it into a container and returns an object with
// `unmount()`; the function may be async (a lazily imported module).

/** The route path of a location hash: '#/workbench?x=1' -> '/workbench', '' or '#' -> '/'. */
export function routePath( hash ) {

	let path = ( hash ?? '' ).replace( /^#/, '' );
	path = path.split( '?' )[ 0 ];
	if ( ! path.startsWith( '/' ) ) path = '/' + path;
	if ( path.length > 1 ) path = path.replace( /\/+$/, '' );
	return path;

}

export class Router {

	/** container: the element views mount into; win: the window (injected for tests). */
	constructor( container, win = globalThis.window ) {

		this.container = container;
		this.window = win;
		this.views = new Map();
		this.current = null;
		this.currentPath = null;
		this.navigation = 0;
		this.onHashChange = () => this.show( routePath( this.window.location.hash ) );

	}

	/** Register view `path` -> mount( container ) => view | Promise<view>. Returns the router. */
	register( path, mount, { title = null } = {} ) {

		if ( routePath( path ) !== path ) throw new Error( `route "${ path }" must look like "/name"` );
		if ( typeof mount !== 'function' ) throw new TypeError( `route "${ path }" needs a mount function` );
		this.views.set( path, { mount, title } );
		return this;

	}

	/** Paths of the registered views. */
	get paths() {

		return [ ...this.views.keys() ];

	}

	start() {

		this.window.addEventListener( 'hashchange', this.onHashChange );
		return this.onHashChange();

	}

	stop() {

		this.window.removeEventListener( 'hashchange', this.onHashChange );
		this.current?.unmount?.();
		this.current = null;

	}

	/** Unmount the current view and mount the one at `path` (a not-found page if unknown). */
	async show( path ) {

		if ( path === this.currentPath ) return this.current;
		const navigation = ++ this.navigation;
		this.current?.unmount?.();
		this.current = null;
		this.currentPath = path;
		this.container.replaceChildren();

		const entry = this.views.get( path );
		if ( ! entry ) {

			this.current = this.notFound( path );
			return this.current;

		}

		const view = await entry.mount( this.container );
		if ( navigation !== this.navigation ) {

			view?.unmount?.(); // a newer navigation started while this view was loading
			return null;

		}

		this.current = view;
		if ( entry.title && this.window.document ) this.window.document.title = entry.title;
		return view;

	}

	notFound( path ) {

		const document = this.container.ownerDocument;
		const message = document.createElement( 'div' );
		message.className = 'not-found';
		message.setAttribute( 'role', 'alert' );
		message.textContent = `There is no page at #${ path }. `;
		const link = document.createElement( 'a' );
		link.href = '#/';
		link.textContent = 'Go to the head view';
		message.append( link );
		this.container.append( message );
		return { unmount: () => message.remove() };

	}

}
