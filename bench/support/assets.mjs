// Shared by the benchmarks: the built assets read as the app reads them. The bytes come from
// assets/build (GLASSHEAD_ASSETS_DIR overrides it) instead of the API, and go through the web
// app's own decoders: the GLBs through three.js's GLTFLoader and scene/gltfGeometry.js (the
// quantised positions dequantised, the node transform baked in, as ui/loaders.js does), the
// collision tables through core/tables.js. A benchmark that parsed them its own way would
// measure, and check against, another mesh than the one the app shows.
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

import { decodeCollisionTables } from '../../web/src/core/tables.js';
import { geometryFromGltf } from '../../web/src/scene/gltfGeometry.js';

export const REPO = resolve( dirname( fileURLToPath( import.meta.url ) ), '..', '..' );
export const ASSETS = process.env.GLASSHEAD_ASSETS_DIR ?? join( REPO, 'assets', 'build' );

/** The bytes of a built file; exits with a message when it is missing. */
export function builtFile( name ) {

	const path = join( ASSETS, name );
	if ( ! existsSync( path ) ) {

		console.error( `${ path } is missing: run \`node scripts/setup.mjs\` (or \`glasshead build\`) first` );
		process.exit( 2 );

	}

	return readFileSync( path );

}

/** A built JSON document, parsed. */
export const builtJson = ( name ) => JSON.parse( builtFile( name ).toString( 'utf8' ) );

/** Whether every named built file is there. */
export const haveBuilt = ( ...names ) => names.every( ( name ) => existsSync( join( ASSETS, name ) ) );

/** The collision tables, decoded as the app decodes them. */
export const builtCollisionTables = () => decodeCollisionTables( builtFile( 'collision-tables.bin' ) );

const arrayBuffer = ( b ) => b.buffer.slice( b.byteOffset, b.byteOffset + b.byteLength );

/**
 * The BufferGeometry the app makes of a built mesh of the manifest (its scene entry by default):
 * float32 millimetres in the project frame.
 */
export async function builtMesh( name, { scene = true } = {} ) {

	const entry = builtJson( 'manifest.json' ).meshes.find( ( m ) => m.name === name && ( ! scene || m.scene !== false ) );
	if ( ! entry ) throw new Error( `the manifest lists no ${ scene ? 'scene ' : '' }mesh "${ name }"` );
	return geometryFromGltf( await new GLTFLoader().parseAsync( arrayBuffer( builtFile( entry.file ) ), '' ) );

}
