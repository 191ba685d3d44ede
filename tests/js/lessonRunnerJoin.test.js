// How children join a class (ui/lessons/LessonRunnerJoin.js, ui/shared/qrCode.js): the join link
// on the school's address or the page's own, the code in two groups, loopback addresses told
// apart, the QR code's SVG path drawing exactly the encoder's dark modules, and the practice
// reading the code a link carries (ui/practice/ChildPracticeFlow.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { isLoopbackAddress, joinLink, siteBase, spacedCode } from '../../web/src/ui/lessons/LessonRunnerJoin.js';
import { qrModules, qrPath } from '../../web/src/ui/shared/qrCode.js';
import { joinCodeFromHash } from '../../web/src/ui/practice/ChildPracticeFlow.js';

test( 'the join link is on the school\'s address when the server has one, else on the page\'s own', () => {

	const page = { origin: 'http://127.0.0.1:8000', pathname: '/' };
	assert.equal( siteBase( 'http://glasshead.school.example:8000/', page ), 'http://glasshead.school.example:8000' );
	assert.equal( siteBase( null, page ), 'http://127.0.0.1:8000' );
	assert.equal( siteBase( null, { origin: 'https://school.example', pathname: '/glasshead/index.html' } ), 'https://school.example/glasshead' );
	assert.equal( joinLink( 'https://school.example', 'ACD347' ), 'https://school.example/#/practice?code=ACD347' );
	assert.equal( spacedCode( 'ACD347' ), 'ACD 347' );

} );

test( 'this computer\'s own addresses are told apart from the school\'s', () => {

	for ( const base of [ 'http://127.0.0.1:8000', 'http://localhost:8000', 'http://[::1]:8000', 'http://app.localhost', 'http://127.1.2.3' ] ) assert.equal( isLoopbackAddress( base ), true, base );
	for ( const base of [ 'http://192.168.1.20:8000', 'https://glasshead.school.example', 'http://localhost.school.example', 'not a url' ] ) assert.equal( isLoopbackAddress( base ), false, base );

} );

test( 'the QR code\'s path covers exactly the dark modules, with a quiet zone of four', () => {

	const text = 'http://glasshead.school.example:8000/#/practice?code=ACD347';
	const modules = qrModules( text );
	const size = modules.length;
	assert.ok( size >= 21 + 8 && ( size - 8 - 17 ) % 4 === 0, `${ size } modules a side: a QR version with its border` );
	for ( let k = 0; k < 4; k ++ ) assert.ok( modules[ k ].every( ( dark ) => ! dark ) && modules.every( ( row ) => ! row[ k ] ), 'quiet zone' );
	const drawn = modules.map( ( row ) => row.map( () => false ) );
	for ( const [ , x, y, w ] of qrPath( modules ).matchAll( /M(\d+) (\d+)h(\d+)v1h-\d+z/g ) ) {

		for ( let i = 0; i < Number( w ); i ++ ) drawn[ Number( y ) ][ Number( x ) + i ] = true;

	}

	assert.deepEqual( drawn, modules );
	// The three finder patterns: 7 x 7 dark rings at the corners.
	assert.equal( modules[ 4 ].slice( 4, 11 ).every( Boolean ), true );
	assert.equal( modules[ 4 ].slice( size - 11, size - 4 ).every( Boolean ), true );

} );

test( 'a join link\'s code is read from the practice\'s address; a code of the wrong shape is none', () => {

	assert.equal( joinCodeFromHash( '#/practice?code=ACD347' ), 'ACD347' );
	assert.equal( joinCodeFromHash( '#/practice?code=acd-347' ), 'ACD347' );
	assert.equal( joinCodeFromHash( '#/practice?code=ABC123' ), null, 'B, 1 and 2 are never in a code' );
	assert.equal( joinCodeFromHash( '#/practice' ), null );

} );
