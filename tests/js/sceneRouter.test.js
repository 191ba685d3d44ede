// The hash router and its view registry (web/src/ui/shared/router.js), with a minimal stand-in DOM.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { Router, routePath } from '../../web/src/ui/shared/router.js';

/** Just enough of a document and window for the router. */
function fakePage( hash = '' ) {

	const document = {
		title: '',
		createElement: ( tag ) => ( {
			tag, children: [], attributes: {}, textContent: '',
			setAttribute( name, value ) {

				this.attributes[ name ] = value;

			},
			append( ...nodes ) {

				this.children.push( ...nodes );

			},
			remove() {

				container.children = container.children.filter( ( node ) => node !== this );

			},
		} ),
	};
	const container = {
		ownerDocument: document, children: [],
		append( ...nodes ) {

			this.children.push( ...nodes );

		},
		replaceChildren() {

			this.children = [];

		},
	};
	const listeners = {};
	const window = {
		document,
		location: { hash },
		addEventListener: ( type, fn ) => ( listeners[ type ] = fn ),
		removeEventListener: ( type ) => delete listeners[ type ],
		navigate( newHash ) {

			this.location.hash = newHash;
			return listeners.hashchange?.();

		},
	};
	return { window, container, listeners };

}

/** A view that records its mounts and unmounts in `log`. */
function view( name, log ) {

	return ( container ) => {

		log.push( `mount ${ name }` );
		container.append( name );
		return { unmount: () => log.push( `unmount ${ name }` ) };

	};

}

test( 'route paths come from the hash, defaulting to the head view', () => {

	assert.equal( routePath( '' ), '/' );
	assert.equal( routePath( '#' ), '/' );
	assert.equal( routePath( '#/' ), '/' );
	assert.equal( routePath( '#/workbench' ), '/workbench' );
	assert.equal( routePath( '#/workbench/' ), '/workbench' );
	assert.equal( routePath( '#clinician?client=3' ), '/clinician' );
	assert.equal( routePath( undefined ), '/' );

} );

test( 'the router mounts the view of the current hash and swaps views on hash changes', async () => {

	const { window, container } = fakePage( '#/' );
	const log = [];
	const router = new Router( container, window )
		.register( '/', view( 'head', log ), { title: 'Glasshead' } )
		.register( '/workbench', async ( c ) => view( 'workbench', log )( c ) );
	await router.start();
	assert.deepEqual( log, [ 'mount head' ] );
	assert.equal( window.document.title, 'Glasshead' );
	await window.navigate( '#/workbench' );
	assert.deepEqual( log, [ 'mount head', 'unmount head', 'mount workbench' ] );
	assert.deepEqual( container.children, [ 'workbench' ] );
	assert.deepEqual( router.paths, [ '/', '/workbench' ] );
	assert.equal( router.currentPath, '/workbench' );

} );

test( 'an unknown route shows a message with a link home', async () => {

	const { window, container } = fakePage( '#/nowhere' );
	const router = new Router( container, window ).register( '/', view( 'head', [] ) );
	await router.start();
	const [ message ] = container.children;
	assert.equal( message.attributes.role, 'alert' );
	assert.match( message.textContent, /no page at #\/nowhere/ );
	assert.equal( message.children[ 0 ].href, '#/' );

} );

test( 'a slow view that is overtaken by a newer navigation is unmounted again', async () => {

	const { window, container } = fakePage( '#/' );
	const log = [];
	let release;
	const slow = ( c ) => new Promise( ( resolve ) => {

		release = () => resolve( view( 'slow', log )( c ) );

	} );
	const router = new Router( container, window ).register( '/', slow ).register( '/fast', view( 'fast', log ) );
	const first = router.start();
	await window.navigate( '#/fast' );
	release();
	assert.equal( await first, null );
	assert.deepEqual( log, [ 'mount fast', 'mount slow', 'unmount slow' ] );
	assert.equal( router.currentPath, '/fast' );

} );

test( 'routes must look like "/name" and need a mount function', () => {

	const { window, container } = fakePage();
	const router = new Router( container, window );
	assert.throws( () => router.register( 'workbench', () => {} ), /must look like/ );
	assert.throws( () => router.register( '/a/', () => {} ), /must look like/ );
	assert.throws( () => router.register( '/a', null ), /mount function/ );

} );
