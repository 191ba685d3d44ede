// The child's practice without a browser (ui/practice/ChildPracticeFlow.js, ui/shared/ChildPracticePictures.js):
// a class code as typed by an adult, a round through a lesson counting the replays of each target
// and making its practice record, and a picture for every avatar the server offers and every face.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

import { JOIN_CODE_ALPHABET, looksLikeJoinCode, normaliseJoinCode, PracticeRound } from '../../web/src/ui/practice/ChildPracticeFlow.js';
import { codeMessage, NO_CLASS } from '../../web/src/ui/practice/practiceMessages.js';
import { AVATAR_NAMES, pictureShapes, RATINGS } from '../../web/src/ui/shared/ChildPracticePictures.js';

/** The server's avatars, read from the store module that defines them. */
function serverAvatars() {

	const source = readFileSync( new URL( '../../server/glasshead/store/lessons.py', import.meta.url ), 'utf8' );
	const tuple = /^AVATARS = \(([^)]*)\)/m.exec( source );
	assert.ok( tuple, 'AVATARS is defined in server/glasshead/store/lessons.py' );
	return [ ...tuple[ 1 ].matchAll( /"([a-z]+)"/g ) ].map( ( match ) => match[ 1 ] );

}

test( 'a class code typed in any case, with spaces or a dash, is read as the server compares it', () => {

	assert.equal( normaliseJoinCode( ' 7kq 4-mx ' ), '7KQ4MX' );
	assert.ok( looksLikeJoinCode( normaliseJoinCode( '7kq4mx' ) ) );
	assert.ok( ! looksLikeJoinCode( '7KQ4M' ), 'five characters' );
	assert.ok( ! looksLikeJoinCode( '7KQ4M0' ), 'a zero is never in a code' );
	assert.ok( ! looksLikeJoinCode( 'SSSSSS' ), 'S looks like 5 and is left out' );

} );

test( 'a round goes through the items one at a time, counting each target\'s replays in its record', () => {

	const lesson = { id: 4, items: [ { target: { kind: 'phoneme', text: 's' } }, { target: { kind: 'word', text: 'ship' } } ] };
	const round = new PracticeRound( lesson, { id: 12 } );
	assert.deepEqual( [ round.index, round.done, round.item.target.text ], [ 0, false, 's' ] );
	round.replayed();
	round.replayed();
	assert.deepEqual( round.record( 3 ), { child_id: 12, lesson_id: 4, item_index: 0, replays: 2, rating: 3, rated_by: 'child' } );
	assert.deepEqual( round.record( 2, { centroid: 5600, verdict: 'in' } ).measures, { centroid: 5600, verdict: 'in' }, 'what the voice measured goes with it' );
	assert.equal( 'measures' in round.record( 2, {} ), false, 'nothing measured, no measures' );
	assert.equal( round.next( { id: 100 } ).target.text, 'ship' );
	assert.deepEqual( round.record(), { child_id: 12, lesson_id: 4, item_index: 1, replays: 0 }, 'no rating without a face chosen; replays start again' );
	assert.equal( round.next( { id: 101 } ), null );
	assert.deepEqual( [ round.done, round.records.map( ( r ) => r.id ) ], [ true, [ 100, 101 ] ] );
	assert.throws( () => new PracticeRound( { id: 5, items: [] }, { id: 12 } ), /lesson with items/ );

} );

test( 'every avatar the server offers has a picture of its own, and every rating a face', () => {

	const avatars = serverAvatars();
	assert.ok( avatars.length >= 10, `${ avatars.length } avatars` );
	assert.deepEqual( [ ...AVATAR_NAMES ].sort(), [ ...avatars ].sort() );
	const drawn = avatars.map( ( name ) => JSON.stringify( pictureShapes( name ) ) );
	assert.equal( new Set( drawn ).size, avatars.length, 'no two avatars look the same' );
	assert.deepEqual( RATINGS.map( ( r ) => r.rating ), [ 1, 2, 3 ] );
	for ( const { face } of RATINGS ) assert.ok( pictureShapes( face ).length >= 3, face );
	assert.equal( pictureShapes( 'unicorn' ).length, 1, 'an avatar added on the server later still gets a plain picture' );

} );

test( 'a typed code is said wrong with what to do: letters codes never have named, or how many there are', () => {

	assert.equal( codeMessage( '7kq 4-mx' ), null, 'spaces, dashes and small letters are fine' );
	assert.equal( codeMessage( 'ABC123' ).text, 'A class code never has B, 1 and 2. Ask a grown-up to read the code again.' );
	assert.equal( codeMessage( 'O0O0O0' ).text, 'A class code never has O and 0. Ask a grown-up to read the code again.' );
	assert.equal( codeMessage( 'abc' ).text, 'A class code never has B. Ask a grown-up to read the code again.' );
	assert.equal( codeMessage( 'ACD' ).text, 'A class code has 6 letters and numbers; this one has 3. Ask a grown-up to check it.' );
	assert.equal( codeMessage( 'ACD34?' ).text, 'A class code has only letters and numbers, not ?. Ask a grown-up to read the code again.' );
	assert.equal( codeMessage( '' ).text, 'Type the class code: six letters and numbers.' );
	for ( const typed of [ 'ABC123', 'ACD', '' ] ) assert.equal( codeMessage( typed ).icon, 'ask-adult', 'every message has its picture' );
	assert.equal( NO_CLASS.icon, 'ask-adult' );

} );

test( 'the page\'s code alphabet is the server\'s', () => {

	const server = readFileSync( new URL( '../../server/glasshead/store/lessons.py', import.meta.url ), 'utf8' );
	assert.equal( /^JOIN_CODE_ALPHABET = "([^"]+)"/m.exec( server )[ 1 ], JOIN_CODE_ALPHABET );

} );
