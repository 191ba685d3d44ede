// The screen of the tract collision (tractCollision.js): which tongue vertices cannot have gone
// into the velum or the pharyngeal wall, for one comparison each.
//
// Every tract point X lies behind the origin T (x < T.x). Seen from T, a direction is the point
// (a, b) = ((y - T.y) / d, (z - T.z) / d) of the central (gnomonic) projection, d = T.x - x the
// depth. A central projection maps a segment to a segment, so the convex hull of some points
// projects into the hull of their projections, and the segment T -> P projects to P's point
// alone. The screen is a grid over (a, b) whose cells hold the smallest depth of any tract hull
// whose projection's box covers the cell: a vertex shallower than its cell's value cannot reach a
// tract triangle, and neither can one outside the grid.
//
// The same cells list the triangles whose hulls cover them (per mesh, and for the moving mesh per
// share interval): the only triangles the segment T -> P of a vertex in that cell can cross, so
// the exact test runs over them alone.
//
// The velum moves, but between two measured poses its vertices move on straight lines, so a
// triangle over a share interval [u0, u1] lies in the hull of its six corners at u0 and u1 (a
// linear map of the box of shares). Each segment between measured poses is cut into
// SCREEN_SUBDIVISIONS intervals, with a table each; the still pharyngeal wall enters every table.
// Values are widened against rounding (the posed velum is stored as float32) by far more than it.

import { COLLISION_TOL } from './constants.js';

/** Intervals per segment between two measured velum poses, each with its own depth table. */
export const SCREEN_SUBDIVISIONS = 4;
/** Cell size of the depth tables, in projected units (mm across per mm of depth). */
export const SCREEN_CELL = 0.025;
/** Widening of each hull's projected box, projected units: float32 posing moves a point by 1e-7. */
const WIDEN = 1e-6;
/** Lowering of each depth bound, mm: float32 posing and storage are off by a few 1e-6 mm. */
const LOWER = 100 * COLLISION_TOL.length;

/**
 * Build the depth tables for tract meshes seen from T.
 * @param {Float64Array} origin T
 * @param {{ poses: Float32Array[], triangles: Uint32Array }[]} meshes at most one with several
 *   poses (the velum); every vertex behind T (x < T.x)
 * @returns {object} { a0, b0, inv, na, nb, tables: Float32Array[] (one per interval, null until
 *   ensureInterval() builds it), moving:
 *   the index of the moving mesh or -1, lists: per mesh, per interval (one for a still mesh),
 *   { offsets: Uint32Array( cells + 1 ), items: triangle indices } }
 */
export function createDepthScreen( origin, meshes ) {

	const moving = meshes.findIndex( ( m ) => m.poses.length > 1 );
	if ( meshes.filter( ( m ) => m.poses.length > 1 ).length > 1 ) throw new Error( 'the tract screen takes one moving mesh' );
	const intervals = moving < 0 ? 1 : ( meshes[ moving ].poses.length - 1 ) * SCREEN_SUBDIVISIONS;
	const [ tx, ty, tz ] = origin;
	let aLo = Infinity, aHi = - Infinity, bLo = Infinity, bHi = - Infinity;
	for ( const { poses } of meshes ) {

		for ( const pose of poses ) {

			for ( let i = 0; i < pose.length; i += 3 ) {

				const d = tx - pose[ i ];
				if ( ! ( d > 0 ) ) throw new Error( `a tract vertex lies at or in front of the origin (x = ${ pose[ i ] } mm)` );
				const a = ( pose[ i + 1 ] - ty ) / d, b = ( pose[ i + 2 ] - tz ) / d;
				aLo = Math.min( aLo, a ); aHi = Math.max( aHi, a );
				bLo = Math.min( bLo, b ); bHi = Math.max( bHi, b );

			}

		}

	}

	const inv = 1 / SCREEN_CELL;
	const a0 = aLo - 2 * SCREEN_CELL, b0 = bLo - 2 * SCREEN_CELL;
	const na = Math.ceil( ( aHi - a0 ) * inv ) + 2, nb = Math.ceil( ( bHi - b0 ) * inv ) + 2;
	const screen = { a0, b0, inv, na, nb, tables: [], moving, lists: meshes.map( () => [] ) };
	const still = new Float32Array( na * nb ).fill( Infinity );
	const corners = new Float64Array( 18 );
	meshes.forEach( ( { poses, triangles }, m ) => {

		if ( m === moving ) return;
		const pairs = [];
		for ( let f = 0; f < triangles.length; f += 3 ) {

			for ( let c = 0; c < 3; c ++ ) for ( let k = 0; k < 3; k ++ ) corners[ 3 * c + k ] = poses[ 0 ][ 3 * triangles[ f + c ] + k ];
			markHull( screen, still, origin, corners, 3, f / 3, pairs );

		}

		screen.lists[ m ].push( cellLists( pairs, na * nb, triangles.length / 3 ) );

	} );
	screen.tables = new Array( intervals ).fill( null );
	if ( moving < 0 ) screen.tables[ 0 ] = still;
	else screen.lists[ moving ] = new Array( intervals ).fill( null );
	// The moving mesh's intervals are built when first needed (a new opening range), not at load.
	screen.build = ( interval ) => buildInterval( screen, interval, still, origin, meshes[ moving ], corners );
	return screen;

}

/** Make sure the table and lists of `interval` exist (built once; a frame then allocates none). */
export function ensureInterval( screen, interval ) {

	if ( screen.tables[ interval ] === null ) screen.build( interval );

}

// The depth table and cell lists of one share interval of the moving mesh.
function buildInterval( screen, interval, still, origin, { poses, triangles }, corners ) {

	const table = still.slice();
	const first = Math.floor( interval / SCREEN_SUBDIVISIONS );
	const step = interval % SCREEN_SUBDIVISIONS;
	const u0 = step / SCREEN_SUBDIVISIONS, u1 = ( step + 1 ) / SCREEN_SUBDIVISIONS;
	const a = poses[ first ], b = poses[ first + 1 ];
	const pairs = [];
	for ( let f = 0; f < triangles.length; f += 3 ) {

		for ( let c = 0; c < 3; c ++ ) {

			const p = 3 * triangles[ f + c ];
			for ( let k = 0; k < 3; k ++ ) {

				corners[ 3 * c + k ] = a[ p + k ] * ( 1 - u0 ) + b[ p + k ] * u0;
				corners[ 9 + 3 * c + k ] = a[ p + k ] * ( 1 - u1 ) + b[ p + k ] * u1;

			}

		}

		markHull( screen, table, origin, corners, 6, f / 3, pairs );

	}

	screen.lists[ screen.moving ][ interval ] = cellLists( pairs, screen.na * screen.nb, triangles.length / 3 );
	screen.tables[ interval ] = table;

}

// Lower the cells under the projected box of `count` points to their smallest depth, and list
// triangle `id` in each of them (pairs: cell, id, ...).
function markHull( screen, table, origin, corners, count, id, pairs ) {

	let aLo = Infinity, aHi = - Infinity, bLo = Infinity, bHi = - Infinity, depth = Infinity;
	for ( let c = 0; c < count; c ++ ) {

		const d = origin[ 0 ] - corners[ 3 * c ];
		const a = ( corners[ 3 * c + 1 ] - origin[ 1 ] ) / d, b = ( corners[ 3 * c + 2 ] - origin[ 2 ] ) / d;
		aLo = Math.min( aLo, a ); aHi = Math.max( aHi, a );
		bLo = Math.min( bLo, b ); bHi = Math.max( bHi, b );
		depth = Math.min( depth, d );

	}

	const { a0, b0, inv, na } = screen;
	const i0 = Math.floor( ( aLo - WIDEN - a0 ) * inv ), i1 = Math.floor( ( aHi + WIDEN - a0 ) * inv );
	const j0 = Math.floor( ( bLo - WIDEN - b0 ) * inv ), j1 = Math.floor( ( bHi + WIDEN - b0 ) * inv );
	const bound = Math.fround( depth - LOWER );
	for ( let j = j0; j <= j1; j ++ ) {

		for ( let i = i0; i <= i1; i ++ ) {

			const cell = j * na + i;
			if ( bound < table[ cell ] ) table[ cell ] = bound;
			pairs.push( cell, id );

		}

	}

}

// CSR lists of (cell, id) pairs: offsets per cell, the ids in the order they were marked.
function cellLists( pairs, cells, ids ) {

	const offsets = new Uint32Array( cells + 1 );
	for ( let k = 0; k < pairs.length; k += 2 ) offsets[ pairs[ k ] + 1 ] ++;
	for ( let c = 0; c < cells; c ++ ) offsets[ c + 1 ] += offsets[ c ];
	const items = ids <= 65536 ? new Uint16Array( pairs.length / 2 ) : new Uint32Array( pairs.length / 2 );
	const fill = offsets.slice( 0, cells );
	for ( let k = 0; k < pairs.length; k += 2 ) items[ fill[ pairs[ k ] ] ++ ] = pairs[ k + 1 ];
	return { offsets, items };

}

/** The index of the table (and lists) for the moving mesh at share `share` after pose `first`. */
export function screenInterval( screen, first, share ) {

	if ( screen.moving < 0 ) return 0;
	const step = Math.min( Math.floor( share * SCREEN_SUBDIVISIONS ), SCREEN_SUBDIVISIONS - 1 );
	return first * SCREEN_SUBDIVISIONS + step;

}

/** The depth table for the moving mesh at share `share` after measured pose `first`. */
export function screenTable( screen, first, share ) {

	const interval = screenInterval( screen, first, share );
	ensureInterval( screen, interval );
	return screen.tables[ interval ];

}
