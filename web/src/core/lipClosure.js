// The lips' mid-sagittal gap and its closure, step 3 of the face rig (face_rig.midline_points,
// lip_gap and solve_closure in server/glasshead/geometry/face_rig.py): where each lip crosses the
// plane z = 0, how far apart the lips are there, and the vertical closure that brings that gap to
// what lip_opening asks. faceRig.js calls these per pose, on the rig's preallocated scratch.

import { COEFF_CLOSURE, COEFF_COUNT } from './faceField.js';

/** Slots of rig.gaps: the lips' gap before closure, after the pose, and scratch for lipGap(). */
export const GAP_NATURAL = 0;
export const GAP_LIPS = 1;
export const GAP_SCRATCH = 2;

// Hot paths pass numbers through typed arrays, never as arguments or return values of calls that
// may not be inlined: a boxed double per call would make garbage every frame.

/**
 * The midline crossings of a lip: for each edge with ends on both sides of z = 0, the height
 * where it crosses (mesh.crossY) and the closure factor there (mesh.crossF).
 */
function crossings( mesh, positions ) {

	const { edges, coeffs, crossY, crossF } = mesh;
	for ( let k = 0; k < crossY.length; k ++ ) {

		const a = edges[ 2 * k ];
		const b = edges[ 2 * k + 1 ];
		const za = positions[ 3 * a + 2 ];
		const t = za / ( za - positions[ 3 * b + 2 ] );
		crossY[ k ] = positions[ 3 * a + 1 ] + t * ( positions[ 3 * b + 1 ] - positions[ 3 * a + 1 ] );
		crossF[ k ] = ( 1 - t ) * coeffs[ COEFF_COUNT * a + COEFF_CLOSURE ] + t * coeffs[ COEFF_COUNT * b + COEFF_CLOSURE ];

	}

}

/**
 * The lips' mid-sagittal gap, mm: the lowest crossing of the upper lip above the highest of the
 * lower lip; 0 when they touch or overlap.
 * @param {object} rig from createFaceRig()
 * @param {ArrayLike<number>} upper posed upper-lip positions (xyz per vertex)
 * @param {ArrayLike<number>} lower posed lower-lip positions
 */
export function lipGap( rig, upper, lower ) {

	measureGap( rig, upper, lower, GAP_SCRATCH );
	return rig.gaps[ GAP_SCRATCH ];

}

/** lipGap() into rig.gaps[ slot ]. */
export function measureGap( rig, upper, lower, slot ) {

	const up = rig.meshes.upper_lip;
	const low = rig.meshes.lower_lip;
	crossings( up, upper );
	crossings( low, lower );
	let upperLowest = Infinity;
	for ( let k = 0; k < up.crossY.length; k ++ ) if ( up.crossY[ k ] < upperLowest ) upperLowest = up.crossY[ k ];
	let lowerHighest = - Infinity;
	for ( let k = 0; k < low.crossY.length; k ++ ) if ( low.crossY[ k ] > lowerHighest ) lowerHighest = low.crossY[ k ];
	rig.gaps[ slot ] = Math.max( 0, upperLowest - lowerHighest );

}

/**
 * Vertical closure c (mm) bringing the gap to `target` (face_rig.solve_closure), from the
 * crossings of the last lipGap(): a crossing's height becomes y + factor * c, the gap is piecewise
 * linear and decreasing in c, and each step is a Newton step on the current extreme pair. Writes
 * c into closure[ 1 ].
 */
export function solveClosure( up, low, target, iterations, closure ) {

	const { crossY: uy, crossF: uf } = up;
	const { crossY: ly, crossF: lf } = low;
	let c = 0;
	for ( let step = 0; step < iterations; step ++ ) {

		let iu = 0;
		for ( let k = 1; k < uy.length; k ++ ) if ( uy[ k ] + uf[ k ] * c < uy[ iu ] + uf[ iu ] * c ) iu = k;
		let il = 0;
		for ( let k = 1; k < ly.length; k ++ ) if ( ly[ k ] + lf[ k ] * c > ly[ il ] + lf[ il ] * c ) il = k;
		const gap = ( uy[ iu ] + uf[ iu ] * c ) - ( ly[ il ] + lf[ il ] * c );
		const slope = lf[ il ] - uf[ iu ];
		if ( slope <= 0 || Math.abs( gap - target ) < 1e-9 ) break;
		c += ( gap - target ) / slope;

	}

	closure[ 1 ] = c;

}
