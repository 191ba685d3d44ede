// First crossings of rays from one origin with a triangle mesh: the paper's ray error (Cohen,
// Beskow and Massaro 1998, part 5), for the workbench's overlay of an observation. For each
// observed point P the ray O + t (P - O), t > 0, first crosses the posed tongue at Q; the error
// vector is P -> Q and its signed length (t - 1) |P - O| (positive when the tongue lies beyond P).
// The Python twin of the same error is server/glasshead/fitting/objective3d.py (RayError3D).
//
// The rays never move while an observation is shown, the tongue does with every change of a
// slider, so everything about the rays is built once (createRayFan) and a call (rayFirstHits)
// visits each triangle once. The directions about O are split by a cube map: a direction
// belongs to the face of its largest component (+x, -x, +y, -y, +z, -z) and, on that face, to
// the cell of its gnomonic coordinates (the other two components over the largest one, in
// [-1, 1]) on an N x N grid. A triangle is clipped to each face's pyramid about O (where that
// face's rays point); the clipped polygon's gnomonic bounding box, widened by PAD, names the
// cells whose rays can cross it, and only those rays are tested. A central projection keeps
// straight edges straight, so the box covers the triangle's whole shadow: nothing that could hit
// is skipped and the answer is the brute force's, bit for bit (the same test, pair by pair).
// A triangle whose corners all lie strictly inside one face's pyramid (most of them) needs no
// clipping. Allocates nothing per call.
//
// The test is two-sided Moller and Trumbore (1997), "Fast, minimum storage ray-triangle
// intersection", with the collision kernels' barycentric slack, as firstHit in collision.js.

import { COLLISION_TOL } from './constants.js';

/** Barycentric slack of the ray-triangle test (the collision kernels' own). */
const SLACK = COLLISION_TOL.barycentric;
/** Gnomonic units. Boxes are widened by this so that culling never drops a hit the slack accepts. */
const PAD = 1e-6;
/** Cells along each edge of a cube face. */
export const FAN_CELLS = 32;
/** The six faces: axis 0, 1, 2 (x, y, z), positive then negative. */
const FACES = 6;
/** Most vertices a triangle clipped by four planes can have. */
const MAX_POLYGON = 7;

/** The other two axes (u, v) of each axis. */
const U_AXIS = Object.freeze( [ 1, 0, 0 ] );
const V_AXIS = Object.freeze( [ 2, 2, 1 ] );

/**
 * The cube face of direction (x, y, z): 2 * axis of the largest |component| (the first on a
 * tie), + 1 when that component is negative; -1 for the zero vector.
 */
export function faceOf( x, y, z ) {

	const ax = Math.abs( x ), ay = Math.abs( y ), az = Math.abs( z );
	if ( ax >= ay && ax >= az ) return ax === 0 ? - 1 : ( x > 0 ? 0 : 1 );
	if ( ay >= az ) return y > 0 ? 2 : 3;
	return z > 0 ? 4 : 5;

}

function cellIndex( g, n ) {

	const i = Math.floor( ( g + 1 ) * 0.5 * n );
	return i < 0 ? 0 : i >= n ? n - 1 : i;

}

/**
 * Everything about a set of rays from one origin that does not depend on the mesh, with the
 * scratch arrays of rayFirstHits.
 * @param {ArrayLike<number>} origin O, xyz (mm)
 * @param {ArrayLike<number>} points the rays' points P, xyz per point (Float32Array, Float64Array
 *   or an array); the ray of point k is O + t (P_k - O)
 * @param {{ count?: number, cells?: number }} [options] `count` of points (default: all)
 * @returns {{ origin: Float64Array, count: number, directions: Float64Array, lengths: Float64Array,
 *   cells: number, cellOffsets: Int32Array, cellRays: Int32Array, faceRays: Int32Array }}
 *   directions P - O (xyz per ray), their lengths |P - O|, and the rays of each cell (cell
 *   c = (face * cells + i) * cells + j holds cellRays[ cellOffsets[ c ] .. cellOffsets[ c + 1 ] ])
 */
export function createRayFan( origin, points, { count = Math.floor( points.length / 3 ), cells = FAN_CELLS } = {} ) {

	if ( ! origin || origin.length < 3 || ! [ 0, 1, 2 ].every( ( k ) => Number.isFinite( origin[ k ] ) ) ) throw new RangeError( 'createRayFan: the origin needs three finite coordinates' );
	if ( ! Number.isInteger( count ) || count < 0 || 3 * count > points.length ) throw new RangeError( `createRayFan: ${ count } points do not fit in ${ points.length } coordinates` );
	if ( ! Number.isInteger( cells ) || cells < 1 ) throw new RangeError( `createRayFan: cells must be a positive integer, got ${ cells }` );
	const o = Float64Array.from( [ origin[ 0 ], origin[ 1 ], origin[ 2 ] ] );
	const directions = new Float64Array( 3 * count );
	const lengths = new Float64Array( count );
	const cellOf = new Int32Array( count );
	const cellCount = FACES * cells * cells;
	const cellOffsets = new Int32Array( cellCount + 1 );
	const faceRays = new Int32Array( FACES );
	for ( let k = 0; k < count; k ++ ) {

		const x = points[ 3 * k ] - o[ 0 ], y = points[ 3 * k + 1 ] - o[ 1 ], z = points[ 3 * k + 2 ] - o[ 2 ];
		if ( ! ( Number.isFinite( x ) && Number.isFinite( y ) && Number.isFinite( z ) ) ) throw new RangeError( `createRayFan: point ${ k } is not finite` );
		directions[ 3 * k ] = x;
		directions[ 3 * k + 1 ] = y;
		directions[ 3 * k + 2 ] = z;
		lengths[ k ] = Math.hypot( x, y, z );
		const face = faceOf( x, y, z );
		cellOf[ k ] = - 1;
		if ( face < 0 ) continue; // a point at the origin has no ray: it crosses nothing
		const axis = face >> 1;
		const d = [ x, y, z ];
		const w = Math.abs( d[ axis ] );
		const c = ( face * cells + cellIndex( d[ U_AXIS[ axis ] ] / w, cells ) ) * cells + cellIndex( d[ V_AXIS[ axis ] ] / w, cells );
		cellOf[ k ] = c;
		cellOffsets[ c + 1 ] ++;
		faceRays[ face ] ++;

	}

	for ( let c = 0; c < cellCount; c ++ ) cellOffsets[ c + 1 ] += cellOffsets[ c ];
	const fill = cellOffsets.slice( 0, cellCount );
	const cellRays = new Int32Array( count );
	for ( let k = 0; k < count; k ++ ) if ( cellOf[ k ] >= 0 ) cellRays[ fill[ cellOf[ k ] ] ++ ] = k;
	return {
		origin: o, count, directions, lengths, cells, cellOffsets, cellRays, faceRays,
		// Scratch of rayFirstHits: the triangle's corners about O, and two polygons for clipping.
		corners: new Float64Array( 9 ),
		polygon: new Float64Array( 3 * MAX_POLYGON ),
		clipped: new Float64Array( 3 * MAX_POLYGON ),
		box: new Float64Array( 4 ),
	};

}

/**
 * The first crossing of every ray of `fan` with a triangle mesh.
 * @param {object} fan from createRayFan
 * @param {Float32Array|Float64Array} positions the mesh's vertices, xyz per vertex (mm)
 * @param {Uint32Array|Uint16Array|Int32Array} triangles three vertex indices per triangle
 * @param {number} triangleCount triangles to use (from the first)
 * @param {Float64Array} target (fan.count) written with the smallest t > 0 at which the ray
 *   O + t (P - O) crosses a triangle (t = 1 at P), Infinity when it crosses none
 * @returns {number} the rays that cross the mesh. Allocates nothing.
 */
export function rayFirstHits( fan, positions, triangles, triangleCount, target ) {

	target.fill( Infinity, 0, fan.count );
	const ox = fan.origin[ 0 ], oy = fan.origin[ 1 ], oz = fan.origin[ 2 ];
	const corners = fan.corners;
	for ( let t = 0; t < triangleCount; t ++ ) {

		let face = - 2;
		let strict = true;
		for ( let c = 0; c < 3; c ++ ) {

			const v = 3 * triangles[ 3 * t + c ];
			const x = positions[ v ] - ox, y = positions[ v + 1 ] - oy, z = positions[ v + 2 ] - oz;
			corners[ 3 * c ] = x;
			corners[ 3 * c + 1 ] = y;
			corners[ 3 * c + 2 ] = z;
			// The face whose pyramid holds the corner strictly inside (-1: on an edge of one).
			const mx = Math.abs( x ), my = Math.abs( y ), mz = Math.abs( z );
			const f = mx > my && mx > mz ? ( x > 0 ? 0 : 1 ) : my > mx && my > mz ? ( y > 0 ? 2 : 3 ) : mz > mx && mz > my ? ( z > 0 ? 4 : 5 ) : - 1;
			if ( f < 0 || ( face !== - 2 && f !== face ) ) strict = false;
			face = f;

		}

		if ( strict ) {

			// Inside one pyramid: the corners' own projections bound the shadow.
			if ( fan.faceRays[ face ] === 0 ) continue;
			projectBox( corners, 3, face, fan.box );
			visitCells( fan, face, t, positions, triangles, target );
			continue;

		}

		for ( let f = 0; f < FACES; f ++ ) {

			if ( fan.faceRays[ f ] === 0 ) continue;
			const n = clipToPyramid( fan, f );
			if ( n === 0 ) continue;
			projectBox( fan.polygon, n, f, fan.box );
			visitCells( fan, f, t, positions, triangles, target );

		}

	}

	let hits = 0;
	for ( let k = 0; k < fan.count; k ++ ) if ( target[ k ] < Infinity ) hits ++;
	return hits;

}

/**
 * Clip the triangle in fan.corners to the closed pyramid of `face` (where s * d_axis >= |d_u|
 * and >= |d_v|), Sutherland-Hodgman over its four planes through O. The polygon is left in
 * fan.polygon; returns its vertex count (0: the triangle is outside the pyramid).
 */
function clipToPyramid( fan, face ) {

	const axis = face >> 1, s = face & 1 ? - 1 : 1, ua = U_AXIS[ axis ], va = V_AXIS[ axis ];
	let src = fan.polygon, dst = fan.clipped;
	src.set( fan.corners );
	let n = 3;
	for ( let plane = 0; plane < 4 && n > 0; plane ++ ) {

		// Plane: s * d_axis + sign * d_other >= 0.
		const other = plane < 2 ? ua : va;
		const sign = plane & 1 ? - 1 : 1;
		let m = 0;
		for ( let i = 0; i < n; i ++ ) {

			const a = 3 * i, b = 3 * ( ( i + 1 ) % n );
			const da = s * src[ a + axis ] + sign * src[ a + other ];
			const db = s * src[ b + axis ] + sign * src[ b + other ];
			if ( da >= 0 ) {

				dst[ 3 * m ] = src[ a ];
				dst[ 3 * m + 1 ] = src[ a + 1 ];
				dst[ 3 * m + 2 ] = src[ a + 2 ];
				m ++;

			}

			if ( ( da >= 0 ) !== ( db >= 0 ) ) {

				const r = da / ( da - db );
				dst[ 3 * m ] = src[ a ] + r * ( src[ b ] - src[ a ] );
				dst[ 3 * m + 1 ] = src[ a + 1 ] + r * ( src[ b + 1 ] - src[ a + 1 ] );
				dst[ 3 * m + 2 ] = src[ a + 2 ] + r * ( src[ b + 2 ] - src[ a + 2 ] );
				m ++;

			}

		}

		n = m;
		const swap = src;
		src = dst;
		dst = swap;

	}

	if ( src !== fan.polygon ) for ( let k = 0; k < 3 * n; k ++ ) fan.polygon[ k ] = src[ k ];
	return n;

}

/** The gnomonic box [ umin, umax, vmin, vmax ] of n points on `face`, widened by PAD (the whole face where a point is at O). */
function projectBox( points, n, face, box ) {

	const axis = face >> 1, s = face & 1 ? - 1 : 1, ua = U_AXIS[ axis ], va = V_AXIS[ axis ];
	box[ 0 ] = Infinity;
	box[ 1 ] = - Infinity;
	box[ 2 ] = Infinity;
	box[ 3 ] = - Infinity;
	for ( let i = 0; i < n; i ++ ) {

		const w = s * points[ 3 * i + axis ];
		if ( ! ( w > 0 ) ) {

			box[ 0 ] = - 1;
			box[ 1 ] = 1;
			box[ 2 ] = - 1;
			box[ 3 ] = 1;
			return;

		}

		const u = points[ 3 * i + ua ] / w, v = points[ 3 * i + va ] / w;
		if ( u < box[ 0 ] ) box[ 0 ] = u;
		if ( u > box[ 1 ] ) box[ 1 ] = u;
		if ( v < box[ 2 ] ) box[ 2 ] = v;
		if ( v > box[ 3 ] ) box[ 3 ] = v;

	}

}

/** Test triangle `t` against the rays of the cells of fan.box on `face`, keeping the first hits. */
function visitCells( fan, face, t, positions, triangles, target ) {

	const box = fan.box, n = fan.cells;
	if ( box[ 1 ] < - 1 - PAD || box[ 0 ] > 1 + PAD || box[ 3 ] < - 1 - PAD || box[ 2 ] > 1 + PAD ) return;
	const i0 = cellIndex( box[ 0 ] - PAD, n ), i1 = cellIndex( box[ 1 ] + PAD, n );
	const j0 = cellIndex( box[ 2 ] - PAD, n ), j1 = cellIndex( box[ 3 ] + PAD, n );
	const offsets = fan.cellOffsets, rays = fan.cellRays, dirs = fan.directions;
	const a = 3 * triangles[ 3 * t ], b = 3 * triangles[ 3 * t + 1 ], c = 3 * triangles[ 3 * t + 2 ];
	const ax = positions[ a ], ay = positions[ a + 1 ], az = positions[ a + 2 ];
	const e1x = positions[ b ] - ax, e1y = positions[ b + 1 ] - ay, e1z = positions[ b + 2 ] - az;
	const e2x = positions[ c ] - ax, e2y = positions[ c + 1 ] - ay, e2z = positions[ c + 2 ] - az;
	const sx = fan.origin[ 0 ] - ax, sy = fan.origin[ 1 ] - ay, sz = fan.origin[ 2 ] - az;
	for ( let i = i0; i <= i1; i ++ ) {

		for ( let j = j0; j <= j1; j ++ ) {

			const cell = ( face * n + i ) * n + j;
			const end = offsets[ cell + 1 ];
			for ( let r = offsets[ cell ]; r < end; r ++ ) {

				// crossing(), inline: a called function would box its floating-point arguments.
				const k = rays[ r ];
				const dx = dirs[ 3 * k ], dy = dirs[ 3 * k + 1 ], dz = dirs[ 3 * k + 2 ];
				const hx = dy * e2z - dz * e2y;
				const hy = dz * e2x - dx * e2z;
				const hz = dx * e2y - dy * e2x;
				const det = e1x * hx + e1y * hy + e1z * hz;
				if ( det === 0 ) continue;
				const inv = 1 / det;
				const u = ( sx * hx + sy * hy + sz * hz ) * inv;
				if ( ! ( u >= - SLACK ) ) continue;
				const qx = sy * e1z - sz * e1y;
				const qy = sz * e1x - sx * e1z;
				const qz = sx * e1y - sy * e1x;
				const v = ( dx * qx + dy * qy + dz * qz ) * inv;
				if ( ! ( v >= - SLACK ) || ! ( u + v <= 1 + SLACK ) ) continue;
				const hit = ( e2x * qx + e2y * qy + e2z * qz ) * inv;
				if ( hit > 0 && hit < target[ k ] ) target[ k ] = hit;

			}

		}

	}

}

/**
 * Ray parameter t at which O + t d crosses the triangle (a, a + e1, a + e2), s = O - a; NaN when
 * it does not (two-sided Moller-Trumbore with the barycentric slack): the test visitCells makes
 * inline, for a brute-force reference.
 */
export function crossing( dx, dy, dz, sx, sy, sz, e1x, e1y, e1z, e2x, e2y, e2z ) {

	const hx = dy * e2z - dz * e2y;
	const hy = dz * e2x - dx * e2z;
	const hz = dx * e2y - dy * e2x;
	const det = e1x * hx + e1y * hy + e1z * hz;
	if ( det === 0 ) return NaN;
	const inv = 1 / det;
	const u = ( sx * hx + sy * hy + sz * hz ) * inv;
	if ( ! ( u >= - SLACK ) ) return NaN;
	const qx = sy * e1z - sz * e1y;
	const qy = sz * e1x - sx * e1z;
	const qz = sx * e1y - sy * e1x;
	const v = ( dx * qx + dy * qy + dz * qz ) * inv;
	if ( ! ( v >= - SLACK ) || ! ( u + v <= 1 + SLACK ) ) return NaN;
	return ( e2x * qx + e2y * qy + e2z * qz ) * inv;

}
