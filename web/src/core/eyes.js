// Eyes in the face's eye openings: where each eyeball sits, where it looks and when it blinks.
// Pure functions over plain arrays (no three.js); the scene side is scene/Eyes.js.

/** Eye proportions and motion, in mm, degrees and seconds. */
export const EYE_MOTION = Object.freeze( {
	eyeballRadius: 12, // mm; an adult eyeball is about 24 mm across
	irisRadius: 5.8, // mm; a human iris is about 11 to 12 mm across
	pupilRadius: 1.9, // mm
	lidCover: 1.4, // mm of the iris under the upper lid at rest
	lidGap: 0.6, // mm between the eyeball and the lid sliding over it
	gazeLimit: 25, // degrees: the largest yaw or pitch the eyes turn toward the camera
	gazeTau: 0.09, // s: time constant of the eyes' approach to their target
	gazeSnap: 0.05, // degrees: closer than this, the eyes are at their target (and stop drawing)
	blinkDuration: 0.15, // s
	blinkClose: 0.4, // fraction of a blink spent closing (the rest opens, more slowly)
	blinkEvery: [ 4, 9 ], // s: a blink follows the last after a delay drawn uniformly from this range
} );

/**
 * The eyeball behind an opening with frame `frame` (openings.js loopFrame) and rim vertices
 * `loop` of `positions`: its centre sits on the opening's normal, as far back as puts the rim,
 * on average, on a sphere of the eyeball's radius (so the visible part is what the opening shows);
 * never so far forward that the eyeball stands out of the opening by more than 0.45 of its radius.
 * Returns { centre: [x, y, z], radius, depth } (depth: centre behind the rim's centre, mm).
 */
export function eyeballPlacement( positions, loop, frame, radius = EYE_MOTION.eyeballRadius ) {

	if ( ! ( radius > 0 ) ) throw new RangeError( `radius must be positive, got ${ radius }` );
	const { centre, normal } = frame;
	let depth = 0;
	for ( const v of loop ) {

		let h = 0, r2 = 0;
		for ( let k = 0; k < 3; k ++ ) {

			const d = positions[ 3 * v + k ] - centre[ k ];
			h += d * normal[ k ];
			r2 += d * d;

		}

		const rho2 = Math.max( 0, r2 - h * h );
		// The depth that puts this rim vertex on the sphere (or the rim plane through the centre).
		depth += ( Math.sqrt( Math.max( 0, radius * radius - rho2 ) ) - h ) / loop.length;

	}

	depth = Math.max( depth, 0.55 * radius );
	return { centre: centre.map( ( c, k ) => c - normal[ k ] * depth ), radius, depth };

}

/**
 * The straight-ahead gaze of a pair of eyes: the mean of their openings' normals (their sideways
 * tilts cancel), with `up` the world's +y made perpendicular to it and `side` = forward x up.
 * Returns { forward, up, side }, unit [x, y, z] arrays.
 */
export function gazeBasis( normals ) {

	const forward = [ 0, 0, 0 ];
	for ( const n of normals ) for ( let k = 0; k < 3; k ++ ) forward[ k ] += n[ k ];
	normalize( forward );
	const up = [ - forward[ 1 ] * forward[ 0 ], 1 - forward[ 1 ] * forward[ 1 ], - forward[ 1 ] * forward[ 2 ] ];
	normalize( up );
	const side = [
		forward[ 1 ] * up[ 2 ] - forward[ 2 ] * up[ 1 ],
		forward[ 2 ] * up[ 0 ] - forward[ 0 ] * up[ 2 ],
		forward[ 0 ] * up[ 1 ] - forward[ 1 ] * up[ 0 ],
	];
	return { forward, up, side };

}

function normalize( v ) {

	const length = Math.hypot( v[ 0 ], v[ 1 ], v[ 2 ] );
	if ( length < 1e-9 ) throw new RangeError( 'the eyes have no forward direction' );
	for ( let k = 0; k < 3; k ++ ) v[ k ] /= length;

}

/**
 * The gaze toward point (px, py, pz) from an eye at `from`, in `basis` (gazeBasis), as yaw (toward
 * `side`) and pitch (toward `up`) in degrees, each clamped to ±limit; a point behind the eyes gives
 * the straight-ahead gaze. Writes into target[0..1] and returns it; allocates nothing.
 */
export function gazeToward( px, py, pz, from, basis, limit, target ) {

	const dx = px - from[ 0 ], dy = py - from[ 1 ], dz = pz - from[ 2 ];
	const { forward: f, up: u, side: s } = basis;
	const a = dx * f[ 0 ] + dy * f[ 1 ] + dz * f[ 2 ];
	const b = dx * s[ 0 ] + dy * s[ 1 ] + dz * s[ 2 ];
	const c = dx * u[ 0 ] + dy * u[ 1 ] + dz * u[ 2 ];
	if ( a <= 0 ) {

		target[ 0 ] = 0;
		target[ 1 ] = 0;
		return target;

	}

	const degrees = 180 / Math.PI;
	target[ 0 ] = clamp( Math.atan2( b, a ) * degrees, limit );
	target[ 1 ] = clamp( Math.atan2( c, Math.hypot( a, b ) ) * degrees, limit );
	return target;

}

function clamp( x, limit ) {

	return Math.min( limit, Math.max( - limit, x ) );

}

/**
 * One step of the eyes' smooth approach from `current` to `target` degrees over dt seconds
 * (exponential, time constant tau); within `snap` degrees the eyes arrive.
 */
export function approachAngle( current, target, dt, tau = EYE_MOTION.gazeTau, snap = EYE_MOTION.gazeSnap ) {

	const next = target + ( current - target ) * Math.exp( - dt / tau );
	return Math.abs( next - target ) < snap ? target : next;

}

/**
 * How far closed a blink is (0 open, 1 shut) `t` seconds after it began: smooth closing over the
 * first `close` fraction of `duration`, smooth opening over the rest; 0 outside the blink.
 */
export function blinkClosure( t, duration = EYE_MOTION.blinkDuration, close = EYE_MOTION.blinkClose ) {

	if ( ! ( t > 0 ) || t >= duration ) return 0;
	const s = t / duration;
	return s < close ? smooth( s / close ) : 1 - smooth( ( s - close ) / ( 1 - close ) );

}

function smooth( x ) {

	return x * x * ( 3 - 2 * x );

}

/** The delay in seconds before the next blink, for a uniform random number u in [0, 1). */
export function nextBlinkDelay( u, [ low, high ] = EYE_MOTION.blinkEvery ) {

	return low + ( high - low ) * u;

}

/**
 * Where the upper lid's edge rests, as a closure (0: at the top of the opening, 1: at its bottom):
 * `cover` mm below the top of the iris of a straight-ahead eye. top and bottom: the opening's
 * extent along its up axis from its centre, mm.
 */
export function restClosure( top, bottom, irisRadius = EYE_MOTION.irisRadius, cover = EYE_MOTION.lidCover ) {

	if ( ! ( top > bottom ) ) throw new RangeError( `the opening's top (${ top }) must be above its bottom (${ bottom })` );
	return Math.min( 1, Math.max( 0, ( top - ( irisRadius - cover ) ) / ( top - bottom ) ) );

}

/**
 * The lid surface: each vertex of a flat patch across the opening (`flat`, 3 per vertex) moved
 * along `normal` just in front of the eyeball sphere (`gap` mm clear of it) where the sphere stands
 * in front of the patch. Writes into `out` (may be `flat`) and returns it.
 */
export function lidPositions( flat, normal, eyeball, gap, out ) {

	const { centre, radius } = eyeball;
	const r = radius + gap;
	for ( let i = 0; i < flat.length; i += 3 ) {

		const dx = flat[ i ] - centre[ 0 ], dy = flat[ i + 1 ] - centre[ 1 ], dz = flat[ i + 2 ] - centre[ 2 ];
		const h = dx * normal[ 0 ] + dy * normal[ 1 ] + dz * normal[ 2 ];
		const rho2 = dx * dx + dy * dy + dz * dz - h * h;
		const lift = rho2 < r * r ? Math.max( 0, Math.sqrt( r * r - rho2 ) - h ) : 0;
		for ( let k = 0; k < 3; k ++ ) out[ i + k ] = flat[ i + k ] + normal[ k ] * lift;

	}

	return out;

}
