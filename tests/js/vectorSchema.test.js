// Every shared vector file follows the one schema, and a file that breaks it is reported with its
// name and the case (index and description).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';

import { checkVectorDocument, schemaProblems, VectorSchemaError } from './support/vectorSchema.js';
import { VECTORS_DIR } from './support/vectors.js';

function goodDocument() {

	return {
		description: 'a small valid document',
		generator: 'glasshead vectors example.json',
		format_version: 1,
		constants: { seed: 1 },
		tolerance: { vertex_mm: { value: 1e-4, unit: 'mm', reason: 'float32 in JS' } },
		fixtures: { rig: {} },
		cases: [
			{ description: 'one', input: { x: 1 }, expected: { y: 2 } },
			{ description: 'a refusal', input: { x: - 1 }, expected: { error: 'negative' } },
		],
	};

}

const files = readdirSync( VECTORS_DIR ).filter( ( name ) => name.endsWith( '.json' ) ).sort();

test( 'there are vector files to check', () => {

	assert.ok( files.length >= 8, `${ files.length } JSON vector files` );

} );

for ( const name of files ) {

	test( `${ name } follows the vector schema`, () => {

		checkVectorDocument( JSON.parse( readFileSync( join( VECTORS_DIR, name ), 'utf8' ) ), name );

	} );

}

test( 'a valid document passes', () => {

	assert.deepEqual( schemaProblems( goodDocument() ), [] );

} );

test( 'a broken case is reported with the file, its index and its description', () => {

	const document = goodDocument();
	document.cases[ 1 ].expected = { error: 'negative', also: 1 };
	document.cases.push( { description: 'one', input: [], expected: {} } );
	assert.throws( () => checkVectorDocument( document, 'broken.json' ), ( error ) => {

		assert.ok( error instanceof VectorSchemaError );
		assert.match( error.message, /broken\.json: case 1 \('a refusal'\): a refusal's expected must be exactly/ );
		assert.match( error.message, /broken\.json: case 2 \('one'\): description repeats case 0/ );
		assert.match( error.message, /broken\.json: case 2 \('one'\): input must be an object/ );
		return true;

	} );

} );

const rules = [
	[ ( d ) => delete d.constants, 'top level: missing constants' ],
	[ ( d ) => ( d.seed = 3 ), 'top level: unknown keys seed' ],
	[ ( d ) => ( d.format_version = '2' ), 'format_version must be an integer' ],
	[ ( d ) => ( d.generator = 'python -m glasshead.geometry.vectors' ), 'generator must be' ],
	[ ( d ) => ( d.tolerance.x = { value: 0, unit: 'mm', reason: 'r' } ), 'value must' ],
	[ ( d ) => ( d.tolerance.x = { value: 1, unit: 'inch', reason: 'r' } ), 'unit \'inch\'' ],
	[ ( d ) => ( d.tolerance.x = 1e-3 ), 'tolerance \'x\': must be exactly' ],
	[ ( d ) => delete d.cases[ 0 ].expected, 'case 0 (\'one\'): missing expected' ],
	[ ( d ) => ( d.cases[ 0 ].note = 'n' ), 'case 0 (\'one\'): unknown keys note' ],
	[ ( d ) => ( d.cases[ 0 ].description = '' ), 'case 0: description must be' ],
];

test( 'each rule names what is wrong, in the file', () => {

	for ( const [ change, fragment ] of rules ) {

		const document = goodDocument();
		change( document );
		assert.throws( () => checkVectorDocument( document, 'broken.json' ), ( error ) => error.message.includes( 'broken.json' ) && error.message.includes( fragment ), fragment );

	}

} );
