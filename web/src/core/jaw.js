// The jaw pose (twin of server/glasshead/geometry/jaw.py): opening as a rotation about the
// temporomandibular axis (z-parallel, through the condyles) plus a forward slide that grows
// linearly with the angle.
//
// A pose is 12 numbers, a row-major 3 x 4 matrix [ R | t ]: p' = R p + t, R the rotation by
// -opening about +z (the chin, at +x, goes down), t = pivot - R pivot + opening * slide.
// Points that ride on the jaw partly move to p + w ( pose( p ) - p ).

/** Numbers in a pose: a row-major 3 x 4 matrix. */
export const POSE_LENGTH = 3 * 4;

/**
 * Pose for an opening in degrees and the jaw block of the rig definition.
 * @param {number} openingDeg
 * @param {{ pivot: number[], translation_per_degree: number[] }} jaw
 * @param {Float64Array} target length POSE_LENGTH
 * @returns {Float64Array} target
 */
export function jawPose( openingDeg, jaw, target ) {

	if ( ! Number.isFinite( openingDeg ) ) throw new RangeError( `jaw opening must be finite, got ${openingDeg}` );
	const angle = - openingDeg * Math.PI / 180;
	const c = Math.cos( angle );
	const s = Math.sin( angle );
	const px = jaw.pivot[ 0 ];
	const py = jaw.pivot[ 1 ];
	target[ 0 ] = c; target[ 1 ] = - s; target[ 2 ] = 0; target[ 3 ] = px - ( c * px - s * py ) + openingDeg * jaw.translation_per_degree[ 0 ];
	target[ 4 ] = s; target[ 5 ] = c; target[ 6 ] = 0; target[ 7 ] = py - ( s * px + c * py ) + openingDeg * jaw.translation_per_degree[ 1 ];
	target[ 8 ] = 0; target[ 9 ] = 0; target[ 10 ] = 1; target[ 11 ] = 0;
	return target;

}

/**
 * Move `count` points with the jaw, each by its weight, in place or into target.
 * @param {Float64Array} pose from jawPose()
 * @param {Float32Array|Float64Array} points flat coordinates, `stride` numbers per point (2: x y in
 *   the mid-sagittal plane; 3: x y z)
 * @param {number} count
 * @param {number} stride 2 or 3
 * @param {ArrayLike<number>|null} weights one per point, or null for all 1
 * @param {Float32Array|Float64Array} target may be `points`
 * @returns target
 */
export function applyJawPose( pose, points, count, stride, weights, target ) {

	for ( let k = 0; k < count; k ++ ) {

		const o = k * stride;
		const x = points[ o ];
		const y = points[ o + 1 ];
		const w = weights === null ? 1 : weights[ k ];
		const mx = pose[ 0 ] * x + pose[ 1 ] * y + pose[ 3 ];
		const my = pose[ 4 ] * x + pose[ 5 ] * y + pose[ 7 ];
		target[ o ] = x + w * ( mx - x );
		target[ o + 1 ] = y + w * ( my - y );
		if ( stride === 3 ) target[ o + 2 ] = points[ o + 2 ];

	}

	return target;

}

// --- Screw decomposition (for the face rig's skinning, faceRig.js) -------------------------------

/** Numbers in a screw: axis u (3), angle, slide along u, t_perp (3), u x t_perp (3). */
export const SCREW_SIZE = 3 + 1 + 1 + 3 + 3;
/** Below this rotation (radians) the jaw motion is a pure translation. */
export const SCREW_MIN_ANGLE = 1e-9;

/**
 * Screw decomposition of a jaw pose (face_rig.jaw_screw): the rigid motion as a turn about an
 * axis and a slide along it (Chasles' theorem). Writes axis u, angle, slide along u, the
 * translation's part perpendicular to u, t_perp, and u x t_perp.
 * @param {ArrayLike<number>} pose row-major 3 x 4 [ R | t ] (jawPose())
 * @param {Float64Array} target length SCREW_SIZE
 */
export function jawScrew( pose, target ) {

	const sx = pose[ 9 ] - pose[ 6 ];
	const sy = pose[ 2 ] - pose[ 8 ];
	const sz = pose[ 4 ] - pose[ 1 ];
	const length = Math.sqrt( sx * sx + sy * sy + sz * sz );
	const sinAngle = 0.5 * length;
	const cosAngle = 0.5 * ( pose[ 0 ] + pose[ 5 ] + pose[ 10 ] - 1 );
	let angle = Math.atan2( sinAngle, cosAngle );
	let ux = 0;
	let uy = 0;
	let uz = 1;
	if ( angle < SCREW_MIN_ANGLE ) {

		angle = 0;

	} else {

		ux = sx / length; uy = sy / length; uz = sz / length;

	}

	const tx = pose[ 3 ];
	const ty = pose[ 7 ];
	const tz = pose[ 11 ];
	const slide = ux * tx + uy * ty + uz * tz;
	const px = tx - slide * ux;
	const py = ty - slide * uy;
	const pz = tz - slide * uz;
	target[ 0 ] = ux; target[ 1 ] = uy; target[ 2 ] = uz; target[ 3 ] = angle; target[ 4 ] = slide;
	target[ 5 ] = px; target[ 6 ] = py; target[ 7 ] = pz;
	target[ 8 ] = uy * pz - uz * py; target[ 9 ] = uz * px - ux * pz; target[ 10 ] = ux * py - uy * px;
	return target;

}
