// The narrowest constriction of the vocal tract in the mid-sagittal section: the smallest gap
// between the floor (the tongue, the lower lip) and the roof (the palate with the upper teeth,
// the velum, the upper lip), where it is along the tract and the nearest place of articulation.
// Pure; the midline is built once, the per-frame search allocates nothing.
//
//
// The gap is the least distance between the two sets of polylines: every floor point against
// every roof segment and every roof point against every floor segment (the distance between two
// polylines that do not cross is reached at a vertex of one of them). The search starts from the
// floor point of the last frame's gap, so that the best gap so far is small from the start: roof
// points farther than it outside the floor's bounding box are skipped, and so are chunks of
// segments whose bounding box is no nearer (first box against box for a chunk's points, then
// for each point). Its place along the tract is
// the arc length, from the lip opening, of the midline point nearest the middle of the gap.

import { chainSegmentCount, CHUNK_SEGMENTS } from './midSection.js';

/** Numbers of a constriction result: see the CONSTRICTION_* offsets. */
export const CONSTRICTION_LENGTH = 10;
/** Width of the gap, mm. */
export const CONSTRICTION_WIDTH = 0;
/** Arc length along the tract's midline from the lip opening, mm. */
export const CONSTRICTION_AT = 1;
/** The floor's point of the gap (x y, mm), then the roof's (x y). */
export const CONSTRICTION_FLOOR = 2;
export const CONSTRICTION_ROOF = 4;
/** Index of the nearest place of articulation (-1: none given). */
export const CONSTRICTION_PLACE = 6;
/** 1 when a gap was found (floor and roof both had points), else 0. */
export const CONSTRICTION_FOUND = 7;
/** The floor part and point of the last gap: searched first in the next frame (a warm start). */
export const CONSTRICTION_HINT = 8;

/**
 * The tract's midline, from the lip opening to the larynx: the upper wall resampled by arc length
 * and each sample moved halfway to the nearest point of the lower wall. Runs once (allocates).
 * @param {Float64Array} upper x y per point, from the larynx to the lip opening (airwayPolygon)
 * @param {Float64Array} lower the same for the lower wall
 * @param {number} [count] samples
 * @returns {{ points: Float64Array, lengths: Float64Array }} x y per sample from the lips, and
 *   the arc length of each sample from the first, mm
 */
export function tractMidline( upper, lower, count = 96 ) {

	if ( upper.length < 4 || lower.length < 4 ) throw new RangeError( 'each wall needs at least two points' );
	const n = upper.length / 2;
	const along = new Float64Array( n );
	for ( let k = 1; k < n; k ++ ) along[ k ] = along[ k - 1 ] + Math.hypot( upper[ 2 * k ] - upper[ 2 * k - 2 ], upper[ 2 * k + 1 ] - upper[ 2 * k - 1 ] );
	const total = along[ n - 1 ];
	const points = new Float64Array( 2 * count );
	const near = new Float64Array( 2 );
	let k = n - 1;
	for ( let i = 0; i < count; i ++ ) {

		// From the lips (the wall's end) back.
		const s = total * ( 1 - i / ( count - 1 ) );
		while ( k > 1 && along[ k - 1 ] > s ) k --;
		const span = along[ k ] - along[ k - 1 ] || 1;
		const f = Math.min( 1, Math.max( 0, ( s - along[ k - 1 ] ) / span ) );
		const x = upper[ 2 * k - 2 ] + ( upper[ 2 * k ] - upper[ 2 * k - 2 ] ) * f;
		const y = upper[ 2 * k - 1 ] + ( upper[ 2 * k + 1 ] - upper[ 2 * k - 1 ] ) * f;
		nearestOnPolyline( lower, 0, lower.length / 2, false, x, y, near );
		points[ 2 * i ] = ( x + near[ 0 ] ) / 2;
		points[ 2 * i + 1 ] = ( y + near[ 1 ] ) / 2;

	}

	const lengths = new Float64Array( count );
	for ( let i = 1; i < count; i ++ ) lengths[ i ] = lengths[ i - 1 ] + Math.hypot( points[ 2 * i ] - points[ 2 * i - 2 ], points[ 2 * i + 1 ] - points[ 2 * i - 1 ] );
	return { points, lengths };

}

/**
 * Nearest point to (x, y) on points[ first .. first + count ) (x y pairs; closed joins the last to
 * the first), written into target (x y). Returns the squared distance.
 */
export function nearestOnPolyline( points, first, count, closed, x, y, target ) {

	let best = Infinity;
	const segments = closed ? count : count - 1;
	for ( let s = 0; s < Math.max( segments, 1 ); s ++ ) {

		const i = first + s, j = first + ( ( s + 1 ) % count );
		const ax = points[ 2 * i ], ay = points[ 2 * i + 1 ];
		const dx = points[ 2 * j ] - ax, dy = points[ 2 * j + 1 ] - ay;
		const length2 = dx * dx + dy * dy;
		let t = length2 > 0 ? ( ( x - ax ) * dx + ( y - ay ) * dy ) / length2 : 0;
		t = t < 0 ? 0 : t > 1 ? 1 : t;
		const px = ax + t * dx, py = ay + t * dy;
		const d = ( px - x ) ** 2 + ( py - y ) ** 2;
		if ( d < best ) {

			best = d;
			target[ 0 ] = px;
			target[ 1 ] = py;

		}

	}

	return best;

}

/** The search's state: best squared gap so far, then its floor point (x y) and roof point (x y). */
const gap = new Float64Array( 5 );
const GAP_BEST = 0, GAP_FLOOR = 1, GAP_ROOF = 3;
/** The floor's bounding box: min x, min y, max x, max y. */
const box = new Float64Array( 4 );

/**
 * Point k of part `from` against the segments of the chunks of part `to` listed in to.near (all
 * of them when `all`), skipping chunks whose box is no nearer than the best gap; a nearer gap
 * goes into `gap`, `from` being the floor or not. Only integers and parts cross the call, so no
 * number is boxed. Returns whether it found one.
 */
function pointAgainstPart( from, k, to, fromFloor, all ) {

	const x = from.points[ 2 * k ], y = from.points[ 2 * k + 1 ];
	const { points, starts, boxes, near } = to;
	const chunks = all ? to.chunkCount : to.nearCount;
	let found = false;
	for ( let m = 0; m < chunks; m ++ ) {

		const chunk = all ? m : near[ m ];
		const bx = Math.max( boxes[ 4 * chunk ] - x, 0, x - boxes[ 4 * chunk + 2 ] );
		const by = Math.max( boxes[ 4 * chunk + 1 ] - y, 0, y - boxes[ 4 * chunk + 3 ] );
		if ( bx * bx + by * by >= gap[ GAP_BEST ] ) continue;
		const c = to.chunkChain[ chunk ];
		const first = starts[ c ];
		const n = starts[ c + 1 ] - first;
		const last = Math.min( to.chunkFirst[ chunk ] + CHUNK_SEGMENTS, chainSegmentCount( to, c ) );
		for ( let s = to.chunkFirst[ chunk ]; s < last; s ++ ) {

			const i = first + s, j = first + ( ( s + 1 ) % n );
			const ax = points[ 2 * i ], ay = points[ 2 * i + 1 ];
			const dx = points[ 2 * j ] - ax, dy = points[ 2 * j + 1 ] - ay;
			const length2 = dx * dx + dy * dy;
			let t = length2 > 0 ? ( ( x - ax ) * dx + ( y - ay ) * dy ) / length2 : 0;
			t = t < 0 ? 0 : t > 1 ? 1 : t;
			const px = ax + t * dx, py = ay + t * dy;
			const d = ( px - x ) * ( px - x ) + ( py - y ) * ( py - y );
			if ( d >= gap[ GAP_BEST ] ) continue;
			gap[ GAP_BEST ] = d;
			const self = fromFloor ? GAP_FLOOR : GAP_ROOF, other = fromFloor ? GAP_ROOF : GAP_FLOOR;
			gap[ self ] = x;
			gap[ self + 1 ] = y;
			gap[ other ] = px;
			gap[ other + 1 ] = py;
			found = true;

		}

	}

	return found;

}

/**
 * The chunks of `to` whose box is nearer chunk `chunk` of `from`'s box than the best gap, into
 * to.near. The best gap only shrinks, so a chunk left out now is no nearer to any point of the
 * chunk later: the search visits what it visited before, in the same order, and finds the same.
 */
function nearChunks( from, chunk, to ) {

	const a = from.boxes, b = to.boxes;
	const x0 = a[ 4 * chunk ], y0 = a[ 4 * chunk + 1 ], x1 = a[ 4 * chunk + 2 ], y1 = a[ 4 * chunk + 3 ];
	let count = 0;
	for ( let m = 0; m < to.chunkCount; m ++ ) {

		const bx = Math.max( b[ 4 * m ] - x1, 0, x0 - b[ 4 * m + 2 ] );
		const by = Math.max( b[ 4 * m + 1 ] - y1, 0, y0 - b[ 4 * m + 3 ] );
		if ( bx * bx + by * by < gap[ GAP_BEST ] ) to.near[ count ++ ] = m;

	}

	to.nearCount = count;

}

/**
 * One past the last point chunk m owns: its points run from its first segment's start up to the
 * next chunk's (the last chunk of a chain owns the rest of it); the chunk's box holds them all.
 */
function ownEnd( part, m ) {

	const c = part.chunkChain[ m ];
	const next = m + 1 < part.chunkCount && part.chunkChain[ m + 1 ] === c ? part.chunkFirst[ m + 1 ] : part.starts[ c + 1 ] - part.starts[ c ];
	return part.starts[ c ] + next;

}

/** Whether roof point k lies farther outside the floor's box than the best gap. */
function outsideBox( part, k ) {

	const x = part.points[ 2 * k ], y = part.points[ 2 * k + 1 ];
	const bx = Math.max( box[ 0 ] - x, 0, x - box[ 2 ] ), by = Math.max( box[ 1 ] - y, 0, y - box[ 3 ] );
	return bx * bx + by * by >= gap[ GAP_BEST ];

}

/**
 * The narrowest gap between floor and roof, into target (CONSTRICTION_* offsets).
 * @param {object[]} floor section parts of the tongue and lower lip (points posed)
 * @param {object[]} roof section parts of the palate, velum and upper lip
 * @param {{ points: Float64Array, lengths: Float64Array }|null} midline from tractMidline
 * @param {Float64Array|null} places x y per place of articulation, or null
 * @param {Float64Array} target CONSTRICTION_LENGTH numbers (the last frame's, for the warm start)
 * @returns {Float64Array} target
 */
export function findConstriction( floor, roof, midline, places, target ) {

	const hintPart = target[ CONSTRICTION_FOUND ] === 1 ? target[ CONSTRICTION_HINT ] : - 1;
	const hintPoint = target[ CONSTRICTION_HINT + 1 ];
	target.fill( 0 );
	target[ CONSTRICTION_PLACE ] = - 1;
	box[ 0 ] = box[ 1 ] = Infinity;
	box[ 2 ] = box[ 3 ] = - Infinity;
	for ( let f = 0; f < floor.length; f ++ ) {

		const points = floor[ f ].points;
		for ( let k = 0; k < floor[ f ].pointCount; k ++ ) {

			const x = points[ 2 * k ], y = points[ 2 * k + 1 ];
			if ( x < box[ 0 ] ) box[ 0 ] = x;
			if ( y < box[ 1 ] ) box[ 1 ] = y;
			if ( x > box[ 2 ] ) box[ 2 ] = x;
			if ( y > box[ 3 ] ) box[ 3 ] = y;

		}

	}

	gap[ GAP_BEST ] = Infinity;
	// The last frame's floor point first, then every floor point against the roof.
	if ( hintPart >= 0 && hintPart < floor.length && hintPoint < floor[ hintPart ].pointCount ) {

		for ( let r = 0; r < roof.length; r ++ ) pointAgainstPart( floor[ hintPart ], hintPoint, roof[ r ], true, true );

	}

	for ( let f = 0; f < floor.length; f ++ ) {

		const part = floor[ f ];
		for ( let m = 0; m < part.chunkCount; m ++ ) {

			for ( let r = 0; r < roof.length; r ++ ) nearChunks( part, m, roof[ r ] );
			const end = ownEnd( part, m );
			for ( let k = part.starts[ part.chunkChain[ m ] ] + part.chunkFirst[ m ]; k < end; k ++ ) {

				for ( let r = 0; r < roof.length; r ++ ) {

					if ( ! pointAgainstPart( part, k, roof[ r ], true, false ) ) continue;
					target[ CONSTRICTION_HINT ] = f;
					target[ CONSTRICTION_HINT + 1 ] = k;

				}

			}

		}

	}

	// Roof points near the floor against the floor.
	for ( let r = 0; r < roof.length; r ++ ) {

		const part = roof[ r ];
		for ( let m = 0; m < part.chunkCount; m ++ ) {

			for ( let f = 0; f < floor.length; f ++ ) nearChunks( part, m, floor[ f ] );
			const end = ownEnd( part, m );
			for ( let k = part.starts[ part.chunkChain[ m ] ] + part.chunkFirst[ m ]; k < end; k ++ ) {

				if ( outsideBox( part, k ) ) continue;
				for ( let f = 0; f < floor.length; f ++ ) pointAgainstPart( part, k, floor[ f ], false, false );

			}

		}

	}

	if ( gap[ GAP_BEST ] === Infinity ) return target;
	target[ CONSTRICTION_FOUND ] = 1;
	target[ CONSTRICTION_WIDTH ] = Math.sqrt( gap[ GAP_BEST ] );
	for ( let k = 0; k < 2; k ++ ) {

		target[ CONSTRICTION_FLOOR + k ] = gap[ GAP_FLOOR + k ];
		target[ CONSTRICTION_ROOF + k ] = gap[ GAP_ROOF + k ];

	}

	if ( midline ) alongInto( midline, target );
	if ( places ) {

		let nearest = Infinity;
		for ( let p = 0; p < places.length / 2; p ++ ) {

			const dx = places[ 2 * p ] - target[ CONSTRICTION_ROOF ], dy = places[ 2 * p + 1 ] - target[ CONSTRICTION_ROOF + 1 ];
			if ( dx * dx + dy * dy >= nearest ) continue;
			nearest = dx * dx + dy * dy;
			target[ CONSTRICTION_PLACE ] = p;

		}

	}

	return target;

}

const probe = new Float64Array( CONSTRICTION_LENGTH );

/** Arc length (mm, from the midline's first point) of the midline point nearest (x, y). */
export function alongMidline( midline, x, y ) {

	probe[ CONSTRICTION_FLOOR ] = probe[ CONSTRICTION_ROOF ] = x;
	probe[ CONSTRICTION_FLOOR + 1 ] = probe[ CONSTRICTION_ROOF + 1 ] = y;
	return alongInto( midline, probe )[ CONSTRICTION_AT ];

}

/** The arc length of the midline point nearest the gap's middle, into target[ CONSTRICTION_AT ]. */
function alongInto( { points, lengths }, target ) {

	const x = ( target[ CONSTRICTION_FLOOR ] + target[ CONSTRICTION_ROOF ] ) / 2;
	const y = ( target[ CONSTRICTION_FLOOR + 1 ] + target[ CONSTRICTION_ROOF + 1 ] ) / 2;
	let best = Infinity;
	for ( let s = 0; s + 1 < lengths.length; s ++ ) {

		const ax = points[ 2 * s ], ay = points[ 2 * s + 1 ];
		const dx = points[ 2 * s + 2 ] - ax, dy = points[ 2 * s + 3 ] - ay;
		const length2 = dx * dx + dy * dy;
		let t = length2 > 0 ? ( ( x - ax ) * dx + ( y - ay ) * dy ) / length2 : 0;
		t = t < 0 ? 0 : t > 1 ? 1 : t;
		const ex = ax + t * dx - x, ey = ay + t * dy - y;
		if ( ex * ex + ey * ey >= best ) continue;
		best = ex * ex + ey * ey;
		target[ CONSTRICTION_AT ] = lengths[ s ] + t * ( lengths[ s + 1 ] - lengths[ s ] );

	}

	return target;

}
