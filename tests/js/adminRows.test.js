import { test } from 'node:test';
import assert from 'node:assert/strict';
import { confirmWords, deletedWords, exportName } from '../../web/src/ui/admin/adminRows.js';

test( 'a deletion is told in words, one and many and none', () => {

	assert.equal( deletedWords( { practice_records: 2, recordings: 1, assignments: 0, child_tokens: 1 } ), '2 practice records, 1 EPG recording, no assignments and 1 sign-in' );
	assert.equal( deletedWords( {} ), 'no practice records, no EPG recordings, no assignments and no sign-ins' );

} );

test( 'the confirmation names the child and what goes, and an export is named by the child’s id', () => {

	const words = confirmWords( { id: 4, display_name: 'Ada' } );
	assert.match( words, /^Delete everything stored about Ada: their practice, EPG recordings/ );
	assert.match( words, /cannot be undone/ );
	assert.equal( exportName( { id: 4 } ), 'child-4.json' );

} );
