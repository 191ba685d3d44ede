// The mid-sagittal polygon of the airway: the section segments of an open tube joined into
// chains, cut at the lips and closed across the larynx, so that it can be filled as the air of
// the cutaway. Pure; runs once when the airway is loaded (it allocates its results).
//
// The airway mesh is measured in one posture and is open at both ends; around the lips it wraps
// onto the face (its section follows the outside of the upper lip to the nose and of the lower
// lip to the chin). Cut by z = 0 it gives two long open chains, its upper wall (palate, velum,
// posterior pharyngeal wall) and its lower wall (lower lip, tongue, epiglottis), and small closed
// loops for what stands inside it (the epiglottis). The air is the region between the two walls,
// from the lip opening (where the walls come closest in front of ANTERIOR_X_MM) to the open end at
// the larynx (the walls' posterior ends, joined by a straight line).

/** Section points closer than this (mm) are the same point of a chain. */
export const WELD_MM = 1e-3;

/** The lips lie in front of this x (mm, project frame); the lip opening is searched there. */
export const ANTERIOR_X_MM = 0;

/**
 * Join section segments into chains.
 * @param {Float32Array|Float64Array} segments x0 y0 z0 x1 y1 z1 per segment (planeSectionSegments)
 * @param {number} count segments to read
 * @param {number} [weld] points closer than this are one point, mm
 * @returns {Array<{ points: Float64Array, closed: boolean }>} x y per point, in walking order; a
 *   closed chain does not repeat its first point
 */
export function chainSegments( segments, count, weld = WELD_MM ) {

	const ids = new Map();
	const xy = [];
	const pointId = ( o ) => {

		const key = `${ Math.round( segments[ o ] / weld ) },${ Math.round( segments[ o + 1 ] / weld ) }`;
		let id = ids.get( key );
		if ( id === undefined ) {

			id = xy.length / 2;
			ids.set( key, id );
			xy.push( segments[ o ], segments[ o + 1 ] );

		}

		return id;

	};

	const neighbours = [];
	for ( let s = 0; s < count; s ++ ) {

		const a = pointId( 6 * s );
		const b = pointId( 6 * s + 3 );
		if ( a === b ) continue;
		( neighbours[ a ] ??= [] ).push( b );
		( neighbours[ b ] ??= [] ).push( a );

	}

	const seen = new Uint8Array( xy.length / 2 );
	const chains = [];
	const walk = ( start ) => {

		const order = [ start ];
		seen[ start ] = 1;
		let current = start;
		for ( ;; ) {

			const next = ( neighbours[ current ] ?? [] ).find( ( n ) => ! seen[ n ] );
			if ( next === undefined ) break;
			seen[ next ] = 1;
			order.push( next );
			current = next;

		}

		const closed = order.length > 2 && neighbours[ current ].includes( start );
		const points = new Float64Array( 2 * order.length );
		order.forEach( ( id, k ) => {

			points[ 2 * k ] = xy[ 2 * id ];
			points[ 2 * k + 1 ] = xy[ 2 * id + 1 ];

		} );
		chains.push( { points, closed } );

	};

	// Open chains first, from one of their ends; what is left is closed loops.
	for ( let id = 0; id < seen.length; id ++ ) if ( ! seen[ id ] && neighbours[ id ]?.length === 1 ) walk( id );
	for ( let id = 0; id < seen.length; id ++ ) if ( ! seen[ id ] && neighbours[ id ] ) walk( id );
	return chains;

}

/** A chain's points reversed (x y pairs kept together). */
function reversed( points ) {

	const n = points.length / 2;
	const out = new Float64Array( points.length );
	for ( let k = 0; k < n; k ++ ) {

		out[ 2 * k ] = points[ 2 * ( n - 1 - k ) ];
		out[ 2 * k + 1 ] = points[ 2 * ( n - 1 - k ) + 1 ];

	}

	return out;

}

/** Whether point (x, y) lies inside the closed polygon `points` (x y pairs; even-odd rule). */
export function insidePolygon( points, x, y ) {

	let inside = false;
	const n = points.length / 2;
	for ( let i = 0, j = n - 1; i < n; j = i ++ ) {

		const xi = points[ 2 * i ], yi = points[ 2 * i + 1 ];
		const xj = points[ 2 * j ], yj = points[ 2 * j + 1 ];
		if ( ( yi > y ) !== ( yj > y ) && x < ( xj - xi ) * ( y - yi ) / ( yj - yi ) + xi ) inside = ! inside;

	}

	return inside;

}

/**
 * The airway's air polygon from its section chains (see the top of this file).
 * @param {Array<{ points: Float64Array, closed: boolean }>} chains from chainSegments()
 * @param {{ anteriorX?: number }} [options] where the lip opening is searched (x above this, mm)
 * @returns {{ outline: Float64Array, holes: Float64Array[], upper: Float64Array, lower: Float64Array,
 *   lips: number[] }} outline: x y per point, closed implicitly across the larynx; holes: loops
 *   inside it; upper, lower: the walls from the larynx to the lip opening; lips: x y of the
 *   upper and lower wall at the lip opening
 */
export function airwayPolygon( chains, { anteriorX = ANTERIOR_X_MM } = {} ) {

	const open = chains.filter( ( chain ) => ! chain.closed ).sort( ( a, b ) => b.points.length - a.points.length );
	if ( open.length < 2 ) throw new Error( `the airway's section has ${ open.length } open wall(s); it needs two` );
	// Each wall from its posterior (laryngeal) end.
	const walls = open.slice( 0, 2 ).map( ( { points } ) => ( points[ 0 ] <= points[ points.length - 2 ] ? points : reversed( points ) ) );

	// The lip opening: the closest pair of wall points in front of anteriorX.
	let best = Infinity, bi = - 1, bj = - 1;
	const [ a, b ] = walls;
	for ( let i = 0; i < a.length / 2; i ++ ) {

		if ( a[ 2 * i ] <= anteriorX ) continue;
		for ( let j = 0; j < b.length / 2; j ++ ) {

			if ( b[ 2 * j ] <= anteriorX ) continue;
			const d = ( a[ 2 * i ] - b[ 2 * j ] ) ** 2 + ( a[ 2 * i + 1 ] - b[ 2 * j + 1 ] ) ** 2;
			if ( d < best ) {

				best = d;
				bi = i;
				bj = j;

			}

		}

	}

	if ( bi < 0 ) throw new Error( `the airway's walls do not reach in front of x = ${ anteriorX } mm (the lips)` );
	let upper = a.slice( 0, 2 * bi + 2 );
	let lower = b.slice( 0, 2 * bj + 2 );
	if ( upper[ 2 * bi + 1 ] < lower[ 2 * bj + 1 ] ) [ upper, lower ] = [ lower, upper ];

	const outline = new Float64Array( upper.length + lower.length );
	outline.set( upper );
	outline.set( reversed( lower ), upper.length );
	const holes = chains.filter( ( chain ) => chain.closed && insidePolygon( outline, chain.points[ 0 ], chain.points[ 1 ] ) ).map( ( chain ) => chain.points );
	const lips = [ upper[ upper.length - 2 ], upper[ upper.length - 1 ], lower[ lower.length - 2 ], lower[ lower.length - 1 ] ];
	return { outline, holes, upper, lower, lips };

}

/**
 * The y values where the polyline `points` (x y pairs) crosses the vertical line at x, written
 * into `target` (sorted, ascending). Returns how many.
 */
export function crossingsAt( points, x, target ) {

	let count = 0;
	for ( let k = 0; k + 3 < points.length; k += 2 ) {

		const x0 = points[ k ], x1 = points[ k + 2 ];
		if ( ( x0 <= x ) === ( x1 <= x ) || count >= target.length ) continue;
		const s = ( x - x0 ) / ( x1 - x0 );
		target[ count ++ ] = points[ k + 1 ] + ( points[ k + 3 ] - points[ k + 1 ] ) * s;

	}

	target.subarray( 0, count ).sort();
	return count;

}
