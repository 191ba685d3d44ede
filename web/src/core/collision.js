// Tongue-palate collision correction, every frame: the JS twin of
// server/glasshead/geometry/collision.py.
//
// Cohen, Beskow and Massaro (1998), part 4: a voxel table screens points, a liner found from the
// point's spherical coordinates about O tests the rest, and a failing point is moved along the
// line toward O onto the surface. The liner cells carry exact bounds and triangles, so the answer
// is that of an exact raycast from O:
//   1. Screen: at or below floorY, or in an ok voxel: outside, no cost (FLAG_SCREENED).
//   2. Test: cell from longitude atan2(dx, dy) and latitude atan2(dz, hypot(dx, dy)); outside the
//      grid, in an empty cell, or nearer than the cell's rmin: outside (FLAG_TESTED). A not-ok
//      voxel skips the rmin comparison and goes straight to correction.
//   3. Correct: PLANE cell: inside when s = n . (P - O) > c (the paper's dot product with the
//      normal), moved to O + (P - O) c / s. LIST cell: two-sided Moller-Trumbore (1997) over the
//      cell's triangles gives the first hit t on O -> P; inside when t < 1, moved to O + t (P - O)
//      (FLAG_CORRECTED).
// The arithmetic follows the Python twin operation by operation (float64 on float32 table
// values), so both give the same flags; tests/vectors/collision-*.json prove it.

import {
	CELL_LIST, CELL_PLANE, COLLISION_TOL, FLAG_CORRECTED, FLAG_SCREENED, FLAG_TESTED,
	VOXEL_NOT_OK, VOXEL_OK,
} from './constants.js';

/** Index of each count in the `stats` target of correctVertices. */
export const STAT_SCREENED = 0;
export const STAT_TESTED = 1;
export const STAT_CORRECTED = 2;

const BARY = COLLISION_TOL.barycentric;

/**
 * The ray's direction in, the first hit out: a called function boxes every floating-point argument
 * and return value on the heap, so firstHit passes them here to allocate nothing per vertex.
 */
const RAY = new Float64Array( 4 );
const RAY_T = 0, RAY_DX = 1, RAY_DY = 2, RAY_DZ = 3;

/**
 * First hit t > 0 of the ray O + t (dx, dy, dz) over the triangles of one liner cell (two-sided
 * Moller-Trumbore), written to RAY[ RAY_T ]; Infinity when none is hit. (dx, dy, dz) is read from
 * RAY[ RAY_DX .. RAY_DZ ].
 */
function firstHit( tables, cell ) {

	const dx = RAY[ RAY_DX ], dy = RAY[ RAY_DY ], dz = RAY[ RAY_DZ ];
	const tri = tables.triangles, list = tables.cellTriangles;
	const end = tables.cellOffsets[ cell + 1 ];
	let best = Infinity;
	for ( let k = tables.cellOffsets[ cell ]; k < end; k ++ ) {

		const o = list[ k ] * 9;
		const ax = tri[ o ], ay = tri[ o + 1 ], az = tri[ o + 2 ];
		const e1x = tri[ o + 3 ], e1y = tri[ o + 4 ], e1z = tri[ o + 5 ];
		const e2x = tri[ o + 6 ], e2y = tri[ o + 7 ], e2z = tri[ o + 8 ];
		const hx = dy * e2z - dz * e2y;
		const hy = dz * e2x - dx * e2z;
		const hz = dx * e2y - dy * e2x;
		const det = e1x * hx + e1y * hy + e1z * hz;
		if ( det === 0 ) continue;
		const inv = 1 / det;
		const sx = - ax, sy = - ay, sz = - az;
		const u = ( sx * hx + sy * hy + sz * hz ) * inv;
		if ( ! ( u >= - BARY ) ) continue;
		const qx = sy * e1z - sz * e1y;
		const qy = sz * e1x - sx * e1z;
		const qz = sx * e1y - sy * e1x;
		const v = ( dx * qx + dy * qy + dz * qz ) * inv;
		if ( ! ( v >= - BARY ) || ! ( u + v <= 1 + BARY ) ) continue;
		const t = ( e2x * qx + e2y * qy + e2z * qz ) * inv;
		if ( t > 0 && t < best ) best = t;

	}

	RAY[ RAY_T ] = best;

}

/**
 * Correct tongue vertices in place against the collision tables.
 *
 * positions: Float32Array (or Float64Array) of 3 * count coordinates, project frame (mm); vertices
 *   inside the palate or teeth are moved onto the surface, the others are left untouched.
 * tables: the result of decodeCollisionTables.
 * flags: Uint8Array (count) written with FLAG_SCREENED / FLAG_TESTED / FLAG_CORRECTED, or null.
 * stats: Int32Array (3) or null, written with screened, tested and corrected counts.
 * Returns the number of corrected vertices. Allocates nothing.
 */
export function correctVertices( positions, count, tables, flags, stats ) {

	const ox = tables.origin[ 0 ], oy = tables.origin[ 1 ], oz = tables.origin[ 2 ];
	const floorY = tables.floorY;
	const vmx = tables.voxelMin[ 0 ], vmy = tables.voxelMin[ 1 ], vmz = tables.voxelMin[ 2 ];
	const vix = tables.voxelInv[ 0 ], viy = tables.voxelInv[ 1 ], viz = tables.voxelInv[ 2 ];
	const nx = tables.voxelShape[ 0 ], ny = tables.voxelShape[ 1 ], nz = tables.voxelShape[ 2 ];
	const voxels = tables.voxels, kinds = tables.cellKind, rmins = tables.cellRmin;
	const offsets = tables.cellOffsets, list = tables.cellTriangles, planes = tables.planes;
	const lon0 = tables.lon0, lat0 = tables.lat0, invStep = tables.invStep;
	const nlon = tables.nlon, nlat = tables.nlat;
	let tested = 0, corrected = 0;

	for ( let v = 0; v < count; v ++ ) {

		const i3 = 3 * v;
		const x = positions[ i3 ], y = positions[ i3 + 1 ], z = positions[ i3 + 2 ];

		// 1. Screen.
		let cls = 1; // borderline outside the voxel grid
		if ( y <= floorY ) {

			cls = VOXEL_OK;

		} else {

			const ix = Math.floor( ( x - vmx ) * vix ), iy = Math.floor( ( y - vmy ) * viy ), iz = Math.floor( ( z - vmz ) * viz );
			if ( ix >= 0 && ix < nx && iy >= 0 && iy < ny && iz >= 0 && iz < nz ) cls = voxels[ ( ix * ny + iy ) * nz + iz ];

		}

		if ( cls === VOXEL_OK ) {

			if ( flags !== null ) flags[ v ] = FLAG_SCREENED;
			continue;

		}

		// 2. Test against the liner cell of the point's direction.
		tested ++;
		if ( flags !== null ) flags[ v ] = FLAG_TESTED;
		const px = x - ox, py = y - oy, pz = z - oz;
		const rho2 = px * px + py * py;
		const i = Math.floor( ( Math.atan2( px, py ) - lon0 ) * invStep );
		const j = Math.floor( ( Math.atan2( pz, Math.sqrt( rho2 ) ) - lat0 ) * invStep );
		if ( i < 0 || i >= nlon || j < 0 || j >= nlat ) continue;
		const cell = j * nlon + i;
		if ( cls !== VOXEL_NOT_OK ) {

			const rmin = rmins[ cell ];
			if ( rho2 + pz * pz < rmin * rmin ) continue;

		}

		// 3. Correct.
		const kind = kinds[ cell ];
		let t = Infinity;
		if ( kind === CELL_PLANE ) {

			const o = list[ offsets[ cell ] ] * 4;
			const s = planes[ o ] * px + planes[ o + 1 ] * py + planes[ o + 2 ] * pz;
			if ( s > planes[ o + 3 ] ) t = planes[ o + 3 ] / s;

		} else if ( kind === CELL_LIST ) {

			RAY[ RAY_DX ] = px; RAY[ RAY_DY ] = py; RAY[ RAY_DZ ] = pz;
			firstHit( tables, cell );
			t = RAY[ RAY_T ];

		}

		if ( t < 1 ) {

			positions[ i3 ] = ox + px * t;
			positions[ i3 + 1 ] = oy + py * t;
			positions[ i3 + 2 ] = oz + pz * t;
			if ( flags !== null ) flags[ v ] = FLAG_CORRECTED;
			corrected ++;

		}

	}

	if ( stats !== null ) {

		stats[ STAT_SCREENED ] = count;
		stats[ STAT_TESTED ] = tested;
		stats[ STAT_CORRECTED ] = corrected;

	}

	return corrected;

}
