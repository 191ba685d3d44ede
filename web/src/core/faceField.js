// The lip field of the face rig: per-vertex coefficients of the shape offsets (protrusion,
// rounding, upper-lip raise, lower-lip tuck) and of the closure, computed once from a vertex's rest
// position and jaw weight (face_rig.field_coefficients and smooth_bump in
// server/glasshead/geometry/face_rig.py). faceRig.js reads them per pose.

import { FACE_RIG_COEFF_COUNT } from './constants.js';

/** Per-vertex field coefficients, COEFF_COUNT per vertex (as in face_rig.py). */
export const COEFF_PROTRUSION = 0;
export const COEFF_ROUND_X = 1;
export const COEFF_ROUND_Z = 2;
export const COEFF_RAISE = 3;
export const COEFF_TUCK = 4;
export const COEFF_CLOSURE = 5;
export const COEFF_COUNT = FACE_RIG_COEFF_COUNT;

/** The quintic smoothstep 6t^5 - 15t^4 + 10t^3 of t clamped to [0, 1]. */
function smoothstep5( t ) {

	const c = t < 0 ? 0 : ( t > 1 ? 1 : t );
	return c * c * c * ( c * ( 6 * c - 15 ) + 10 );

}

/** Compact bump with a flat top (face_rig.smooth_bump): 1 on the plateau, 0 outside the radii. */
export function bumpAt( bump, x, y, z ) {

	const dx = ( x - bump.centre[ 0 ] ) / bump.radii[ 0 ];
	const dy = ( y - bump.centre[ 1 ] ) / bump.radii[ 1 ];
	const dz = ( z - bump.centre[ 2 ] ) / bump.radii[ 2 ];
	const r = Math.sqrt( dx * dx + dy * dy + dz * dz );
	return smoothstep5( ( 1 - r ) / ( 1 - bump.plateau ) );

}

/**
 * The field coefficients of a mesh (face_rig.field_coefficients), and the vertices they or the
 * jaw can move.
 * @param {Float64Array} rest rest positions, xyz per vertex
 * @param {Float64Array} weights jaw weight per vertex
 * @param {object} field the rig definition's `field`
 * @returns {{ coeffs: Float64Array, moving: Uint32Array }} COEFF_COUNT coefficients per vertex,
 *   and the vertices whose weight or coefficients are not all 0
 */
export function fieldCoefficients( rest, weights, field ) {

	const count = weights.length;
	const coeffs = new Float64Array( COEFF_COUNT * count );
	const { mouth: mouthBump, raise: raiseBump, tuck: tuckBump } = field.bumps;
	const halfWidth = field.mouth_half_width;
	const moving = [];
	for ( let v = 0; v < count; v ++ ) {

		const x = rest[ 3 * v ];
		const y = rest[ 3 * v + 1 ];
		const z = rest[ 3 * v + 2 ];
		const w = weights[ v ];
		const mouth = bumpAt( mouthBump, x, y, z );
		const zn = z / halfWidth;
		const medial = zn * Math.exp( 0.5 * ( 1 - zn * zn ) );
		const o = COEFF_COUNT * v;
		coeffs[ o + COEFF_PROTRUSION ] = mouth;
		coeffs[ o + COEFF_ROUND_X ] = mouth * ( field.rounding_forward * Math.exp( - zn * zn ) + field.rounding_along_arch * Math.abs( medial ) );
		coeffs[ o + COEFF_ROUND_Z ] = - mouth * medial;
		coeffs[ o + COEFF_RAISE ] = bumpAt( raiseBump, x, y, z ) * ( 1 - w );
		coeffs[ o + COEFF_TUCK ] = bumpAt( tuckBump, x, y, z ) * w;
		coeffs[ o + COEFF_CLOSURE ] = mouth * ( w - field.closure_upper_share );
		let still = w === 0;
		for ( let k = 0; k < COEFF_COUNT && still; k ++ ) still = coeffs[ o + k ] === 0;
		if ( ! still ) moving.push( v );

	}

	return { coeffs, moving: Uint32Array.from( moving ) };

}
