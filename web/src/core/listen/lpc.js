// Formants by linear prediction, as Praat's "To Formant (burg)" (Sound_to_Formant.cpp): the
// sound resampled to twice the formant ceiling (resample.js), pre-emphasised from 50 Hz, a
// Gaussian window of 2 x 25 ms per frame, LPC coefficients of order 2 x 5 by Burg's method, and
// the roots of the LPC polynomial: each root z above the real axis whose frequency
// |arg z| fs / 2 pi lies between 50 Hz and the ceiling less 50 Hz is a formant, of bandwidth
// -ln|z| fs / pi; sorted by frequency.
//
// Burg's method: J. P. Burg (1975), "Maximum entropy spectral analysis", PhD thesis, Stanford;
// in the form of Press et al., Numerical Recipes, 3rd ed., section 13.6 (memcof), which Praat's
// VECburg also follows: each reflection coefficient minimises the sum of the forward and
// backward prediction errors, so the filter is stable and needs no autocorrelation window.

import { gaussianWindow, preEmphasisFactor } from './frames.js';
import { FORMANT_COUNT, FORMANT_MARGIN_HZ, FORMANT_WINDOW_S, PREEMPHASIS_FROM_HZ } from './params.js';
import { fixIntoUnitCircle, polynomialRoots } from './roots.js';

/**
 * LPC by Burg's method of x[ start .. start + n ): writes a[0..order] with a[0] = 1 and
 * A(z) = sum_k a[k] z^-k, the prediction error filter (x[i] + sum_k a[k] x[i - k] is the
 * error). Returns the mean squared prediction error (the gain squared), 0 for a silent frame
 * (then a is 1, 0, 0, ...). Allocates nothing.
 * @param {Float32Array | Float64Array} x
 * @param {number} start
 * @param {number} n samples, more than order
 * @param {number} order
 * @param {Float64Array} a receives order + 1 coefficients
 * @param {Float64Array} forward scratch of n
 * @param {Float64Array} backward scratch of n
 * @returns {number}
 */
export function burg( x, start, n, order, a, forward, backward ) {

	let error = 0;
	for ( let i = 0; i < n; i ++ ) {

		const v = x[ start + i ];
		forward[ i ] = v;
		backward[ i ] = v;
		error += v * v;

	}

	error /= n;
	a[ 0 ] = 1;
	for ( let k = 1; k <= order; k ++ ) a[ k ] = 0;
	if ( error === 0 ) return 0;
	for ( let m = 1; m <= order; m ++ ) {

		// The reflection coefficient that minimises forward plus backward error power.
		let num = 0, den = 0;
		for ( let i = m; i < n; i ++ ) {

			const f = forward[ i ], b = backward[ i - 1 ];
			num += f * b;
			den += f * f + b * b;

		}

		if ( den <= 0 ) break;
		const k = - 2 * num / den;
		// Levinson's update of the filter: a[i] += k a[m - i], in place from both ends.
		for ( let i = 1, j = m - 1; i <= j; i ++, j -- ) {

			const ai = a[ i ], aj = a[ j ];
			a[ i ] = ai + k * aj;
			if ( i !== j ) a[ j ] = aj + k * ai;

		}

		a[ m ] = k;
		// The errors of order m from those of order m - 1 (backward, so that b[i - 1] is still old).
		for ( let i = n - 1; i >= m; i -- ) {

			const f = forward[ i ];
			forward[ i ] = f + k * backward[ i - 1 ];
			backward[ i ] = backward[ i - 1 ] + k * f;

		}

		error *= 1 - k * k;

	}

	return error;

}

/**
 * Formants from the roots of A(z): those above the real axis between `margin` and
 * sampleRate / 2 - margin (Hz), sorted by frequency, into frequencies[] and bandwidths[] (Hz).
 * Returns how many.
 */
export function formantsFromRoots( re, im, count, sampleRate, margin, frequencies, bandwidths ) {

	const nyquist = sampleRate / 2;
	let found = 0;
	for ( let k = 0; k < count; k ++ ) {

		if ( im[ k ] < 0 ) continue;
		const f = Math.abs( Math.atan2( im[ k ], re[ k ] ) ) * nyquist / Math.PI;
		if ( ! ( f >= margin && f <= nyquist - margin ) ) continue; // (a NaN root is no formant either)
		// -ln|z| fs / pi, as -ln|z|^2 fs / 2 pi (Math.hypot would box its arguments on every call).
		const b = - 0.5 * Math.log( re[ k ] * re[ k ] + im[ k ] * im[ k ] ) * sampleRate / Math.PI;
		// Insertion into the sorted run.
		let at = found;
		while ( at > 0 && frequencies[ at - 1 ] > f ) {

			frequencies[ at ] = frequencies[ at - 1 ];
			bandwidths[ at ] = bandwidths[ at - 1 ];
			at --;

		}

		frequencies[ at ] = f;
		bandwidths[ at ] = b;
		found ++;

	}

	return found;

}

/**
 * Scratch and window of the formant analysis of a stream at `sampleRate` (twice the ceiling).
 * @param {{ sampleRate: number, formants?: number, windowS?: number, preEmphasisHz?: number }} options
 * @returns {object} frameLength: samples a frame reads (one more before it, for the pre-emphasis)
 */
export function createFormantAnalysis( { sampleRate, formants = FORMANT_COUNT, windowS = FORMANT_WINDOW_S, preEmphasisHz = PREEMPHASIS_FROM_HZ } ) {

	const order = 2 * formants;
	const frameLength = Math.floor( 2 * windowS * sampleRate );
	if ( frameLength <= order ) throw new RangeError( `formant window of ${ frameLength } samples is too short for order ${ order }` );
	return {
		sampleRate, order, frameLength,
		window: gaussianWindow( frameLength ),
		emphasis: preEmphasisFactor( preEmphasisHz, sampleRate ),
		frame: new Float64Array( frameLength ),
		forward: new Float64Array( frameLength ),
		backward: new Float64Array( frameLength ),
		a: new Float64Array( order + 1 ),
		poly: new Float64Array( order + 1 ),
		re: new Float64Array( order ), im: new Float64Array( order ), done: new Uint8Array( order ),
		frequencies: new Float64Array( order ), bandwidths: new Float64Array( order ),
		gain2: 0, count: 0,
	};

}

/**
 * Formants of the frame samples[ start .. start + frameLength ) (samples[ start - 1 ] is read
 * for the pre-emphasis): into analysis.frequencies / bandwidths [0 .. count), count returned.
 * analysis.a and analysis.gain2 keep the frame's LPC for lpcSpectrumDb(). Allocates nothing.
 */
export function analyseFormants( analysis, samples, start ) {

	const { frameLength, window, emphasis, frame, order, a, poly, re, im } = analysis;
	let sounding = false;
	for ( let i = 0; i < frameLength; i ++ ) {

		const v = samples[ start + i ] - emphasis * samples[ start + i - 1 ];
		frame[ i ] = v * window[ i ];
		if ( v !== 0 ) sounding = true;

	}

	analysis.count = 0;
	analysis.gain2 = 0;
	if ( ! sounding ) {

		a.fill( 0 );
		a[ 0 ] = 1;
		return 0; // Burg has nothing to fit in digital silence

	}

	analysis.gain2 = burg( frame, 0, frameLength, order, a, analysis.forward, analysis.backward );
	// A(z) z^order = z^order + a1 z^(order-1) + ... + a_order: the polynomial whose roots are the poles.
	for ( let k = 0; k <= order; k ++ ) poly[ k ] = a[ k ];
	polynomialRoots( poly, order, re, im, analysis.done );
	fixIntoUnitCircle( re, im, order );
	analysis.count = formantsFromRoots( re, im, order, analysis.sampleRate, FORMANT_MARGIN_HZ, analysis.frequencies, analysis.bandwidths );
	return analysis.count;

}

/**
 * The LPC spectrum 10 log10( gain2 / |A(e^iw)|^2 ) in dB at target.length frequencies evenly
 * from 0 to `maxHz` (both included): the smooth envelope whose peaks are the formants. dB re 1
 * (full scale squared per sample): compare levels within a spectrum, not across recordings.
 * Allocates nothing.
 * @param {Float64Array} a order + 1 coefficients, a[0] = 1
 * @param {number} order
 * @param {number} gain2 mean squared prediction error
 * @param {number} sampleRate of the analysed stream
 * @param {Float32Array | Float64Array} target receives dB
 * @param {number} [maxHz] defaults to sampleRate / 2
 */
export function lpcSpectrumDb( a, order, gain2, sampleRate, target, maxHz = sampleRate / 2 ) {

	const n = target.length;
	const floor = gain2 > 0 ? gain2 : 1e-30;
	for ( let bin = 0; bin < n; bin ++ ) {

		const w = 2 * Math.PI * ( n > 1 ? bin * maxHz / ( n - 1 ) : 0 ) / sampleRate;
		// A(e^iw) = sum_k a[k] e^(-iwk), the powers of e^(-iw) by rotation.
		const cr = Math.cos( w ), ci = - Math.sin( w );
		let pr = 1, pi = 0, sr = 0, si = 0;
		for ( let k = 0; k <= order; k ++ ) {

			sr += a[ k ] * pr;
			si += a[ k ] * pi;
			const t = pr * cr - pi * ci;
			pi = pr * ci + pi * cr;
			pr = t;

		}

		target[ bin ] = 10 * Math.log10( floor / Math.max( sr * sr + si * si, 1e-300 ) );

	}

	return target;

}
