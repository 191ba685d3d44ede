// Comparing computed floats: always within a stated tolerance (float results differ in their last
// bits between CPUs, SIMD paths and engines; an exact comparison is for integers, flags and bytes).
import assert from 'node:assert/strict';

/** |actual - expected| <= tol, or fail with both values and what they are. */
export function near( actual, expected, tol, what ) {

	assert.ok( Math.abs( actual - expected ) <= tol, `${ what }: got ${ actual }, expected ${ expected } (tolerance ${ tol })` );

}

/** |actual - expected| <= tol * max(1, |expected|): relative above 1, absolute below. */
export function nearRelative( actual, expected, tol, what ) {

	near( actual, expected, tol * Math.max( 1, Math.abs( expected ) ), what );

}

/** Two arrays of numbers of the same length, element by element within ``tol``. */
export function nearArray( actual, expected, tol, what ) {

	assert.equal( actual.length, expected.length, `${ what }: lengths` );
	for ( let k = 0; k < expected.length; k ++ ) {

		if ( ! ( Math.abs( actual[ k ] - expected[ k ] ) <= tol ) ) near( actual[ k ], expected[ k ], tol, `${ what } [${ k }]` );

	}

}
