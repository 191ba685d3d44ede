// Tongue collision with the vocal tract behind the palate: the velum (soft palate), posed by
// velum_opening, and the posterior pharyngeal wall. Twin of
// server/glasshead/geometry/tract_collision.py; tests/vectors/tract-collision.json keeps the two
// in agreement (docs/collision.md, "The velum and the pharyngeal wall").
//
// "Inside" is defined as for the palate, from a fixed origin T in the mouth (tractOrigin): a
// tongue vertex P is inside when the segment T -> P crosses a tract triangle (either side) before
// reaching P, and it is moved back along that segment onto the first crossing. Exact: the first
// crossing is found by two-sided Moller-Trumbore (1997) over every triangle the segment can
// meet, found through a bounding-volume hierarchy (BVH) built once on the mesh's fixed topology.
//
// The velum moves, but as a blend of measured poses: a vertex at share u between poses A and B
// lies at A (1 - u) + B u, so a node's box at u lies inside its box in A times (1 - u) plus its
// box in B times u (the minimum of a sum is at least the sum of the minima). Each node keeps its
// box in every pose, and a query blends the two it needs: no refit per frame, and the boxes stay
// tight at the measured poses. Boxes are widened by COLLISION_TOL.length, far beyond rounding.
//
// createTractCollider() allocates everything once; correctTract() allocates nothing.

import { COLLISION_TOL, FLAG_CORRECTED, FLAG_SCREENED, FLAG_TESTED, TRACT_ORIGIN_AHEAD_MM } from './constants.js';
import { STAT_CORRECTED, STAT_SCREENED, STAT_TESTED } from './collision.js';
import { createDepthScreen, screenTable } from './tractScreen.js';

/** Triangles per BVH leaf. */
const LEAF_SIZE = 4;
const PAD = COLLISION_TOL.length;
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
 *   mesh: name, triangles, positions (the current pose, set by setTractPose), the BVH and its
 *   boxes per pose, relative to T), and scratch
 */
export function createTractCollider( origin, meshes ) {

	let screenX = - Infinity;
	const built = meshes.map( ( { name, poses, triangles } ) => {

		if ( ! poses.length || poses.some( ( p ) => p.length !== poses[ 0 ].length ) ) throw new Error( `tract mesh ${ name } needs poses of one vertex count` );
		for ( const pose of poses ) for ( let i = 0; i < pose.length; i += 3 ) screenX = Math.max( screenX, pose[ i ] );
		const bvh = buildBvh( poses[ 0 ], triangles );
		const boxes = poses.map( ( pose ) => nodeBoxes( bvh, pose, triangles, origin ) );
		return { name, triangles, positions: poses[ 0 ], ...bvh, boxes, pose: new Float64Array( 2 ) };

	} );
	if ( ! ( origin[ 0 ] >= screenX ) ) throw new Error( `the tract origin x = ${ origin[ 0 ] } mm lies behind a tract mesh (front ${ screenX } mm)` );
	const depth = Math.max( ...built.map( ( m ) => m.depth ) );
	return {
		origin: Float64Array.from( origin ),
		screenX,
		meshes: built,
		/** The depth tables of the screen (tractScreen.js). */
		screen: createDepthScreen( origin, meshes ),
		/** Scratch: the stack of a BVH walk, and the ray (t, dx, dy, dz). */
		stack: new Int32Array( 2 * depth + 2 ),
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
	if ( ! ( first >= 0 && first <= Math.max( 0, mesh.boxes.length - 2 ) && share >= 0 && share <= 1 ) ) throw new RangeError( `tract mesh ${ mesh.name }: pose ${ first } at share ${ share } does not exist` );
	mesh.positions = positions;
	mesh.pose[ 0 ] = first;
	mesh.pose[ 1 ] = share;

}

// Median split of the triangles' centroids along the longest side of their box, down to
// LEAF_SIZE triangles; nodes in depth-first order, a node's left child right after it.
function buildBvh( positions, triangles ) {

	const count = triangles.length / 3;
	const order = new Uint32Array( count );
	const centroid = new Float64Array( 3 * count );
	for ( let t = 0; t < count; t ++ ) {

		order[ t ] = t;
		for ( let c = 0; c < 3; c ++ ) {

			centroid[ 3 * t + c ] = ( positions[ 3 * triangles[ 3 * t ] + c ] + positions[ 3 * triangles[ 3 * t + 1 ] + c ] + positions[ 3 * triangles[ 3 * t + 2 ] + c ] ) / 3;

		}

	}

	const start = [], size = [], right = [], axes = [];
	let depth = 0;
	function split( from, to, level ) {

		const node = start.length;
		start.push( from );
		size.push( 0 );
		right.push( - 1 );
		axes.push( 0 );
		depth = Math.max( depth, level );
		if ( to - from <= LEAF_SIZE ) {

			size[ node ] = to - from;
			return node;

		}

		const lo = [ Infinity, Infinity, Infinity ], hi = [ - Infinity, - Infinity, - Infinity ];
		for ( let k = from; k < to; k ++ ) {

			for ( let c = 0; c < 3; c ++ ) {

				lo[ c ] = Math.min( lo[ c ], centroid[ 3 * order[ k ] + c ] );
				hi[ c ] = Math.max( hi[ c ], centroid[ 3 * order[ k ] + c ] );

			}

		}

		const axis = [ 0, 1, 2 ].reduce( ( best, c ) => ( hi[ c ] - lo[ c ] > hi[ best ] - lo[ best ] ? c : best ), 0 );
		axes[ node ] = axis;
		const part = Array.from( order.subarray( from, to ) ).sort( ( p, q ) => centroid[ 3 * p + axis ] - centroid[ 3 * q + axis ] || p - q );
		order.set( part, from );
		const middle = ( from + to ) >> 1;
		split( from, middle, level + 1 );
		right[ node ] = split( middle, to, level + 1 );
		return node;

	}

	split( 0, count, 0 );
	return { order, nodeStart: Int32Array.from( start ), nodeSize: Int32Array.from( size ), nodeRight: Int32Array.from( right ), nodeAxis: Uint8Array.from( axes ), depth };

}

// Each node's box (min xyz, max xyz, relative to T, widened by PAD) in one pose, children first.
function nodeBoxes( bvh, positions, triangles, origin ) {

	const nodes = bvh.nodeStart.length;
	const boxes = new Float64Array( 6 * nodes );
	for ( let n = nodes - 1; n >= 0; n -- ) {

		const o = 6 * n;
		boxes.fill( Infinity, o, o + 3 );
		boxes.fill( - Infinity, o + 3, o + 6 );
		if ( bvh.nodeSize[ n ] > 0 ) {

			for ( let k = bvh.nodeStart[ n ]; k < bvh.nodeStart[ n ] + bvh.nodeSize[ n ]; k ++ ) {

				for ( let corner = 0; corner < 3; corner ++ ) {

					const p = 3 * triangles[ 3 * bvh.order[ k ] + corner ];
					for ( let c = 0; c < 3; c ++ ) {

						const value = positions[ p + c ] - origin[ c ];
						boxes[ o + c ] = Math.min( boxes[ o + c ], value );
						boxes[ o + 3 + c ] = Math.max( boxes[ o + 3 + c ], value );

					}

				}

			}

			// Widened once, at the leaves: a parent's union of its children is widened too.
			for ( let c = 0; c < 3; c ++ ) {

				boxes[ o + c ] -= PAD;
				boxes[ o + 3 + c ] += PAD;

			}

		} else {

			const l = 6 * ( n + 1 ), r = 6 * bvh.nodeRight[ n ];
			for ( let c = 0; c < 3; c ++ ) {

				boxes[ o + c ] = Math.min( boxes[ l + c ], boxes[ r + c ] );
				boxes[ o + 3 + c ] = Math.max( boxes[ l + 3 + c ], boxes[ r + 3 + c ] );

			}

		}

	}

	return boxes;

}

// The first crossing t in (0, ray[0]) of the segment T + t (dx, dy, dz) with the mesh at its
// current pose, written to ray[0] when one is nearer (ray = [t, dx, dy, dz]).
function meshFirstHit( collider, mesh ) {

	const ray = collider.ray, stack = collider.stack;
	const dx = ray[ 1 ], dy = ray[ 2 ], dz = ray[ 3 ];
	const ix = 1 / dx, iy = 1 / dy, iz = 1 / dz;
	const first = mesh.pose[ 0 ], u = mesh.pose[ 1 ], w = 1 - u;
	const a = mesh.boxes[ first ], b = mesh.boxes[ Math.min( first + 1, mesh.boxes.length - 1 ) ];
	const ox = collider.origin[ 0 ], oy = collider.origin[ 1 ], oz = collider.origin[ 2 ];
	const pos = mesh.positions, tri = mesh.triangles, order = mesh.order;
	const starts = mesh.nodeStart, sizes = mesh.nodeSize, rights = mesh.nodeRight, axes = mesh.nodeAxis;
	let best = ray[ 0 ];
	let top = 0;
	stack[ top ++ ] = 0;
	while ( top > 0 ) {

		const node = stack[ -- top ];
		const o = 6 * node;
		// Slab test of the segment against the node's box blended to this pose; an axis the
		// segment runs parallel to gives infinite or NaN bounds, which the comparisons reject
		// or pass as the point's side of the slab decides.
		let t0 = 0, t1 = best;
		let lo = a[ o ] * w + b[ o ] * u, hi = a[ o + 3 ] * w + b[ o + 3 ] * u;
		if ( dx === 0 ) {

			if ( lo > 0 || hi < 0 ) continue;

		} else {

			const p = lo * ix, q = hi * ix;
			t0 = Math.max( t0, Math.min( p, q ) );
			t1 = Math.min( t1, Math.max( p, q ) );

		}

		lo = a[ o + 1 ] * w + b[ o + 1 ] * u;
		hi = a[ o + 4 ] * w + b[ o + 4 ] * u;
		if ( dy === 0 ) {

			if ( lo > 0 || hi < 0 ) continue;

		} else {

			const p = lo * iy, q = hi * iy;
			t0 = Math.max( t0, Math.min( p, q ) );
			t1 = Math.min( t1, Math.max( p, q ) );

		}

		lo = a[ o + 2 ] * w + b[ o + 2 ] * u;
		hi = a[ o + 5 ] * w + b[ o + 5 ] * u;
		if ( dz === 0 ) {

			if ( lo > 0 || hi < 0 ) continue;

		} else {

			const p = lo * iz, q = hi * iz;
			t0 = Math.max( t0, Math.min( p, q ) );
			t1 = Math.min( t1, Math.max( p, q ) );

		}

		if ( t0 > t1 ) continue;
		const size = sizes[ node ];
		if ( size === 0 ) {

			// The child nearer along the ray first (left holds the lower coordinates on the split
			// axis): a crossing found there shortens the segment the other must meet.
			const axis = axes[ node ];
			if ( ( axis === 0 ? dx : axis === 1 ? dy : dz ) >= 0 ) {

				stack[ top ++ ] = rights[ node ];
				stack[ top ++ ] = node + 1;

			} else {

				stack[ top ++ ] = node + 1;
				stack[ top ++ ] = rights[ node ];

			}
			continue;

		}

		for ( let k = starts[ node ], end = starts[ node ] + size; k < end; k ++ ) {

			// Two-sided Moller-Trumbore relative to T, as firstHit in collision.js and
			// collision_exact.ray_triangle_hits compute it.
			const f = 3 * order[ k ];
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
	const table = moving === null ? screen.tables[ 0 ] : screenTable( screen, moving[ 0 ], moving[ 1 ] );
	const a0 = screen.a0, b0 = screen.b0, inv = screen.inv, na = screen.na, nb = screen.nb;
	let tested = 0, corrected = 0;
	for ( let v = 0; v < count; v ++ ) {

		const i3 = 3 * v;
		const x = positions[ i3 ];
		// Screen: in front of every tract mesh (T is too), outside the tables' grid, or shallower
		// than every tract hull in the vertex's direction (tractScreen.js).
		let screened = x >= screenX;
		const px = x - ox, py = positions[ i3 + 1 ] - oy, pz = positions[ i3 + 2 ] - oz;
		if ( ! screened ) {

			const depth = - px;
			const i = Math.floor( ( py / depth - a0 ) * inv ), j = Math.floor( ( pz / depth - b0 ) * inv );
			screened = i < 0 || i >= na || j < 0 || j >= nb || depth < table[ j * na + i ];

		}

		if ( screened ) {

			if ( flags !== null ) flags[ v ] = FLAG_SCREENED;
			continue;

		}

		tested ++;
		ray[ 0 ] = 1;
		ray[ 1 ] = px; ray[ 2 ] = py; ray[ 3 ] = pz;
		for ( let m = 0; m < meshes.length; m ++ ) meshFirstHit( collider, meshes[ m ] );
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
