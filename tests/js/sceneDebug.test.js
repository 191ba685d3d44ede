// The read-only `window.glasshead` debug object (web/src/debug.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { createDebugObject, debugObject, installDebug, registerDebug, snapshot } from '../../web/src/debug.js';

test( 'a debug field reads the live value on every access', () => {

	let value = 1;
	const object = createDebugObject( new Map( [ [ 'value', () => value ] ] ) );
	assert.equal( object.value, 1 );
	value = 2;
	assert.equal( object.value, 2 );

} );

test( 'writing, adding or deleting a field throws in strict code and changes nothing', () => {

	'use strict';
	const object = createDebugObject( new Map( [ [ 'transparency', () => 40 ] ] ) );
	assert.ok( Object.isFrozen( object ) );
	assert.throws( () => {

		object.transparency = 0;

	}, TypeError );
	assert.throws( () => {

		object.extra = 1;

	}, TypeError );
	assert.throws( () => delete object.transparency, TypeError );
	assert.equal( object.transparency, 40 );
	assert.deepEqual( Object.keys( object ), [ 'transparency' ] );

} );

test( 'values are frozen copies that cannot reach the application state', () => {

	const meshes = [ { name: 'maxilla', triangles: 10 } ];
	const object = createDebugObject( new Map( [ [ 'meshes', () => meshes ], [ 'params', () => new Float32Array( [ 1.5, 2 ] ) ] ] ) );
	const read = object.meshes;
	assert.ok( Object.isFrozen( read ) && Object.isFrozen( read[ 0 ] ) );
	assert.throws( () => {

		'use strict';
		read[ 0 ].triangles = 0;

	}, TypeError );
	assert.equal( meshes[ 0 ].triangles, 10 );
	assert.notEqual( read, meshes );
	assert.deepEqual( object.params, [ 1.5, 2 ] );
	assert.ok( Array.isArray( object.params ) );

} );

test( 'a getter that throws reads as null without hiding the other fields', () => {

	const object = createDebugObject( new Map( [ [ 'broken', () => {

		throw new Error( 'boom' );

	} ], [ 'fine', () => 'ok' ] ] ) );
	assert.equal( object.broken, null );
	assert.equal( object.fine, 'ok' );
	assert.deepEqual( JSON.parse( JSON.stringify( object ) ), { broken: null, fine: 'ok' } );

} );

test( 'snapshot refuses functions, since the debug object holds data', () => {

	assert.throws( () => snapshot( () => 1 ), TypeError );
	assert.throws( () => snapshot( { nested: [ () => 1 ] } ), TypeError );
	assert.equal( snapshot( null ), null );
	assert.equal( snapshot( 'text' ), 'text' );

} );

test( 'registerDebug adds a field to the installed object and its remover takes it away', () => {

	const page = {};
	installDebug( page );
	const remove = registerDebug( 'sceneDebugProbe', () => 7 );
	assert.equal( page.glasshead.sceneDebugProbe, 7 );
	assert.equal( page.glasshead, debugObject() );
	remove();
	assert.equal( 'sceneDebugProbe' in page.glasshead, false );

} );

test( 'the installed property cannot be replaced or deleted', () => {

	'use strict';
	const page = {};
	installDebug( page );
	const before = page.glasshead;
	assert.throws( () => {

		page.glasshead = {};

	}, TypeError );
	assert.throws( () => delete page.glasshead, TypeError );
	assert.equal( page.glasshead, before );

} );

test( 'registerDebug rejects names that are not identifiers and getters that are not functions', () => {

	assert.throws( () => registerDebug( 'two words', () => 1 ), /identifier/ );
	assert.throws( () => registerDebug( '', () => 1 ), /identifier/ );
	assert.throws( () => registerDebug( 'value', 3 ), /getter/ );

} );
