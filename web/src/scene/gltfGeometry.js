// Geometry from a parsed glTF: what the anatomy GLBs (GET /anatomy) become in the Head. The
// files are fetched by the views (ui/shared/loaders.js); nothing here fetches.

import { BufferAttribute } from 'three';
import { mergeGeometries } from 'three/addons/utils/BufferGeometryUtils.js';

/**
 * A plain Float32 copy of a vec3 attribute that may be interleaved or quantised, so that kernels
 * can read `attribute.array` as x y z per vertex.
 */
function toFloat32( attribute ) {

	if ( ! attribute.isInterleavedBufferAttribute && attribute.array instanceof Float32Array && ! attribute.normalized ) return attribute;
	const array = new Float32Array( 3 * attribute.count );
	for ( let i = 0; i < attribute.count; i ++ ) {

		array[ 3 * i ] = attribute.getX( i );
		array[ 3 * i + 1 ] = attribute.getY( i );
		array[ 3 * i + 2 ] = attribute.getZ( i );

	}

	return new BufferAttribute( array, 3 );

}

/**
 * One BufferGeometry from a loaded glTF scene: every mesh's geometry with its node transform baked
 * in, merged when there are several. Only positions, normals and the index are kept.
 */
export function geometryFromGltf( gltf ) {

	const geometries = [];
	gltf.scene.updateMatrixWorld( true );
	gltf.scene.traverse( ( object ) => {

		if ( ! object.isMesh ) return;
		const geometry = object.geometry.clone();
		for ( const name of Object.keys( geometry.attributes ) ) {

			if ( name !== 'position' && name !== 'normal' ) geometry.deleteAttribute( name );

		}

		for ( const name of [ 'position', 'normal' ] ) {

			const attribute = geometry.getAttribute( name );
			if ( attribute ) geometry.setAttribute( name, toFloat32( attribute ) );

		}

		geometry.applyMatrix4( object.matrixWorld );
		geometries.push( geometry );

	} );

	if ( geometries.length === 0 ) throw new Error( 'the file holds no triangle mesh' );
	if ( geometries.length === 1 ) return geometries[ 0 ];
	const merged = mergeGeometries( geometries.map( ( g ) => ( g.index ? g : g.toNonIndexed() ) ) );
	if ( ! merged ) throw new Error( 'its meshes have different attributes and cannot be merged' );
	return merged;

}
