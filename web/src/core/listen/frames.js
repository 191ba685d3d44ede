// Framing: analysis windows, pre-emphasis, where a frame sits in a stream, and the stream itself.
//
// Sample n of a stream is at time n / sampleRate; frame k of every analysis is centred on the hop
// time t = k * HOP_S. A window of length L centred on sample c covers [ c - floor( L / 2 ),
// c - floor( L / 2 ) + L ). Samples before the start of the signal are zeros.

/**
 * Praat's Gaussian window (Sound_to_Formant): exp( -48 (i - mid)^2 / (L + 1)^2 ), lowered so that
 * it reaches 0 at the edges (its value there is exp( -12 )) and rescaled to 1 at the centre.
 * @param {number} length samples
 * @returns {Float64Array}
 */
export function gaussianWindow( length ) {

	const window = new Float64Array( length );
	const mid = 0.5 * ( length - 1 ), edge = Math.exp( - 12 ), width = ( length + 1 ) * ( length + 1 );
	for ( let i = 0; i < length; i ++ ) window[ i ] = ( Math.exp( - 48 * ( i - mid ) * ( i - mid ) / width ) - edge ) / ( 1 - edge );
	return window;

}

/**
 * Hann window, sampled at the centres of L equal parts so that no sample is wasted on a zero:
 * 0.5 - 0.5 cos( 2 pi (i + 0.5) / L ).
 * @param {number} length samples
 * @returns {Float64Array}
 */
export function hannWindow( length ) {

	const window = new Float64Array( length );
	for ( let i = 0; i < length; i ++ ) window[ i ] = 0.5 - 0.5 * Math.cos( 2 * Math.PI * ( i + 0.5 ) / length );
	return window;

}

/** The modified Bessel function I0 by its power series (converges quickly for the betas used). */
export function besselI0( x ) {

	let sum = 1, term = 1;
	const q = 0.25 * x * x;
	for ( let k = 1; k < 200; k ++ ) {

		term *= q / ( k * k );
		sum += term;
		if ( term < 1e-17 * sum ) break;

	}

	return sum;

}

/**
 * Kaiser window of 2 half + 1 samples: I0( beta sqrt( 1 - x^2 ) ), x from -1 to 1 across it
 * (not normalised: weighted means divide by the window's sum).
 * @param {number} half samples each side of the centre
 * @param {number} beta shape (Praat's intensity uses 2 pi^2 + 0.5)
 * @returns {Float64Array}
 */
export function kaiserWindow( half, beta ) {

	const window = new Float64Array( 2 * half + 1 );
	for ( let i = - half; i <= half; i ++ ) {

		const x = half === 0 ? 0 : i / half;
		window[ i + half ] = besselI0( beta * Math.sqrt( Math.max( 0, 1 - x * x ) ) );

	}

	return window;

}

/**
 * The first-order pre-emphasis factor for +6 dB per octave above `fromHz`: y[n] = x[n] - a x[n-1]
 * with a = exp( -2 pi fromHz / sampleRate ) (Praat's Sound_preEmphasize).
 */
export function preEmphasisFactor( fromHz, sampleRate ) {

	return Math.exp( - 2 * Math.PI * fromHz / sampleRate );

}

/** The sample nearest to time t in a stream of `sampleRate`. */
export function centreSample( t, sampleRate ) {

	return Math.round( t * sampleRate );

}

/** The first sample of a window of `length` centred on sample `centre`. */
export function windowStart( centre, length ) {

	return centre - Math.floor( length / 2 );

}

/**
 * A growing run of samples of which only the recent part is kept: absolute sample indices stay
 * valid as old samples are dropped. Starts with `lead` zeros before sample 0, so that a window
 * reaching before the start of the signal reads zeros.
 */
export class SampleStream {

	/**
	 * @param {number} lead zeros kept before sample 0
	 * @param {number} [capacity] initial room (grows by doubling)
	 */
	constructor( lead, capacity = 4096 ) {

		this.data = new Float32Array( Math.max( capacity, 2 * lead + 16 ) );
		/** Absolute index of data[ 0 ]. */
		this.base = - lead;
		/** Absolute index one past the last sample held. */
		this.end = 0;

	}

	/** Index into `data` of absolute sample `n` (which must be held). */
	offset( n ) {

		return n - this.base;

	}

	/** Make room for `count` more samples; returns the index into `data` where they go. */
	reserve( count ) {

		const used = this.end - this.base;
		if ( used + count > this.data.length ) {

			let size = this.data.length;
			while ( used + count > size ) size *= 2;
			const grown = new Float32Array( size );
			grown.set( this.data.subarray( 0, used ) );
			this.data = grown;

		}

		return used;

	}

	/** Append samples[ from .. to ). */
	append( samples, from = 0, to = samples.length ) {

		const at = this.reserve( to - from );
		this.data.set( from === 0 && to === samples.length ? samples : samples.subarray( from, to ), at );
		this.end += to - from;

	}

	/** Append `count` zeros. */
	appendZeros( count ) {

		const at = this.reserve( count );
		this.data.fill( 0, at, at + count );
		this.end += count;

	}

	/** Forget the samples before absolute index `n`, moving the rest to the front when that pays. */
	discardBefore( n ) {

		const drop = Math.min( n, this.end ) - this.base;
		if ( drop <= 0 || drop < this.data.length >> 1 ) return; // move only when half is stale
		this.data.copyWithin( 0, drop, this.end - this.base );
		this.base += drop;

	}

}
