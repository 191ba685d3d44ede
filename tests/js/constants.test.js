// web/src/core/constants.js exports exactly the constants of server/glasshead/constants.py, with
// the same values (tests/vectors/constants.json holds the Python side; pytest checks it is fresh).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import * as constants from '../../web/src/core/constants.js';

import { nearRelative, readVectors, tolerance } from './support/vectors.js';

const DOCUMENT = readVectors( 'constants.json' );
const PYTHON = DOCUMENT.constants;
/** Relative tolerance of constants written in two languages (the file states the reason). */
const RELATIVE = tolerance( DOCUMENT, 'value' );

/** A JS value as plain JSON, the way Python writes it (frozen objects and typed arrays unwrapped). */
function plain( value ) {

	return JSON.parse( JSON.stringify( value, ( _key, v ) => ( ArrayBuffer.isView( v ) ? Array.from( v ) : v ) ) );

}

function same( js, py, path ) {

	if ( typeof py === 'number' ) {

		assert.equal( typeof js, 'number', `${path}: expected a number` );
		nearRelative( js, py, RELATIVE, path );
	} else if ( Array.isArray( py ) ) {

		assert.ok( Array.isArray( js ) && js.length === py.length, `${path}: JS ${JSON.stringify( js )}, Python ${JSON.stringify( py )}` );
		py.forEach( ( v, k ) => same( js[ k ], v, `${path}[${k}]` ) );
	} else if ( py !== null && typeof py === 'object' ) {

		assert.deepEqual( Object.keys( js ).sort(), Object.keys( py ).sort(), `${path}: keys` );
		for ( const key of Object.keys( py ) ) same( js[ key ], py[ key ], `${path}.${key}` );
	} else {

		assert.equal( js, py, path );

	}

}

test( 'JS exports the same constant names as Python', () => {

	const names = Object.keys( constants ).filter( ( name ) => name === name.toUpperCase() );
	assert.deepEqual( names.sort(), Object.keys( PYTHON ).sort() );

} );

test( 'every constant has the same value on both sides', () => {

	for ( const [ name, value ] of Object.entries( PYTHON ) ) same( plain( constants[ name ] ), value, name );

} );
