// The real head in Node: every scene mesh of assets/build (GLB), the parametric tongue with the
// collision tables, the face rig and the velum rig, as the views load them.
import { readFileSync } from 'node:fs';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { Head } from '../../../web/src/scene/Head.js';
import { geometryFromGltf } from '../../../web/src/scene/gltfGeometry.js';
import { createArticulation } from '../../../web/src/scene/Articulation.js';
import { decodeCollisionTables } from '../../../web/src/core/tables.js';

const BUILD = new URL( '../../../assets/build/', import.meta.url );
const file = ( name ) => readFileSync( new URL( name, BUILD ) );
const json = ( name ) => JSON.parse( file( name ).toString( 'utf8' ) );
const arrayBuffer = ( b ) => b.buffer.slice( b.byteOffset, b.byteOffset + b.byteLength );

/** { head, articulation, landmarks } from the built assets (no viewer: updates are the caller's). */
export async function loadBuiltHead() {

	const head = new Head();
	for ( const entry of json( 'manifest.json' ).meshes.filter( ( m ) => m.scene ) ) {

		const gltf = await new GLTFLoader().parseAsync( arrayBuffer( file( entry.file ) ), '' );
		head.addPart( { name: entry.name, role: entry.role }, geometryFromGltf( gltf ) );

	}

	head.finishLoading();
	const articulation = createArticulation( head, null, {
		definition: json( 'tongue-rig.json' ), tables: decodeCollisionTables( file( 'collision-tables.bin' ) ),
		face: json( 'face-rig.json' ), velum: json( 'velum-rig.json' ),
	} );
	return { head, articulation, landmarks: json( 'landmarks.json' ) };

}
