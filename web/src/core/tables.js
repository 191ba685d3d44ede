// Loader for the collision tables file written by glasshead.pipeline.collision_tables.
// Layout (server/glasshead/geometry/collision_format.py): 8 magic bytes "GHCOLTAB", uint32 format
// version, uint32 header length L, L bytes of JSON (UTF-8, space padded to 8), then the payload:
// little-endian arrays on 8-byte boundaries, each declared in the header with dtype, shape,
// offset and nbytes, guarded by the payload's CRC-32. Anything unexpected is refused with a
// message; nothing is guessed.

import { COLLISION_TABLES_ARRAYS, COLLISION_TABLES_FORMAT_VERSION, COLLISION_TABLES_MAGIC } from './constants.js';

/** Collision tables that cannot be read as this version of the format. */
export class CollisionTablesError extends Error {

	constructor( message ) {

		super( message );
		this.name = 'CollisionTablesError';

	}

}

/** Bytes before the JSON header: magic (8) + version (4) + header length (4). */
const PREFIX_BYTES = 8 + 4 + 4;

/** The typed array of each dtype of the payload (COLLISION_TABLES_ARRAYS, in numpy's notation). */
const TYPED_ARRAYS = Object.freeze( { '<f4': Float32Array, '<u4': Uint32Array, '|u1': Uint8Array } );

let crcTable = null;

/** zlib's CRC-32 (polynomial 0xEDB88320), as Python's zlib.crc32. */
export function crc32( bytes ) {

	if ( crcTable === null ) {

		crcTable = new Uint32Array( 256 );
		for ( let n = 0; n < 256; n ++ ) {

			let c = n;
			for ( let k = 0; k < 8; k ++ ) c = c & 1 ? 0xEDB88320 ^ ( c >>> 1 ) : c >>> 1;
			crcTable[ n ] = c >>> 0;

		}

	}

	let crc = 0xFFFFFFFF;
	for ( let i = 0; i < bytes.length; i ++ ) crc = crcTable[ ( crc ^ bytes[ i ] ) & 0xFF ] ^ ( crc >>> 8 );
	return ( crc ^ 0xFFFFFFFF ) >>> 0;

}

function toBytes( data ) {

	if ( data instanceof ArrayBuffer ) return new Uint8Array( data );
	if ( ArrayBuffer.isView( data ) ) {

		const bytes = new Uint8Array( data.buffer, data.byteOffset, data.byteLength );
		// Typed views need aligned offsets; copy when the caller's view is not 8-byte aligned.
		return data.byteOffset % 8 === 0 ? bytes : bytes.slice();

	}

	throw new CollisionTablesError( 'collision tables must be an ArrayBuffer or a typed array' );

}

/** The JSON header, after checking the magic bytes and the format version (decode_collision_header). */
export function decodeCollisionHeader( data ) {

	const bytes = toBytes( data );
	const magic = new TextDecoder().decode( bytes.subarray( 0, 8 ) );
	if ( bytes.length < PREFIX_BYTES || magic !== COLLISION_TABLES_MAGIC ) {

		throw new CollisionTablesError( 'not a Glasshead collision tables file (bad magic bytes)' );

	}

	const view = new DataView( bytes.buffer, bytes.byteOffset, bytes.byteLength );
	const version = view.getUint32( 8, true );
	const length = view.getUint32( 12, true );
	if ( version !== COLLISION_TABLES_FORMAT_VERSION ) {

		throw new CollisionTablesError( `collision tables format version ${ version } is not supported ` +
			`(this client understands version ${ COLLISION_TABLES_FORMAT_VERSION }); reload the page ` +
			'after the server has been rebuilt, or rebuild the tables with `glasshead build`' );

	}

	if ( PREFIX_BYTES + length > bytes.length ) throw new CollisionTablesError( 'collision tables file is truncated inside its header' );
	let header;
	try {

		header = JSON.parse( new TextDecoder( 'utf-8', { fatal: true } ).decode( bytes.subarray( PREFIX_BYTES, PREFIX_BYTES + length ) ) );

	} catch ( error ) {

		throw new CollisionTablesError( `collision tables header is not valid JSON (${ error.message })` );

	}

	if ( header.format !== 'glasshead-collision-tables' || header.format_version !== version ) {

		throw new CollisionTablesError( 'collision tables header does not match its binary prefix' );

	}

	if ( header.byte_order !== 'little' ) throw new CollisionTablesError( 'collision tables must be little-endian' );
	return { header, bytes, payloadStart: PREFIX_BYTES + length };

}

/**
 * Decode and check a collision tables file (twin of collision_format.decode_collision_tables).
 * data: ArrayBuffer or typed array of the whole file. Returns the tables: the header, typed array
 * views on the payload (no copies) and the numbers the kernel needs, ready for correctVertices.
 */
export function decodeCollisionTables( data ) {

	const { header, bytes, payloadStart } = decodeCollisionHeader( data );
	const payload = bytes.subarray( payloadStart );
	if ( payload.length !== header.payload_bytes ) {

		throw new CollisionTablesError( `collision tables payload is ${ payload.length } bytes, header says ${ header.payload_bytes } (truncated or padded file)` );

	}

	if ( crc32( payload ) !== header.payload_crc32 ) throw new CollisionTablesError( 'collision tables payload fails its CRC-32 check (corrupt)' );

	const arrays = {};
	for ( const [ name, dtype ] of Object.entries( COLLISION_TABLES_ARRAYS ) ) {

		const Type = TYPED_ARRAYS[ dtype ];

		const entry = header.arrays && header.arrays[ name ];
		if ( ! entry ) throw new CollisionTablesError( `collision tables lack the array "${ name }"` );
		if ( entry.dtype !== dtype ) throw new CollisionTablesError( `array "${ name }" has dtype ${ entry.dtype }, expected ${ dtype }` );
		const length = entry.shape.reduce( ( a, b ) => a * b, 1 );
		if ( length * Type.BYTES_PER_ELEMENT !== entry.nbytes || entry.offset % 8 !== 0 || entry.offset + entry.nbytes > payload.length ) {

			throw new CollisionTablesError( `array "${ name }" does not fit its declared shape/offset` );

		}

		arrays[ name ] = new Type( payload.buffer, payload.byteOffset + entry.offset, length );

	}

	const { liner, voxels } = header;
	const nlon = liner.nlon, nlat = liner.nlat;
	const triangleCount = arrays.triangles.length / 9;
	const expected = {
		node_radius: ( nlat + 1 ) * ( nlon + 1 ), cell_kind: nlat * nlon, cell_rmin: nlat * nlon,
		cell_rmax: nlat * nlon, cell_offsets: nlat * nlon + 1, planes: triangleCount * 4,
		voxels: voxels.shape[ 0 ] * voxels.shape[ 1 ] * voxels.shape[ 2 ],
	};
	for ( const [ name, length ] of Object.entries( expected ) ) {

		if ( arrays[ name ].length !== length ) throw new CollisionTablesError( `array "${ name }" has ${ arrays[ name ].length } values, expected ${ length }` );

	}

	const offsets = arrays.cell_offsets;
	if ( offsets[ 0 ] !== 0 || offsets[ offsets.length - 1 ] !== arrays.cell_triangles.length ) {

		throw new CollisionTablesError( 'cell_offsets are not a valid index into cell_triangles' );

	}

	for ( let c = 1; c < offsets.length; c ++ ) {

		if ( offsets[ c ] < offsets[ c - 1 ] ) throw new CollisionTablesError( 'cell_offsets are not a valid index into cell_triangles' );

	}

	for ( let k = 0; k < arrays.cell_triangles.length; k ++ ) {

		if ( arrays.cell_triangles[ k ] >= triangleCount ) throw new CollisionTablesError( 'cell_triangles refers to a triangle that does not exist' );

	}

	for ( const name of [ 'cell_kind', 'voxels' ] ) {

		for ( let k = 0; k < arrays[ name ].length; k ++ ) {

			if ( arrays[ name ][ k ] > 2 ) throw new CollisionTablesError( 'unknown cell kind or voxel class code' );

		}

	}

	const [ nx, ny, nz ] = voxels.shape;
	const bmin = voxels.bounds.min, bmax = voxels.bounds.max;
	return {
		header,
		origin: Float64Array.from( header.origin ),
		floorY: header.floor_y,
		lon0: liner.lon0, lat0: liner.lat0, step: liner.step, invStep: 1 / liner.step, nlon, nlat,
		voxelShape: Int32Array.of( nx, ny, nz ),
		voxelMin: Float64Array.from( bmin ),
		voxelInv: Float64Array.of( nx / ( bmax[ 0 ] - bmin[ 0 ] ), ny / ( bmax[ 1 ] - bmin[ 1 ] ), nz / ( bmax[ 2 ] - bmin[ 2 ] ) ),
		nodeRadius: arrays.node_radius,
		cellKind: arrays.cell_kind,
		cellRmin: arrays.cell_rmin,
		cellRmax: arrays.cell_rmax,
		cellOffsets: arrays.cell_offsets,
		cellTriangles: arrays.cell_triangles,
		triangles: arrays.triangles,
		planes: arrays.planes,
		voxels: arrays.voxels,
	};

}

/**
 * Check the answer of GET /collision/tables ({ format_version, url, ... }) before its binary is
 * downloaded: a server whose tables have another format version is refused here. Returns the
 * answer.
 */
export function checkCollisionTablesInfo( info ) {

	if ( info?.format_version !== COLLISION_TABLES_FORMAT_VERSION ) {

		throw new CollisionTablesError( `the server offers collision tables format version ${ info?.format_version }; ` +
			`this client understands version ${ COLLISION_TABLES_FORMAT_VERSION }` );

	}

	if ( typeof info.url !== 'string' ) throw new CollisionTablesError( 'the collision tables answer has no url' );
	return info;

}
