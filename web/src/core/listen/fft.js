// A real FFT of a power-of-two size: the spectrum of n real samples through one complex FFT of
// n / 2 points (even samples as the real part, odd ones as the imaginary part) and a split step
// (Cooley-Tukey radix-2, decimation in time; the packing as in Press et al., Numerical Recipes,
// 3rd ed., section 12.3). Tables are made once per size; forward() and inverse() allocate nothing.
//
//   const fft = createRealFft( 512 );
//   fft.forward( frame, re, im );     // frame: 512 samples; re, im: 257 bins (0 .. Nyquist)
//   fft.inverse( re, im, frame );     // back to the 512 samples
//
// Bin k is at frequency k * sampleRate / n. No scaling forward; inverse() divides by n, so
// inverse( forward( x ) ) is x.

/**
 * Tables and scratch for real FFTs of `size` points.
 * @param {number} size a power of two, at least 4
 * @returns {{ size: number, bins: number,
 *   forward: ( input: ArrayLike<number>, re: Float64Array, im: Float64Array ) => void,
 *   inverse: ( re: Float64Array, im: Float64Array, output: Float32Array | Float64Array ) => void }}
 */
export function createRealFft( size ) {

	if ( ! Number.isInteger( size ) || size < 4 || ( size & ( size - 1 ) ) !== 0 ) {

		throw new RangeError( `FFT size must be a power of two of at least 4, got ${ size }` );

	}

	const half = size >> 1;
	const bits = Math.log2( half );
	const reversed = new Uint32Array( half );
	for ( let i = 0; i < half; i ++ ) {

		let r = 0;
		for ( let b = 0, v = i; b < bits; b ++, v >>= 1 ) r = ( r << 1 ) | ( v & 1 );
		reversed[ i ] = r;

	}

	// Twiddles of the half-size complex FFT: exp( sign 2 pi i k / half ), k < half / 2.
	const cosHalf = new Float64Array( Math.max( 1, half >> 1 ) );
	const sinHalf = new Float64Array( Math.max( 1, half >> 1 ) );
	for ( let k = 0; k < half >> 1; k ++ ) {

		cosHalf[ k ] = Math.cos( 2 * Math.PI * k / half );
		sinHalf[ k ] = Math.sin( 2 * Math.PI * k / half );

	}

	// Twiddles of the split step: exp( -2 pi i k / size ), k <= half.
	const cosFull = new Float64Array( half + 1 );
	const sinFull = new Float64Array( half + 1 );
	for ( let k = 0; k <= half; k ++ ) {

		cosFull[ k ] = Math.cos( 2 * Math.PI * k / size );
		sinFull[ k ] = - Math.sin( 2 * Math.PI * k / size );

	}

	const zr = new Float64Array( half );
	const zi = new Float64Array( half );

	/** In-place complex FFT of zr + i zi (half points); sign -1 forward, +1 backward (unscaled). */
	function complexFft( sign ) {

		for ( let i = 0; i < half; i ++ ) {

			const j = reversed[ i ];
			if ( j > i ) {

				let t = zr[ i ]; zr[ i ] = zr[ j ]; zr[ j ] = t;
				t = zi[ i ]; zi[ i ] = zi[ j ]; zi[ j ] = t;

			}

		}

		for ( let span = 1; span < half; span <<= 1 ) {

			const stride = half / ( span << 1 ); // twiddle index step at this stage
			for ( let start = 0; start < half; start += span << 1 ) {

				for ( let k = 0; k < span; k ++ ) {

					const wr = cosHalf[ k * stride ];
					const wi = sign * sinHalf[ k * stride ];
					const a = start + k, b = a + span;
					const tr = zr[ b ] * wr - zi[ b ] * wi;
					const ti = zr[ b ] * wi + zi[ b ] * wr;
					zr[ b ] = zr[ a ] - tr; zi[ b ] = zi[ a ] - ti;
					zr[ a ] += tr; zi[ a ] += ti;

				}

			}

		}

	}

	/** Spectrum of input[ 0 .. size ) into re, im [ 0 .. size / 2 ]. */
	function forward( input, re, im ) {

		for ( let k = 0; k < half; k ++ ) {

			zr[ k ] = input[ 2 * k ];
			zi[ k ] = input[ 2 * k + 1 ];

		}

		complexFft( - 1 );
		// Split: X[k] = E[k] + W^k O[k], E = (Z[k] + conj Z[m-k]) / 2, O = (Z[k] - conj Z[m-k]) / 2i.
		for ( let k = 0; k <= half; k ++ ) {

			const a = k === half ? 0 : k, b = k === 0 ? 0 : half - k;
			const er = 0.5 * ( zr[ a ] + zr[ b ] ), ei = 0.5 * ( zi[ a ] - zi[ b ] );
			const or = 0.5 * ( zi[ a ] + zi[ b ] ), oi = - 0.5 * ( zr[ a ] - zr[ b ] );
			const wr = cosFull[ k ], wi = sinFull[ k ];
			re[ k ] = er + wr * or - wi * oi;
			im[ k ] = ei + wr * oi + wi * or;

		}

	}

	/** Samples output[ 0 .. size ) of the spectrum re, im [ 0 .. size / 2 ] (divided by size). */
	function inverse( re, im, output ) {

		// E = (X[k] + conj X[m-k]) / 2, O = (X[k] - conj X[m-k]) conj(W^k) / 2, Z = E + i O.
		for ( let k = 0; k < half; k ++ ) {

			const b = half - k;
			const er = 0.5 * ( re[ k ] + re[ b ] ), ei = 0.5 * ( im[ k ] - im[ b ] );
			const dr = 0.5 * ( re[ k ] - re[ b ] ), di = 0.5 * ( im[ k ] + im[ b ] );
			const wr = cosFull[ k ], wi = - sinFull[ k ];
			const or = dr * wr - di * wi, oi = dr * wi + di * wr;
			zr[ k ] = er - oi;
			zi[ k ] = ei + or;

		}

		complexFft( 1 );
		const scale = 1 / half; // the half-size inverse FFT's 1 / m
		for ( let k = 0; k < half; k ++ ) {

			output[ 2 * k ] = zr[ k ] * scale;
			output[ 2 * k + 1 ] = zi[ k ] * scale;

		}

	}

	return { size, bins: half + 1, forward, inverse };

}

/** The smallest power of two at least `n` (and at least 4). */
export function nextPowerOfTwo( n ) {

	let size = 4;
	while ( size < n ) size <<= 1;
	return size;

}
