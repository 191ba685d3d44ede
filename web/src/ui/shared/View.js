// The base of every view the router mounts (main.js): mounting into the router's container,
// the clean-ups that unmount() runs (window.glasshead fields, window and document listeners,
// resize observers, frame hooks, and what parts attached to the view push: HeadEpg.js,
// ItemPresenter), and for the views with a head the 3D stage (the viewer and the head), its
// debug fields and its disposal.
//
//   class AdminView extends View {
//   	mount( container ) {
//   		this.attach( container, h( 'div', { className: 'admin-view' } ) );
//   		this.debugFields( { admin: () => ( { ...this.state } ) } );
//   		this.listen( this.window, 'hashchange', () => this.route() );
//   		return this;
//   	}
//   	dispose() { … }   // what the view holds besides its clean-ups, before the stage goes
//   }
//   export const mountAdminView = ( container ) => new AdminView().mount( container );

import { api as pageApi } from '../../api.js';
import { registerDebug } from '../../debug.js';
import { createHeadStage } from './headStage.js';
import { signedOutPrompt } from './SignInPrompt.js';

export class View {

	/**
	 * @param {{ api?: object, win?: Window }} options the HTTP client the view loads through and
	 *   the window whose location, keys and storage it uses (both injected by tests)
	 */
	constructor( { api = pageApi, win = globalThis.window } = {} ) {

		this.api = api;
		this.window = win;
		/** Functions unmount() runs, in the order they were added; parts of the view push theirs. */
		this.unregister = [];
		/** The view's element in the router's container (attach()). */
		this.root = null;

	}

	/**
	 * Show a failed request's `error`: for a 401 the "Please sign in" prompt in `box` (the
	 * session is forgotten), else its message through `say( words )`.
	 */
	showFailure( error, box, say ) {

		const prompt = signedOutPrompt( error, { win: this.window } );
		if ( prompt ) box.replaceChildren( prompt );
		else say( error.message );

	}

	/** Make `root` the view's element, in `container`. Returns the view. */
	attach( container, root ) {

		this.root = root;
		container.append( root );
		return this;

	}

	/** Have unmount() run each of `cleanups`, after those added before. */
	onUnmount( ...cleanups ) {

		this.unregister.push( ...cleanups );

	}

	/** The window.glasshead fields { name: getter } while the view is mounted. */
	debugFields( fields ) {

		for ( const [ name, getter ] of Object.entries( fields ) ) this.unregister.push( registerDebug( name, getter ) );

	}

	/** `handler` for `type` events of `target` (the window, the document) while the view is mounted. */
	listen( target, type, handler ) {

		target.addEventListener( type, handler );
		this.unregister.push( () => target.removeEventListener( type, handler ) );

	}

	/** `onResize()` whenever one of `elements` changes size, while the view is mounted. */
	observeResize( elements, onResize ) {

		const observer = new ResizeObserver( () => onResize() );
		for ( const element of elements ) observer.observe( element );
		this.unregister.push( () => observer.disconnect() );

	}

	/**
	 * The 3D stage in `element`: this.viewer, with this.head in its scene. Without WebGL2 (or when
	 * the graphics driver resets) the view's fail( message ) says so; returns whether there is a stage.
	 */
	mountStage( element ) {

		const stage = createHeadStage( element, ( message ) => this.fail( message ) );
		if ( ! stage ) return false;
		( { viewer: this.viewer, head: this.head } = stage );
		return true;

	}

	/** The window.glasshead fields of the stage's viewer (see debugFields()). */
	stageDebugFields() {

		return {
			frames: () => ( this.viewer ? this.viewer.frameCount : 0 ),
			frameTimeMs: () => ( this.viewer ? this.viewer.frameTimeMs : null ),
			cameraMoving: () => ( this.viewer ? this.viewer.animating : false ),
			renderPending: () => ( this.viewer ? this.viewer.renderPending : false ),
		};

	}

	/** What the view holds besides its clean-ups; unmount() releases it before the stage. */
	dispose() {}

	/**
	 * Run the clean-ups, release what the view holds (dispose()), then the stage, and take the
	 * view's element out of the page. `this.viewer` is null afterwards: a load still under way
	 * sees that the view is gone.
	 */
	unmount() {

		const cleanups = this.unregister;
		this.unregister = [];
		for ( const cleanup of cleanups ) cleanup();
		this.dispose();
		this.viewer?.dispose();
		this.head?.dispose();
		this.viewer = null;
		this.root?.remove();

	}

}
