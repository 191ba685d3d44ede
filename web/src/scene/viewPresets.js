// Camera poses for the named views, and the interpolation used to fly between them.
// Pure functions over plain arrays (no three.js), so they are unit-tested in Node.
//
// Project frame: +x anterior, +y superior, +z the subject's left. The cutaway keeps the left half
// (z >= 0), so its cut face looks toward -z: the profile camera sits on the -z side, where it sees
// the mid-sagittal section when the cutaway is on, and the subject's right cheek when it is off.

export const VIEW_NAMES = Object.freeze( [ 'front', 'profile', 'three-quarter' ] );

/** Unit directions from the target to the camera, before elevation. */
const AZIMUTH_DEG = Object.freeze( {
	front: 0, // on +x, looking back at the face
	'three-quarter': 45, // between the face and the cut side
	profile: 90, // on -z, looking at the section
} );

/** A slight look down from above eye level reads more naturally than a dead-level camera. */
export const VIEW_ELEVATION_DEG = 8;

/**
 * The unit vector from the target toward the camera for `name`.
 * Azimuth is measured from +x toward -z, elevation from the horizontal toward +y.
 */
export function viewDirection( name, target = [ 0, 0, 0 ] ) {

	if ( ! ( name in AZIMUTH_DEG ) ) {

		throw new RangeError( `unknown view "${ name }"; expected one of ${ VIEW_NAMES.join( ', ' ) }` );

	}

	const azimuth = AZIMUTH_DEG[ name ] * Math.PI / 180;
	const elevation = VIEW_ELEVATION_DEG * Math.PI / 180;
	target[ 0 ] = Math.cos( elevation ) * Math.cos( azimuth );
	target[ 1 ] = Math.sin( elevation );
	target[ 2 ] = - Math.cos( elevation ) * Math.sin( azimuth );
	return target;

}

/**
 * Camera distance at which a sphere of `radius` fills the view with a margin.
 * fovDeg is the vertical field of view; aspect = width / height (a narrow view fits the width).
 */
export function fitDistance( radius, fovDeg, aspect = 1, margin = 1.1 ) {

	if ( ! ( radius > 0 ) || ! ( fovDeg > 0 && fovDeg < 180 ) || ! ( aspect > 0 ) ) {

		throw new RangeError( `fitDistance needs radius > 0, 0 < fov < 180 and aspect > 0 (got ${ radius }, ${ fovDeg }, ${ aspect })` );

	}

	const halfV = fovDeg * Math.PI / 360;
	const halfH = Math.atan( Math.tan( halfV ) * aspect );
	return margin * radius / Math.sin( Math.min( halfV, halfH ) );

}

/**
 * The pose of view `name` around a bounding sphere (center [x, y, z], radius in mm).
 * Returns { position: [x, y, z], target: [x, y, z] }.
 */
export function viewPose( name, center, radius, fovDeg, aspect = 1 ) {

	const direction = viewDirection( name );
	const distance = fitDistance( radius, fovDeg, aspect );
	return {
		position: [
			center[ 0 ] + direction[ 0 ] * distance,
			center[ 1 ] + direction[ 1 ] * distance,
			center[ 2 ] + direction[ 2 ] * distance,
		],
		target: [ center[ 0 ], center[ 1 ], center[ 2 ] ],
	};

}

/** Smooth ease in and out on [0, 1] (a cubic smoothstep). */
export function easeInOut( s ) {

	const x = Math.min( 1, Math.max( 0, s ) );
	return x * x * ( 3 - 2 * x );

}

/**
 * The pose a fraction `s` of the way from pose `a` to pose `b`, written into `out`
 * ({ position, target } arrays). The camera swings around the target (the direction is slerped and
 * the distance interpolated) rather than cutting straight through the head.
 */
export function interpolatePose( a, b, s, out ) {

	for ( let i = 0; i < 3; i ++ ) out.target[ i ] = a.target[ i ] + ( b.target[ i ] - a.target[ i ] ) * s;

	let da = 0, db = 0;
	const ua = [ 0, 0, 0 ], ub = [ 0, 0, 0 ];
	for ( let i = 0; i < 3; i ++ ) {

		ua[ i ] = a.position[ i ] - a.target[ i ];
		ub[ i ] = b.position[ i ] - b.target[ i ];
		da += ua[ i ] * ua[ i ];
		db += ub[ i ] * ub[ i ];

	}

	da = Math.sqrt( da );
	db = Math.sqrt( db );
	let cos = 0;
	for ( let i = 0; i < 3; i ++ ) {

		ua[ i ] /= da;
		ub[ i ] /= db;
		cos += ua[ i ] * ub[ i ];

	}

	const angle = Math.acos( Math.min( 1, Math.max( - 1, cos ) ) );
	let wa = 1 - s, wb = s;
	if ( angle > 1e-6 && angle < Math.PI - 1e-6 ) {

		wa = Math.sin( ( 1 - s ) * angle ) / Math.sin( angle );
		wb = Math.sin( s * angle ) / Math.sin( angle );

	}

	const distance = da + ( db - da ) * s;
	let norm = 0;
	const u = [ 0, 0, 0 ];
	for ( let i = 0; i < 3; i ++ ) {

		u[ i ] = wa * ua[ i ] + wb * ub[ i ];
		norm += u[ i ] * u[ i ];

	}

	norm = Math.sqrt( norm ) || 1;
	for ( let i = 0; i < 3; i ++ ) out.position[ i ] = out.target[ i ] + u[ i ] / norm * distance;
	return out;

}
