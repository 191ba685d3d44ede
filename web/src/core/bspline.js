// B-spline basis functions and knot vectors (twin of server/glasshead/geometry/bspline.py).
//
// The tongue evaluates its curves at parameters fixed when the rig is loaded, so basisTable()
// turns (knots, degree, parameters) into flat tables once; per frame only weighted sums remain.
// findSpan() and basisFuns() write into caller-owned arrays and allocate nothing.

/**
 * The NURBS Book (Piegl and Tiller, 2nd ed.), algorithm A2.1 FindSpan.
 * Index i of the knot span with knots[ i ] <= u < knots[ i + 1 ] within the curve's domain;
 * u is clamped into [ knots[ degree ], knots[ n + 1 ] ] and the right end maps to the last span.
 * @param {ArrayLike<number>} knots m + 1 non-decreasing knots; the curve has m - degree control points.
 * @param {number} degree
 * @param {number} u
 * @returns {number}
 */
export function findSpan( knots, degree, u ) {

	const n = knots.length - degree - 2;
	if ( u >= knots[ n + 1 ] ) return n;
	if ( u <= knots[ degree ] ) return degree;
	let low = degree;
	let high = n + 1;
	let mid = ( low + high ) >> 1;
	while ( u < knots[ mid ] || u >= knots[ mid + 1 ] ) {

		if ( u < knots[ mid ] ) high = mid;
		else low = mid;
		mid = ( low + high ) >> 1;

	}

	return mid;

}

/**
 * The NURBS Book (Piegl and Tiller, 2nd ed.), algorithm A2.2 BasisFuns.
 * Writes the degree + 1 non-zero basis functions N[ span - degree .. span ] at u into
 * target[ offset .. offset + degree ]. left and right are scratch arrays of length degree + 1.
 * @param {ArrayLike<number>} knots
 * @param {number} degree
 * @param {number} span from findSpan()
 * @param {number} u
 * @param {Float64Array} target
 * @param {number} offset
 * @param {Float64Array} left scratch, length >= degree + 1
 * @param {Float64Array} right scratch, length >= degree + 1
 * @returns {Float64Array} target
 */
export function basisFuns( knots, degree, span, u, target, offset, left, right ) {

	target[ offset ] = 1.0;
	for ( let j = 1; j <= degree; j ++ ) {

		left[ j ] = u - knots[ span + 1 - j ];
		right[ j ] = knots[ span + j ] - u;
		let saved = 0.0;
		for ( let r = 0; r < j; r ++ ) {

			const temp = target[ offset + r ] / ( right[ r + 1 ] + left[ j - r ] );
			target[ offset + r ] = saved + right[ r + 1 ] * temp;
			saved = left[ j - r ] * temp;

		}

		target[ offset + j ] = saved;

	}

	return target;

}

/**
 * Spans and non-zero basis values at each parameter (allocates; call once at load time).
 * @param {ArrayLike<number>} knots
 * @param {number} degree
 * @param {ArrayLike<number>} params
 * @returns {{ first: Int32Array, values: Float64Array }} first[ k ]: first control point row k
 *   weights (span - degree); values[ k * ( degree + 1 ) + i ]: its weight on control first[ k ] + i.
 */
export function basisTable( knots, degree, params ) {

	checkKnots( knots, degree );
	const width = degree + 1;
	const first = new Int32Array( params.length );
	const values = new Float64Array( params.length * width );
	const left = new Float64Array( width );
	const right = new Float64Array( width );
	for ( let k = 0; k < params.length; k ++ ) {

		const span = findSpan( knots, degree, params[ k ] );
		first[ k ] = span - degree;
		basisFuns( knots, degree, span, params[ k ], values, k * width, left, right );

	}

	return { first, values };

}

/**
 * Uniform knots of a closed curve with `count` distinct control points, domain [ 0, 1 ):
 * knot i is ( i - degree ) / count; the curve uses count + degree wrapped control points.
 * @param {number} count
 * @param {number} degree
 * @returns {Float64Array}
 */
export function periodicKnots( count, degree ) {

	if ( count <= degree ) throw new RangeError( `a closed curve of degree ${degree} needs more than ${degree} points` );
	const knots = new Float64Array( count + 2 * degree + 1 );
	for ( let i = 0; i < knots.length; i ++ ) knots[ i ] = ( i - degree ) / count;
	return knots;

}

function checkKnots( knots, degree ) {

	if ( ! Number.isInteger( degree ) || degree < 1 ) throw new RangeError( `degree must be a positive integer, got ${degree}` );
	if ( knots.length < 2 * degree + 2 ) throw new RangeError( `${knots.length} knots are too few for degree ${degree}` );
	for ( let i = 1; i < knots.length; i ++ ) {

		if ( ! ( knots[ i ] >= knots[ i - 1 ] ) ) throw new RangeError( 'knots must be non-decreasing and finite' );

	}

}
