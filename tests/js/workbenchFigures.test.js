// The collision figures of the workbench (web/src/scene/LinerWireframe.js, VoxelDots.js) from
// the shared collision tables: the liner's lines lie on the rays' first hits, the voxel dots at
// the centres of voxels of their class.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { decodeCollisionTables } from '../../web/src/core/tables.js';
import { VOXEL_BORDER, VOXEL_NOT_OK, VOXEL_OK } from '../../web/src/core/constants.js';
import { LINER_LIFT_MM, LinerWireframe, linerSegments } from '../../web/src/scene/LinerWireframe.js';
import { voxelCentres, VoxelDots } from '../../web/src/scene/VoxelDots.js';

const TABLES = decodeCollisionTables( readFileSync( join( dirname( fileURLToPath( import.meta.url ) ), '..', 'vectors', 'collision-tables.bin' ) ) );

/** Longitude, latitude and radius about O of a point, in the liner's angle convention. */
function spherical( x, y, z ) {

	const [ dx, dy, dz ] = [ x - TABLES.origin[ 0 ], y - TABLES.origin[ 1 ], z - TABLES.origin[ 2 ] ];
	return { theta: Math.atan2( dx, dy ), phi: Math.atan2( dz, Math.hypot( dx, dy ) ), r: Math.hypot( dx, dy, dz ) };

}

test( 'every liner segment joins two neighbouring grid nodes whose rays hit, just in front of the hit', () => {

	const every = 2;
	const segments = linerSegments( TABLES, every );
	assert.ok( segments.length > 0 && segments.length % 6 === 0 );
	const { lon0, lat0, step, nlon } = TABLES;
	for ( let s = 0; s < segments.length; s += 6 ) {

		const ends = [ 0, 3 ].map( ( o ) => spherical( segments[ s + o ], segments[ s + o + 1 ], segments[ s + o + 2 ] ) );
		const nodes = ends.map( ( { theta, phi, r } ) => {

			const i = ( theta - lon0 ) / step;
			const j = ( phi - lat0 ) / step;
			assert.ok( Math.abs( i - Math.round( i ) ) < 1e-3 && Math.abs( j - Math.round( j ) ) < 1e-3, 'an end off the grid' );
			const radius = TABLES.nodeRadius[ Math.round( j ) * ( nlon + 1 ) + Math.round( i ) ];
			assert.ok( Number.isFinite( radius ) );
			assert.ok( Math.abs( r - ( radius - LINER_LIFT_MM ) ) < 1e-3, `an end at ${ r } mm, its ray hits at ${ radius }` );
			return [ Math.round( i ), Math.round( j ) ];

		} );
		const di = Math.abs( nodes[ 0 ][ 0 ] - nodes[ 1 ][ 0 ] );
		const dj = Math.abs( nodes[ 0 ][ 1 ] - nodes[ 1 ][ 1 ] );
		assert.equal( di + dj, 1, 'a segment joins grid neighbours' );
		// A longitude line (constant i) or a latitude line (constant j) that is drawn.
		assert.ok( di === 0 ? nodes[ 0 ][ 0 ] % every === 0 : nodes[ 0 ][ 1 ] % every === 0 );

	}

} );

test( 'drawing fewer grid lines gives fewer segments, and the wireframe starts hidden', () => {

	assert.ok( linerSegments( TABLES, 1 ).length > linerSegments( TABLES, 4 ).length );
	assert.throws( () => linerSegments( TABLES, 0 ), /positive integer/ );
	const wireframe = new LinerWireframe( TABLES, { every: 3 } );
	assert.equal( wireframe.visible, false );
	assert.equal( wireframe.segmentCount, linerSegments( TABLES, 3 ).length / 6 );

} );

test( 'voxel dots sit at the centres of the voxels of their class, every voxel once', () => {

	const [ nx, ny, nz ] = TABLES.voxelShape;
	let total = 0;
	for ( const voxelClass of [ VOXEL_OK, VOXEL_BORDER, VOXEL_NOT_OK ] ) {

		const centres = voxelCentres( TABLES, voxelClass );
		total += centres.length / 3;
		for ( let k = 0; k < centres.length; k += 3 ) {

			const f = [ 0, 1, 2 ].map( ( a ) => ( centres[ k + a ] - TABLES.voxelMin[ a ] ) * TABLES.voxelInv[ a ] );
			f.forEach( ( value ) => assert.ok( Math.abs( value - Math.floor( value ) - 0.5 ) < 1e-3, 'not a voxel centre' ) );
			const [ ix, iy, iz ] = f.map( Math.floor );
			assert.equal( TABLES.voxels[ ( ix * ny + iy ) * nz + iz ], voxelClass );

		}

	}

	assert.equal( total, nx * ny * nz );
	const dots = new VoxelDots( TABLES );
	assert.equal( dots.visible, false );
	assert.equal( dots.counts.ok + dots.counts.borderline + dots.counts[ 'not ok' ], nx * ny * nz );
	assert.equal( dots.children.length, Object.values( dots.counts ).filter( ( n ) => n > 0 ).length, 'no empty point clouds' );

} );
