// How the skin is drawn at a given transparency (pure; unit-tested in Node).
//
// The skin (face_skin and head_shell) is drawn after the opaque anatomy inside it, in three
// ordered passes that share its geometry:
//   1. back faces   (the inside of the far side of the head), blended, no depth write;
//   2. a depth-only pre-pass of the front faces, so that only the nearest skin layer is blended
//      (the nose does not show through the cheek);
//   3. front faces, blended with depth test "less or equal" against the pre-pass.
// At 0 % the skin is an ordinary opaque surface; at 100 % it is not drawn at all.

/** Render orders: the opaque anatomy uses 0 and is drawn first regardless (opaque queue). */
export const SKIN_RENDER_ORDER = Object.freeze( { back: 10, prepass: 11, front: 12 } );

/** Strength of the fresnel rim that keeps the silhouette readable when the skin is faint. */
export const SKIN_RIM_STRENGTH = 0.55;

/**
 * The pass settings for skin transparency `percent` (0 = opaque skin, 100 = no skin).
 * Returns { visible, transparent, opacity, depthWrite, prepass, rim }.
 */
export function skinPassState( percent ) {

	if ( typeof percent !== 'number' || ! Number.isFinite( percent ) || percent < 0 || percent > 100 ) {

		throw new RangeError( `skin transparency must be a number from 0 to 100, got ${ percent }` );

	}

	const opacity = 1 - percent / 100;
	if ( percent === 100 ) {

		return { visible: false, transparent: true, opacity: 0, depthWrite: false, prepass: false, rim: 0 };

	}

	if ( percent === 0 ) {

		return { visible: true, transparent: false, opacity: 1, depthWrite: true, prepass: false, rim: 0 };

	}

	// The rim fades in with transparency so the opaque and nearly opaque skin look unchanged.
	return {
		visible: true,
		transparent: true,
		opacity,
		depthWrite: false,
		prepass: true,
		rim: SKIN_RIM_STRENGTH * Math.min( 1, percent / 50 ),
	};

}

/** How far the lips fade with the skin: at 100 % skin transparency they keep 1 - LIP_FADE. */
export const LIP_FADE = 0.7;

/** Render order of the lips: after the opaque anatomy and the markers over it, before the skin. */
export const LIP_RENDER_ORDER = 9;

/**
 * Opacity of the lips at skin transparency `percent`. The lips are soft tissue of the face and
 * fade with it, but never vanish, so the mouth stays in place while the teeth show through.
 */
export function lipOpacity( percent ) {

	skinPassState( percent ); // validates
	return 1 - LIP_FADE * percent / 100;

}
