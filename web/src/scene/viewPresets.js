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

/** The mouth and throat, lips to larynx: what the speech player and a lesson at zoom 1 frame. */
export const MOUTH_AND_THROAT = Object.freeze( { center: Object.freeze( [ - 4, - 8, 0 ] ), radius: 68 } );
/** The oral cavity, lips to velum and tongue to palate: where the camera closes in as it zooms. */
const ORAL_CAVITY_CENTER = Object.freeze( [ - 8, 4, 0 ] );

/**
 * The pose of view `name` at `zoom` (1 frames the mouth and throat; 2 is twice as close, and the
 * camera turns onto the oral cavity as it comes in, reaching it at zoom 2).
 */
export function zoomedPose( name, zoom, fovDeg, aspect = 1 ) {

	const z = Math.max( 1, Number( zoom ) || 1 );
	const toward = Math.min( z - 1, 1 );
	const center = MOUTH_AND_THROAT.center.map( ( c, i ) => c + ( ORAL_CAVITY_CENTER[ i ] - c ) * toward );
	return viewPose( name, center, MOUTH_AND_THROAT.radius / z, fovDeg, aspect );

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
