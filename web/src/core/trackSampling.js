// Sampling an utterance's parameter tracks at a time t: linear interpolation between the two
// frames around t of every track, written into the parameter array the articulation reads.
//
// The server sends tracks as { name: [value per frame] } at `rate_hz` (frame i at t = i / rate_hz).
// packTracks() lays them out once, frame-major (frame i's values together, so one sample reads
// two short runs of memory), with each track's slot in the target array and its range;
// sampleTracks() is the per-frame kernel: it allocates nothing and writes only the slots of the
// packed tracks, so parameters without a track keep their value. Pure: no DOM, no three.js.
//
//   const packed = packTracks( utterance.tracks, utterance.rate_hz, state.names, state );
//   sampleTracks( packed, t, state.values );   // every frame

/**
 * Pack tracks for sampling.
 * @param {Object<string, number[]>} tracks one array per parameter, all of the same length
 * @param {number} rateHz frames per second (frame i at t = i / rateHz)
 * @param {string[]} names the target array's parameter order; tracks of other names are left out
 * @param {{ minimum?: Float32Array, maximum?: Float32Array }} range per slot of `names` (a
 *   ParamState): sampled values are clamped into it; without it they are not clamped
 * @returns {{ data: Float32Array, count: number, frames: number, rateHz: number,
 *   slots: Int32Array, minimum: Float32Array, maximum: Float32Array, names: string[] }}
 *   data[ i * count + k ] is track k at frame i; slots[ k ] its index in the target
 */
export function packTracks( tracks, rateHz, names, { minimum = null, maximum = null } = {} ) {

	if ( ! ( rateHz > 0 ) ) throw new RangeError( `tracks need a positive rate, got ${ rateHz }` );
	const used = names.filter( ( name ) => Array.isArray( tracks?.[ name ] ) );
	if ( used.length === 0 ) throw new RangeError( `no track for any parameter (tracks: ${ Object.keys( tracks ?? {} ).join( ', ' ) || 'none' })` );
	const frames = tracks[ used[ 0 ] ].length;
	if ( frames < 1 ) throw new RangeError( 'tracks need at least one frame' );
	for ( const name of used ) {

		if ( tracks[ name ].length !== frames ) throw new RangeError( `track "${ name }" has ${ tracks[ name ].length } frames, not ${ frames }` );

	}

	const count = used.length;
	const data = new Float32Array( frames * count );
	const slots = new Int32Array( count );
	const low = new Float32Array( count ).fill( - Infinity );
	const high = new Float32Array( count ).fill( Infinity );
	used.forEach( ( name, k ) => {

		const slot = names.indexOf( name );
		slots[ k ] = slot;
		if ( minimum ) low[ k ] = minimum[ slot ];
		if ( maximum ) high[ k ] = maximum[ slot ];
		const track = tracks[ name ];
		for ( let i = 0; i < frames; i ++ ) data[ i * count + k ] = track[ i ];

	} );
	return { data, count, frames, rateHz, slots, minimum: low, maximum: high, names: used };

}

/**
 * Write every packed track's value at time `t` (seconds) into target[ slots[ k ] ]: linear
 * interpolation between frames floor( t * rateHz ) and the next; before the first frame the first
 * value, after the last the last. Values are clamped to the packed range. Allocates nothing.
 * Returns the (fractional) frame position sampled.
 */
export function sampleTracks( packed, t, target ) {

	const { data, count, frames, slots, minimum, maximum } = packed;
	let f = t * packed.rateHz;
	if ( ! ( f > 0 ) ) f = 0; // also NaN
	const last = frames - 1;
	if ( f > last ) f = last;
	const i0 = Math.floor( f );
	const i1 = i0 < last ? i0 + 1 : last;
	const w = f - i0;
	const a = i0 * count;
	const b = i1 * count;
	for ( let k = 0; k < count; k ++ ) {

		const v0 = data[ a + k ];
		let v = v0 + w * ( data[ b + k ] - v0 );
		if ( v < minimum[ k ] ) v = minimum[ k ];
		else if ( v > maximum[ k ] ) v = maximum[ k ];
		target[ slots[ k ] ] = v;

	}

	return f;

}

/** The duration the packed tracks cover, seconds (the last frame's time). */
export function trackDuration( packed ) {

	return ( packed.frames - 1 ) / packed.rateHz;

}
