// Sharing a class from the lesson runner (ui/lessons/LessonRunnerStaff.js): who may change whom a class is
// shared with (its owner, an admin; not its staff), and how a member is named in the list.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { changesStaff, memberLabel } from '../../web/src/ui/lessons/LessonRunnerStaff.js';

const staff = { owner: { user_id: 3, username: 'ann@school.example', display_name: 'Ann', role: 'teacher' }, staff: [ { user_id: 7, username: 'cleo@clinic.example', display_name: 'Cleo', role: 'clinician' } ] };

test( 'the owner of a class and an admin change whom it is shared with; its staff and nobody signed in do not', () => {

	assert.equal( changesStaff( { id: 3, role: 'teacher' }, staff ), true );
	assert.equal( changesStaff( { id: 9, role: 'admin' }, staff ), true );
	assert.equal( changesStaff( { id: 7, role: 'clinician' }, staff ), false );
	assert.equal( changesStaff( null, staff ), false );
	assert.equal( changesStaff( { id: 3, role: 'teacher' }, { owner: null, staff: [] } ), false, 'an ownerless class is an admin\'s' );

} );

test( 'a member is named by their display name and role, or their username when they have no name', () => {

	assert.equal( memberLabel( staff.staff[ 0 ] ), 'Cleo (clinician)' );
	assert.equal( memberLabel( { username: 'tom@school.example', display_name: '', role: 'teacher' } ), 'tom@school.example (teacher)' );

} );
