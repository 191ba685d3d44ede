// The admin's people (ui/admin/AdminPeople.js): a made-up password and what a refused change says.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { madePassword, peopleErrorWords, STAFF_ROLES } from '../../web/src/ui/admin/AdminPeople.js';

test( 'a made-up password is twelve letters without look-alikes, in three groups of four', () => {

	const seen = new Set();
	for ( let k = 0; k < 200; k ++ ) {

		const password = madePassword();
		assert.match( password, /^[a-hjkmnp-z2-9]{4}-[a-hjkmnp-z2-9]{4}-[a-hjkmnp-z2-9]{4}$/ );
		seen.add( password );

	}

	assert.equal( seen.size, 200, 'no two alike' );
	assert.equal( madePassword( ( n ) => new Uint32Array( n ) ), 'aaaa-aaaa-aaaa', 'the letters come from the random values given' );

} );

test( 'a refused change says why in words: someone else changed it, a taken username, the field a 422 names', () => {

	assert.match( peopleErrorWords( { status: 412 } ), /Someone else changed this person/ );
	assert.equal( peopleErrorWords( { status: 409, detail: "field username: 'ann' is taken" } ), "That username: 'ann' is taken" );
	assert.equal( peopleErrorWords( { status: 422, detail: 'body.password: String should have at least 8 characters' } ), 'password: String should have at least 8 characters' );
	assert.deepEqual( STAFF_ROLES, [ 'teacher', 'clinician', 'author', 'admin' ] );

} );
