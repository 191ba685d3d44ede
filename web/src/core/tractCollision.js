// Tongue collision with the vocal tract behind the palate: the velum (soft palate), posed by
// velum_opening, and the posterior pharyngeal wall. Twin of
// server/glasshead/geometry/tract_collision.py; tests/vectors/tract-collision.json keeps the two
// in agreement (docs/collision.md, "The velum and the pharyngeal wall").
//
// "Inside" is defined as for the palate, from a fixed origin T in the mouth (tractOrigin): a
// tongue vertex P is inside when the segment T -> P crosses a tract triangle (either side) before
// reaching P, and it is moved back along that segment onto the first crossing. Exact: the first
// crossing is found by two-sided Moller-Trumbore (1997) over every triangle the segment can
// meet. Those are listed once, at load, per cell of directions from T (tractScreen.js): the
// segment T -> P lies in P's direction alone, and a triangle of the moving velum stays, over each
// share interval between its measured poses, inside the hull its corners sweep, whose projection
// the lists cover. So a frame tests each tongue vertex that the depth screen lets through against
// its cell's few triangles, at their current positions, with no search structure to update.
//
// createTractCollider() allocates everything once; correctTract() allocates nothing.

import { COLLISION_TOL, FLAG_CORRECTED, FLAG_SCREENED, FLAG_TESTED, TRACT_ORIGIN_AHEAD_MM } from './constants.js';
import { STAT_CORRECTED, STAT_SCREENED, STAT_TESTED } from './collision.js';
import { createDepthScreen, ensureInterval, screenInterval } from './tractScreen.js';

const BARY = COLLISION_TOL.barycentric;

/**
 * The origin T of the tract collision (twin of tract_collision.tract_origin): in the mid-sagittal
 * plane, TRACT_ORIGIN_AHEAD_MM in front of the velum's most anterior point and at the height of
 * its lowest point, over every pose. From there the velum's oral surface and the pharyngeal wall
 * are seen from the front, and no tract mesh lies in front of T (the screen of correctTract).
 * @param {Float32Array[]} velumPoses positions (xyz per vertex, mm) of each measured pose
 * @returns {Float64Array} T (3)
 */
export function tractOrigin( velumPoses ) {

	let front = - Infinity, low = Infinity;
	for ( const pose of velumPoses ) {

		for ( let i = 0; i < pose.length; i += 3 ) {

			if ( pose[ i ] > front ) front = pose[ i ];
			if ( pose[ i + 1 ] < low ) low = pose[ i + 1 ];

		}

	}

	return Float64Array.of( front + TRACT_ORIGIN_AHEAD_MM, low, 0 );

}

/**
 * Build the collider once.
 * @param {Float64Array} origin T, from tractOrigin()
 * @param {{ name: string, poses: Float32Array[], triangles: Uint32Array }[]} meshes each tract
 *   mesh with its positions in every measured pose (one pose for a mesh that does not move) and
 *   its triangles
 * @returns {object} the collider: origin, screenX (no mesh reaches in front of it), meshes (per
 *   mesh: name, triangles, positions (the current pose, set by setTractPose), its pose count and
 *   current pose), the screen with its tables and cell lists, and scratch
 */
export function createTractCollider( origin, meshes ) {

	let screenX = - Infinity;
	const built = meshes.map( ( { name, poses, triangles } ) => {

		if ( ! poses.length || poses.some( ( p ) => p.length !== poses[ 0 ].length ) ) throw new Error( `tract mesh ${ name } needs poses of one vertex count` );
		for ( const pose of poses ) for ( let i = 0; i < pose.length; i += 3 ) screenX = Math.max( screenX, pose[ i ] );
		return { name, triangles, positions: poses[ 0 ], poseCount: poses.length, pose: new Float64Array( 2 ) };

	} );
	if ( ! ( origin[ 0 ] >= screenX ) ) throw new Error( `the tract origin x = ${ origin[ 0 ] } mm lies behind a tract mesh (front ${ screenX } mm)` );
	return {
		origin: Float64Array.from( origin ),
		screenX,
		meshes: built,
		/** The depth tables and cell lists of the screen (tractScreen.js). */
		screen: createDepthScreen( origin, meshes ),
		/** Scratch: the ray (t, dx, dy, dz). */
		ray: new Float64Array( 4 ),
	};

}

/**
 * Tell the collider where a mesh is this frame: its positions (the array the scene shows) lie at
 * share u between measured poses first and first + 1 (u = 0 and first = 0 for a still mesh).
 */
export function setTractPose( collider, meshIndex, positions, first, share ) {

	const mesh = collider.meshes[ meshIndex ];
	if ( positions.length !== mesh.positions.length ) throw new Error( `tract mesh ${ mesh.name }: ${ positions.length / 3 } vertices, expected ${ mesh.positions.length / 3 }` );
	if ( ! ( first >= 0 && first <= Math.max( 0, mesh.poseCount - 2 ) && share >= 0 && share <= 1 ) ) throw new RangeError( `tract mesh ${ mesh.name }: pose ${ first } at share ${ share } does not exist` );
	mesh.positions = positions;
	mesh.pose[ 0 ] = first;
	mesh.pose[ 1 ] = share;

}

// The first crossing t in (0, ray[0]) of the segment T + t (dx, dy, dz) with the triangles of one
// mesh listed in `cell`, written to ray[0] when one is nearer (ray = [t, dx, dy, dz]).
function cellFirstHit( collider, mesh, list, cell ) {

	const ray = collider.ray;
	const dx = ray[ 1 ], dy = ray[ 2 ], dz = ray[ 3 ];
	const ox = collider.origin[ 0 ], oy = collider.origin[ 1 ], oz = collider.origin[ 2 ];
	const pos = mesh.positions, tri = mesh.triangles, items = list.items;
	let best = ray[ 0 ];
	for ( let k = list.offsets[ cell ], end = list.offsets[ cell + 1 ]; k < end; k ++ ) {

		// Two-sided Moller-Trumbore relative to T, as firstHit in collision.js and
		// collision_exact.ray_triangle_hits compute it.
		const f = 3 * items[ k ];
		const pa = 3 * tri[ f ], pb = 3 * tri[ f + 1 ], pc = 3 * tri[ f + 2 ];
		const ax = pos[ pa ] - ox, ay = pos[ pa + 1 ] - oy, az = pos[ pa + 2 ] - oz;
		const e1x = ( pos[ pb ] - ox ) - ax, e1y = ( pos[ pb + 1 ] - oy ) - ay, e1z = ( pos[ pb + 2 ] - oz ) - az;
		const e2x = ( pos[ pc ] - ox ) - ax, e2y = ( pos[ pc + 1 ] - oy ) - ay, e2z = ( pos[ pc + 2 ] - oz ) - az;
		const hx = dy * e2z - dz * e2y;
		const hy = dz * e2x - dx * e2z;
		const hz = dx * e2y - dy * e2x;
		const det = e1x * hx + e1y * hy + e1z * hz;
		if ( det === 0 ) continue;
		const inv = 1 / det;
		const sx = - ax, sy = - ay, sz = - az;
		const bu = ( sx * hx + sy * hy + sz * hz ) * inv;
		if ( ! ( bu >= - BARY ) ) continue;
		const qx = sy * e1z - sz * e1y;
		const qy = sz * e1x - sx * e1z;
		const qz = sx * e1y - sy * e1x;
		const bv = ( dx * qx + dy * qy + dz * qz ) * inv;
		if ( ! ( bv >= - BARY ) || ! ( bu + bv <= 1 + BARY ) ) continue;
		const t = ( e2x * qx + e2y * qy + e2z * qz ) * inv;
		if ( t > 0 && t < best ) best = t;

	}

	ray[ 0 ] = best;

}

/**
 * Correct tongue vertices in place against the tract meshes at their current poses.
 *
 * positions: Float32Array (or Float64Array), 3 * count coordinates (mm), already corrected
 *   against the palate; a vertex whose segment from T crosses a tract triangle is moved onto the
 *   first crossing, every other vertex is left untouched, bit for bit.
 * flags: Uint8Array (count) or null: FLAG_SCREENED (the depth screen of tractScreen.js settles
 *   it), FLAG_TESTED or FLAG_CORRECTED.
 * stats: Int32Array (3) or null: screened (all), tested and corrected counts.
 * Returns the number of corrected vertices. Allocates nothing.
 */
export function correctTract( positions, count, collider, flags, stats ) {

	const ox = collider.origin[ 0 ], oy = collider.origin[ 1 ], oz = collider.origin[ 2 ];
	const screenX = collider.screenX, meshes = collider.meshes, ray = collider.ray;
	const screen = collider.screen;
	const moving = screen.moving >= 0 ? meshes[ screen.moving ].pose : null;
	const interval = moving === null ? 0 : screenInterval( screen, moving[ 0 ], moving[ 1 ] );
	ensureInterval( screen, interval );
	const table = screen.tables[ interval ], lists = screen.lists;
	const a0 = screen.a0, b0 = screen.b0, inv = screen.inv, na = screen.na, nb = screen.nb;
	let tested = 0, corrected = 0;
	for ( let v = 0; v < count; v ++ ) {

		const i3 = 3 * v;
		const x = positions[ i3 ];
		// Screen: in front of every tract mesh (T is too), outside the tables' grid, or shallower
		// than every tract hull in the vertex's direction (tractScreen.js).
		let screened = x >= screenX;
		const px = x - ox, py = positions[ i3 + 1 ] - oy, pz = positions[ i3 + 2 ] - oz;
		let cell = - 1;
		if ( ! screened ) {

			const depth = - px;
			const i = Math.floor( ( py / depth - a0 ) * inv ), j = Math.floor( ( pz / depth - b0 ) * inv );
			cell = j * na + i;
			screened = i < 0 || i >= na || j < 0 || j >= nb || depth < table[ cell ];

		}

		if ( screened ) {

			if ( flags !== null ) flags[ v ] = FLAG_SCREENED;
			continue;

		}

		tested ++;
		ray[ 0 ] = 1;
		ray[ 1 ] = px; ray[ 2 ] = py; ray[ 3 ] = pz;
		for ( let m = 0; m < meshes.length; m ++ ) {

			const perMesh = lists[ m ];
			cellFirstHit( collider, meshes[ m ], perMesh[ perMesh.length === 1 ? 0 : interval ], cell );

		}
		const t = ray[ 0 ];
		if ( t < 1 ) {

			positions[ i3 ] = ox + px * t;
			positions[ i3 + 1 ] = oy + py * t;
			positions[ i3 + 2 ] = oz + pz * t;
			if ( flags !== null ) flags[ v ] = FLAG_CORRECTED;
			corrected ++;

		} else if ( flags !== null ) flags[ v ] = FLAG_TESTED;

	}

	if ( stats !== null ) {

		stats[ STAT_SCREENED ] = count;
		stats[ STAT_TESTED ] = tested;
		stats[ STAT_CORRECTED ] = corrected;

	}

	return corrected;

}
