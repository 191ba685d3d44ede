// EPG indices in JS against the shared vectors (written by Python) and a slow reference that
// follows emuR's R code line by line (R/epg.class.R), over every real frame of the emuR set.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, existsSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { nearRelative, readVectors, tolerance } from './support/vectors.js';

import {
	EPG_CELLS, EPG_COLUMNS, EPG_ELECTRODES, EPG_MISSING_CELLS, EPG_ROWS, EPG_ZONES,
} from '../../web/src/core/constants.js';
import {
	INDEX_SLOTS, INDEX_STRIDE, epgIndices, epgIndicesAll, rowsToFrame,
} from '../../web/src/core/epgIndices.js';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const VECTORS = readVectors( 'epg-indices.json' );
const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( HERE, '..', '..', '..', 'shared', 'data' );
/** Relative above 1, absolute below (the vector file states the reason). */
const INDEX_TOLERANCE = tolerance( VECTORS, 'index' );

function close( actual, expected, what ) {

	nearRelative( actual, expected, INDEX_TOLERANCE, what );

}

// emuR, transcribed: epgsum by row / column over an 8 x 8 array, then the index formulae.
function emurReference( grid ) {

	const rowSum = ( r ) => grid[ r ].reduce( ( a, b ) => a + b, 0 );
	const colSum = ( c ) => grid.reduce( ( a, row ) => a + row[ c ], 0 );
	const rows = [ 0, 1, 2, 3, 4, 5, 6, 7 ].map( rowSum );
	const total = rows.reduce( ( a, b ) => a + b, 0 );
	const cogWeights = [ 7.5, 6.5, 5.5, 4.5, 3.5, 2.5, 1.5, 0.5 ];
	const aiWeights = [ 1, 9, 81, 729, 4921 ]; // applied to rows 5:1
	const aiDivisor = [ 8, 8, 8, 8, 6 ];
	const aiRows = [ 4, 3, 2, 1, 0 ].map( ( r ) => rows[ r ] );
	const aiNum = Math.log( aiRows.reduce( ( a, o, k ) => a + aiWeights[ k ] * o / aiDivisor[ k ], 0 ) + 1 );
	const ciWeights = [ 1, 17, 289, 4913 ];
	const ciNum = Math.log( ciWeights[ 0 ] * ( colSum( 0 ) + colSum( 7 ) ) / 14 + ciWeights[ 1 ] * ( colSum( 1 ) + colSum( 6 ) ) / 16 +
		ciWeights[ 2 ] * ( colSum( 2 ) + colSum( 5 ) ) / 16 + ciWeights[ 3 ] * ( colSum( 3 ) + colSum( 4 ) ) / 16 + 1 );
	return {
		contacts: total,
		cog: total === 0 ? 0 : rows.reduce( ( a, s, r ) => a + s * cogWeights[ r ], 0 ) / total,
		anteriority: aiNum / Math.log( 5741 + 1 ),
		centrality: ciNum / Math.log( 5220 + 1 ),
		dorsopalatal: ( rows[ 5 ] + rows[ 6 ] + rows[ 7 ] ) / 24,
	};

}

test( 'the shared vectors are well formed and agree with the JS constants', () => {

	assert.equal( VECTORS.format_version, 2 );
	const descriptions = VECTORS.cases.map( ( c ) => c.description );
	assert.equal( new Set( descriptions ).size, descriptions.length, 'descriptions are unique' );
	assert.ok( VECTORS.cases.length >= 50, 'many real frames' );
	const k = VECTORS.constants;
	assert.deepEqual( [ k.rows, k.columns, k.electrodes ], [ EPG_ROWS, EPG_COLUMNS, EPG_ELECTRODES ] );
	assert.deepEqual( k.missing_cells, [ ...EPG_MISSING_CELLS ] );
	assert.deepEqual( k.zones, { alveolar: [ 0, 2 ], palatal: [ 2, 5 ], velar: [ 5, 8 ] } );
	assert.deepEqual( Object.fromEntries( Object.entries( EPG_ZONES ).map( ( [ n, z ] ) => [ n, [ ...z ] ] ) ), k.zones );
	assert.deepEqual( k.slots, [ ...INDEX_SLOTS ] );
	assert.equal( INDEX_STRIDE, INDEX_SLOTS.length );

} );

test( 'every vector case gives the Python values in every slot', () => {

	const frames = new Uint8Array( EPG_CELLS );
	const target = new Float64Array( INDEX_STRIDE );
	for ( const c of VECTORS.cases ) {

		rowsToFrame( c.input.rows, frames, 0 );
		epgIndices( frames, 0, target );
		INDEX_SLOTS.forEach( ( name, i ) => close( target[ i ], c.expected[ name ], `${c.description}: ${name}` ) );

	}

} );

test( 'all frames at once write each frame into its own stride and nothing past the end', () => {

	const cases = VECTORS.cases;
	const frames = new Uint8Array( cases.length * EPG_CELLS );
	cases.forEach( ( c, i ) => rowsToFrame( c.input.rows, frames, i ) );
	const target = new Float64Array( cases.length * INDEX_STRIDE + 3 ).fill( - 7 );
	epgIndicesAll( frames, cases.length, target );
	cases.forEach( ( c, i ) => {

		close( target[ i * INDEX_STRIDE ], c.expected.contacts, `${c.description}: contacts` );
		close( target[ i * INDEX_STRIDE + INDEX_STRIDE - 1 ], c.expected.dorsopalatal, `${c.description}: dorsopalatal` );

	} );
	assert.deepEqual( [ ...target.slice( - 3 ) ], [ - 7, - 7, - 7 ] );
	assert.throws( () => epgIndicesAll( frames, cases.length + 1, target ), RangeError );

} );

test( 'every real frame of the emuR set matches a line-by-line transcription of emuR', () => {

	const path = join( DATA_DIR, 'epg', 'emur-engassim.json' );
	assert.ok( existsSync( path ), `reference EPG data missing at ${path}; set GLASSHEAD_DATA_DIR` );
	const segments = JSON.parse( readFileSync( path, 'utf8' ) ).segments;
	const frameRows = segments.flatMap( ( s ) => s.frames.map( ( f ) => f.rows ) );
	assert.equal( frameRows.length, 1421 );
	const frames = new Uint8Array( frameRows.length * EPG_CELLS );
	frameRows.forEach( ( rows, i ) => rowsToFrame( rows, frames, i ) );
	const target = new Float64Array( frameRows.length * INDEX_STRIDE );
	epgIndicesAll( frames, frameRows.length, target );
	frameRows.forEach( ( rows, i ) => {

		const grid = rows.map( ( row ) => [ ...row ].map( Number ) );
		const expected = emurReference( grid );
		const at = ( name ) => target[ i * INDEX_STRIDE + INDEX_SLOTS.indexOf( name ) ];
		for ( const name of Object.keys( expected ) ) close( at( name ), expected[ name ], `frame ${i}: ${name}` );

	} );

} );

test( 'rowsToFrame refuses a wrong row count, a short row and a value other than 0 or 1', () => {

	const frames = new Uint8Array( EPG_CELLS );
	const good = [ '00000000', '00000000', '00000000', '00000000', '00000000', '00000000', '00000000', '00000000' ];
	assert.throws( () => rowsToFrame( good.slice( 1 ), frames, 0 ), /expected 8 rows/ );
	assert.throws( () => rowsToFrame( [ '0000000', ...good.slice( 1 ) ], frames, 0 ), /row 1 has 7/ );
	assert.throws( () => rowsToFrame( [ ...good.slice( 0, 7 ), '00200000' ], frames, 0 ), /row 8 column 3/ );

} );
