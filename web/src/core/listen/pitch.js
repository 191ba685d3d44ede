// Fundamental frequency by YIN (de Cheveigné & Kawahara 2002, "YIN, a fundamental frequency
// estimator for speech and music", JASA 111(4), 1917-1930), steps 1 to 5:
//   d(tau)  = sum_{j < W} ( x[j] - x[j + tau] )^2                       difference function (2)
//   d'(tau) = d(tau) tau / sum_{k = 1..tau} d(k),  d'(0) = 1            cumulative mean normalised (8)
// A dip of d' at lag tau is a candidate period, refined by a parabola through d around it; the
// dip's depth is the candidate's aperiodicity (0 for a perfectly periodic signal, about 1 for
// noise). yinPitch() makes YIN's own choice in one frame (the first dip below an absolute
// threshold, else the deepest); yinCandidates() lists the dips for the tracker (pitchTrack.js),
// which chooses across frames and so avoids most octave errors.
//
// d(tau) = e(0) + e(tau) - 2 r(tau), with e(tau) the energy of x[ tau .. tau + W ) (prefix sums)
// and r(tau) = sum_{j < W} x[j] x[j + tau], one cross-correlation done by FFT; so a frame costs
// three FFTs of the frame's size instead of W x maxLag products. One change to the paper's d:
// the lagged segment is taken at the level of the first, d(tau) = (e(0) + e(tau)) (1 - r(tau) /
// sqrt( e(0) e(tau) )), i.e. 1 - the normalised cross-correlation (Talkin 1995, RAPT), scaled.
// With a steady level it is the paper's d; where the voice swells or fades within a frame (the
// start of a vowel) the level change alone no longer makes a periodic stretch look aperiodic.
// On Hillenbrand's 576 vowels this voiced 157 more of the 15,813 hops between the authors' vowel
// starts and ends (among them 2 of the 3 steady states left unvoiced), and moved no steady-state
// F0 by more than 0.5 %; white and low-passed noise stayed as unvoiced as before.
//
// The lags searched are those of the speaker group's pitch range (GROUPS in params.js): the
// range itself is the first guard against octave errors. W, the integration window, is one
// period of the pitch floor, as in the paper.

import { createRealFft, nextPowerOfTwo } from './fft.js';
import { PITCH_CANDIDATES, YIN_THRESHOLD } from './params.js';

/**
 * Scratch and sizes of YIN for a sample rate and a pitch range.
 * @param {{ sampleRate: number, floor: number, ceiling: number, threshold?: number, candidates?: number }}
 *   options: rate and range in Hz; YIN's threshold; how many dips yinCandidates() keeps
 * @returns {object} frameLength: samples a frame reads; the rest is scratch
 */
export function createYin( { sampleRate, floor, ceiling, threshold = YIN_THRESHOLD, candidates = PITCH_CANDIDATES } ) {

	if ( ! ( floor > 0 && ceiling > floor && ceiling < sampleRate / 4 ) ) {

		throw new RangeError( `pitch range ${ floor }-${ ceiling } Hz does not fit a sample rate of ${ sampleRate } Hz` );

	}

	const minLag = Math.max( 2, Math.floor( sampleRate / ceiling ) );
	const maxLag = Math.ceil( sampleRate / floor );
	const lags = maxLag + 1; // one past the range, for the parabola at its end
	const integration = maxLag;
	const frameLength = integration + lags;
	const fft = createRealFft( nextPowerOfTwo( frameLength ) );
	const bins = fft.bins;
	return {
		sampleRate, minLag, maxLag, lags, integration, frameLength, threshold, fft,
		head: new Float64Array( fft.size ), whole: new Float64Array( fft.size ),
		headRe: new Float64Array( bins ), headIm: new Float64Array( bins ),
		wholeRe: new Float64Array( bins ), wholeIm: new Float64Array( bins ),
		correlation: new Float64Array( fft.size ),
		energy: new Float64Array( frameLength + 1 ),
		difference: new Float64Array( lags + 1 ),
		normalised: new Float64Array( lags + 1 ),
		maxCandidates: candidates,
		candidateF0: new Float64Array( candidates ),
		candidateAperiodicity: new Float64Array( candidates ),
		candidateCount: 0,
	};

}

/**
 * Steps 1 to 3 on samples[ start .. start + yin.frameLength ): fills yin.difference (d) and
 * yin.normalised (d') for lags 0 .. yin.lags. Returns false for a silent frame (then d' is not
 * filled). Allocates nothing.
 * @param {object} yin from createYin()
 * @param {Float32Array | Float64Array} samples
 * @param {number} start
 * @returns {boolean}
 */
export function yinDifference( yin, samples, start ) {

	const { fft, head, whole, integration, frameLength, lags, energy, difference, normalised } = yin;
	energy[ 0 ] = 0;
	for ( let j = 0; j < frameLength; j ++ ) {

		const v = samples[ start + j ];
		whole[ j ] = v;
		head[ j ] = j < integration ? v : 0;
		energy[ j + 1 ] = energy[ j ] + v * v;

	}

	if ( energy[ frameLength ] === 0 ) return false;
	whole.fill( 0, frameLength );
	head.fill( 0, frameLength );

	// r(tau) = sum_j head[j] whole[j + tau]: the inverse FFT of conj(HEAD) WHOLE. The FFT is at least
	// frameLength long, so j + tau never wraps round.
	const { headRe, headIm, wholeRe, wholeIm, correlation } = yin;
	fft.forward( head, headRe, headIm );
	fft.forward( whole, wholeRe, wholeIm );
	for ( let k = 0; k < fft.bins; k ++ ) {

		const ar = headRe[ k ], ai = headIm[ k ], br = wholeRe[ k ], bi = wholeIm[ k ];
		wholeRe[ k ] = ar * br + ai * bi;
		wholeIm[ k ] = ar * bi - ai * br;

	}

	fft.inverse( wholeRe, wholeIm, correlation );

	const e0 = energy[ integration ];
	difference[ 0 ] = 0;
	normalised[ 0 ] = 1;
	let running = 0;
	for ( let tau = 1; tau <= lags; tau ++ ) {

		// The two segments' levels equalised (see the head of this file); rounding can take a
		// near-zero difference below zero.
		const et = energy[ tau + integration ] - energy[ tau ];
		const similarity = e0 > 0 && et > 0 ? correlation[ tau ] / Math.sqrt( e0 * et ) : 0;
		const d = Math.max( 0, ( e0 + et ) * ( 1 - similarity ) );
		difference[ tau ] = d;
		running += d;
		normalised[ tau ] = running > 0 ? d * tau / running : 1;

	}

	return true;

}

/** Step 5: the lag of the dip at integer lag `tau`, refined by a parabola through d (unbiased by the normalisation). */
function refinedLag( difference, tau ) {

	const a = difference[ tau - 1 ], b = difference[ tau ], c = difference[ tau + 1 ];
	const curvature = a - 2 * b + c;
	if ( ! ( curvature > 0 ) ) return tau;
	return tau + Math.max( - 1, Math.min( 1, 0.5 * ( a - c ) / curvature ) );

}

/**
 * The bottom of the dip of d' at integer lag `tau`, by the same parabola. At high pitches a period
 * is few samples long and d' at the nearest whole lag is raised by the fractional misalignment
 * (most in vowels with strong high formants, such as /i/), while twice the period can fall
 * nearer a whole lag: without this the undertone would often look more periodic than the tone.
 */
function refinedDepth( normalised, tau ) {

	const a = normalised[ tau - 1 ], b = normalised[ tau ], c = normalised[ tau + 1 ];
	const curvature = a - 2 * b + c;
	if ( ! ( curvature > 0 ) ) return b;
	return Math.max( 0, b - ( a - c ) * ( a - c ) / ( 8 * curvature ) );

}

/**
 * YIN's single-frame estimate on samples[ start .. start + yin.frameLength ): the first dip of d'
 * below the threshold, followed down to its bottom, else the deepest dip in range. Writes
 * result.f0 (Hz; 0 for a silent frame) and result.aperiodicity (d' there; 1 when silent).
 * Allocates nothing.
 * @param {object} yin from createYin()
 * @param {Float32Array | Float64Array} samples
 * @param {number} start
 * @param {{ f0: number, aperiodicity: number }} result
 * @returns {typeof result}
 */
export function yinPitch( yin, samples, start, result ) {

	if ( ! yinDifference( yin, samples, start ) ) {

		result.f0 = 0;
		result.aperiodicity = 1;
		return result;

	}

	const { minLag, maxLag, normalised } = yin;
	let best = - 1;
	for ( let tau = minLag; tau <= maxLag; tau ++ ) {

		if ( normalised[ tau ] < yin.threshold ) {

			while ( tau + 1 <= maxLag && normalised[ tau + 1 ] < normalised[ tau ] ) tau ++;
			best = tau;
			break;

		}

	}

	if ( best < 0 ) {

		best = minLag;
		for ( let tau = minLag + 1; tau <= maxLag; tau ++ ) if ( normalised[ tau ] < normalised[ best ] ) best = tau;

	}

	result.f0 = yin.sampleRate / refinedLag( yin.difference, best );
	result.aperiodicity = normalised[ best ];
	return result;

}

/**
 * Every dip of d' in the pitch range as a candidate for the tracker (pitchTrack.js): the
 * yin.maxCandidates deepest local minima, into yin.candidateF0 (Hz, refined by step 5) and
 * yin.candidateAperiodicity (d'), deepest first. Returns their count (0 for a silent frame).
 * Allocates nothing.
 */
export function yinCandidates( yin, samples, start ) {

	yin.candidateCount = 0;
	return yinDifference( yin, samples, start ) ? collectCandidates( yin ) : 0;

}

/**
 * The candidates (as yinCandidates) from the d and d' already in yin.difference and
 * yin.normalised, however they were computed. Allocates nothing.
 */
export function collectCandidates( yin ) {

	const { minLag, maxLag, normalised, candidateF0, candidateAperiodicity, maxCandidates } = yin;
	let count = 0;
	for ( let tau = minLag; tau <= maxLag; tau ++ ) {

		// A dip: lower than the lag before it and not higher than the one after (edges only when
		// they are the bottom, i.e. the range's end is not cutting a slope).
		if ( ! ( normalised[ tau ] < normalised[ tau - 1 ] && normalised[ tau ] <= normalised[ tau + 1 ] ) ) continue;
		const v = refinedDepth( normalised, tau );
		if ( count === maxCandidates && v >= candidateAperiodicity[ count - 1 ] ) continue;
		let at = count < maxCandidates ? count ++ : count - 1;
		while ( at > 0 && candidateAperiodicity[ at - 1 ] > v ) {

			candidateAperiodicity[ at ] = candidateAperiodicity[ at - 1 ];
			candidateF0[ at ] = candidateF0[ at - 1 ];
			at --;

		}

		candidateAperiodicity[ at ] = v;
		candidateF0[ at ] = yin.sampleRate / refinedLag( yin.difference, tau );

	}

	yin.candidateCount = count;
	return count;

}
