// Reading the shared vectors (tests/vectors) and comparing floats with their stated tolerances.
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { checkVectorDocument } from './vectorSchema.js';

export { near, nearArray, nearRelative } from './near.js';

export const VECTORS_DIR = join( dirname( fileURLToPath( import.meta.url ) ), '..', '..', 'vectors' );

/** A vector file: JSON documents parsed and checked against the schema, other files as bytes. */
export function readVectors( name ) {

	const bytes = readFileSync( join( VECTORS_DIR, name ) );
	return name.endsWith( '.json' ) ? checkVectorDocument( JSON.parse( bytes.toString( 'utf8' ) ), name ) : bytes;

}

/** The value of a document's tolerance ``name`` (its unit and reason are in the file). */
export function tolerance( document, name ) {

	const entry = document.tolerance[ name ];
	if ( ! entry ) throw new Error( `the vector file states no tolerance '${ name }'` );
	return entry.value;

}

/** The float32 values of base64 little-endian bytes (inputs given bit for bit). */
export function decodeF32( text ) {

	const bytes = Buffer.from( text, 'base64' );
	return new Float32Array( bytes.buffer.slice( bytes.byteOffset, bytes.byteOffset + bytes.byteLength ) );

}
