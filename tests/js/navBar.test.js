// The navigation between the views and the head view's first-run hint, without a browser: which
// links the bar lists and which one is current, the bar following the address through a small
// stand-in window, and the hint's dismissal kept in storage.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { NAV_VIEWS, NavBar, navItems } from '../../web/src/ui/shared/NavBar.js';
import { dismissHint, hintDismissed, HINT_KEY } from '../../web/src/ui/head/FirstRunHint.js';
import { knownParams } from '../../web/src/ui/head/HeadTargets.js';

/** Just enough of a document for NavBar: elements with attributes and children. */
function fakeWindow( hash ) {

	const listeners = new Map();
	const createElement = ( tag ) => ( {
		tag, children: [], attributes: new Map(), className: '', textContent: '', href: '',
		append( ...nodes ) {

			this.children.push( ...nodes );

		},
		setAttribute( name, value ) {

			this.attributes.set( name, String( value ) );

		},
		getAttribute( name ) {

			return this.attributes.get( name ) ?? null;

		},
		removeAttribute( name ) {

			this.attributes.delete( name );

		},
		remove() {},
	} );
	return {
		location: { hash },
		document: { createElement },
		addEventListener: ( type, fn ) => listeners.set( type, fn ),
		removeEventListener: ( type ) => listeners.delete( type ),
		fire: ( type ) => listeners.get( type )?.(),
		listeners,
	};

}

/** A Storage stand-in; `refuse` makes every call throw, as a locked-down browser's does. */
function fakeStorage( { refuse = false } = {} ) {

	const items = new Map();
	const check = () => {

		if ( refuse ) throw new Error( 'SecurityError: storage is disabled' );

	};

	return {
		getItem: ( key ) => ( check(), items.has( key ) ? items.get( key ) : null ),
		setItem: ( key, value ) => ( check(), items.set( key, String( value ) ) ),
		items,
	};

}

test( 'the bar lists every view in order, each as a #/ link, and marks only the view on screen', () => {

	assert.deepEqual( NAV_VIEWS.map( ( view ) => view.path ), [ '/', '/workbench', '/clinician', '/speak', '/listen' ] );
	const items = navItems( '/clinician' );
	assert.deepEqual( items.map( ( item ) => item.href ), [ '#/', '#/workbench', '#/clinician', '#/speak', '#/listen' ] );
	assert.deepEqual( items.map( ( item ) => item.label ), [ 'Head', 'Workbench', 'Clinician', 'Speak', 'Listen' ] );
	assert.deepEqual( items.filter( ( item ) => item.current ).map( ( item ) => item.path ), [ '/clinician' ] );

} );

test( 'an address that is no view marks no link as current', () => {

	assert.equal( navItems( '/nowhere' ).filter( ( item ) => item.current ).length, 0 );

} );

test( 'the bar follows the address: aria-current moves to the view the hash names', () => {

	const win = fakeWindow( '#/workbench?x=1' );
	const nav = new NavBar( { win } ).start();
	const current = () => nav.links.filter( ( link ) => link.getAttribute( 'aria-current' ) === 'page' ).map( ( link ) => link.textContent );
	assert.equal( nav.element.getAttribute( 'aria-label' ), 'Views' );
	assert.deepEqual( nav.links.map( ( link ) => link.href ), [ '#/', '#/workbench', '#/clinician', '#/speak', '#/listen' ] );
	assert.deepEqual( current(), [ 'Workbench' ] );
	win.location.hash = '';
	win.fire( 'hashchange' );
	assert.deepEqual( current(), [ 'Head' ] );
	win.location.hash = '#/speak';
	win.fire( 'hashchange' );
	assert.deepEqual( current(), [ 'Speak' ] );
	nav.dispose();
	assert.equal( win.listeners.size, 0, 'disposing stops following the address' );

} );

test( 'the hint shows until it is dismissed, and the dismissal is kept in storage', () => {

	const storage = fakeStorage();
	assert.equal( hintDismissed( storage ), false );
	assert.equal( dismissHint( storage ), true );
	assert.equal( storage.items.get( HINT_KEY ), '1' );
	assert.equal( hintDismissed( storage ), true );

} );

test( 'a browser that refuses storage still shows the hint, and dismissing it there throws nothing', () => {

	const storage = fakeStorage( { refuse: true } );
	assert.equal( hintDismissed( storage ), false );
	assert.equal( dismissHint( storage ), false );
	assert.equal( hintDismissed( null ), false );
	assert.equal( dismissHint( null ), false );

} );

test( 'the head view poses only the parameters its rigs know, and only with finite values', () => {

	const params = { tip_height: 6, jaw_opening: 3, lip_opening: 9, unknown_rig: 1, tip_front: Number.NaN };
	assert.deepEqual( knownParams( params, [ 'tip_height', 'jaw_opening', 'tip_front' ] ), { tip_height: 6, jaw_opening: 3 } );
	assert.deepEqual( knownParams( null, [ 'tip_height' ] ), {} );

} );

test( 'the editor, fit, privacy and lesson runner links show only while an author, a clinician, an admin or a teacher is signed in, and are marked when on screen', () => {

	const win = fakeWindow( '#/author' );
	const nav = new NavBar( { win } );
	assert.deepEqual( nav.roleLinks.map( ( link ) => link.href ), [ '#/author', '#/fits', '#/admin', '#/teach' ] );
	const shown = () => nav.roleItems.map( ( item ) => ! item.hidden );
	assert.deepEqual( shown(), [ false, false, false, false ], 'nobody signed in' );
	const as = ( role ) => ( { kind: 'user', token: 't', user: { id: 1, username: role, display_name: role, role } } );
	nav.showAccount( as( 'author' ) );
	assert.deepEqual( shown(), [ true, true, false, false ] );
	nav.showAccount( as( 'clinician' ) );
	assert.deepEqual( shown(), [ false, true, false, false ] );
	nav.showAccount( as( 'admin' ) );
	assert.deepEqual( shown(), [ true, true, true, true ] );
	nav.showAccount( as( 'teacher' ) );
	assert.deepEqual( shown(), [ false, false, false, true ] );
	nav.showAccount( { kind: 'child', token: 't', child: { id: 3 } } );
	assert.deepEqual( shown(), [ false, false, false, false ] );
	nav.mark( '/author' );
	assert.deepEqual( nav.roleLinks.map( ( link ) => link.getAttribute( 'aria-current' ) ), [ 'page', null, null, null ] );
	assert.deepEqual( nav.links.map( ( link ) => link.getAttribute( 'aria-current' ) ), [ null, null, null, null, null ] );

} );
