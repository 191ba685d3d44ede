// Spectral moments of a frame: the power spectrum treated as a distribution over frequency
// (Forrest, Weismer, Milenkovic & Dougall 1988, "Statistical analysis of word-initial voiceless
// obstruents", JASA 84(1), 115-123; Jongman, Wayland & Wong 2000, "Acoustic characteristics of
// English fricatives", JASA 108(3), 1252-1263):
//   centroid = sum f P(f) / sum P(f)                         (Hz; /s/ high, /ʃ/ lower)
//   spread   = sqrt( sum (f - centroid)^2 P / sum P )        (Hz, the standard deviation)
//   skew     = sum (f - centroid)^3 P / sum P / spread^3     (no unit; /ʃ/ > /s/)
//   kurtosis = sum (f - centroid)^4 P / sum P / spread^4 - 3 (excess; no unit)
//   peak     = the frequency of the strongest bin (refined by a parabola through its dB)
// over a band (0 to Nyquist by default). The frame's mean is removed and it is Hann-windowed
// (Forrest et al. used a 20 ms Hamming window) and zero-padded to a power of two.

import { createRealFft, nextPowerOfTwo } from './fft.js';
import { hannWindow } from './frames.js';

/** Slots of a moments result (Float64Array( MOMENT_SLOTS )). */
export const MOMENT_CENTROID = 0;
export const MOMENT_SPREAD = 1;
export const MOMENT_SKEW = 2;
export const MOMENT_KURTOSIS = 3;
export const MOMENT_PEAK = 4;
/** Total power in the band (sum of |X|^2 over its bins); 0 means no moments. */
export const MOMENT_POWER = 5;
export const MOMENT_SLOTS = 6;

/**
 * Moments of the power spectrum power[ lo .. hi ] (bins of `binHz` Hz) into target (the
 * MOMENT_* slots). With no power in the band every slot is NaN but MOMENT_POWER (0). Allocates
 * nothing.
 * @param {Float64Array} power
 * @param {number} binHz
 * @param {number} lo first bin
 * @param {number} hi last bin (included)
 * @param {Float64Array} target
 * @returns {Float64Array} target
 */
export function spectralMoments( power, binHz, lo, hi, target ) {

	let total = 0, first = 0, strongest = lo;
	for ( let k = lo; k <= hi; k ++ ) {

		const p = power[ k ];
		total += p;
		first += p * k;
		if ( p > power[ strongest ] ) strongest = k;

	}

	target[ MOMENT_POWER ] = total;
	if ( ! ( total > 0 ) ) {

		target.fill( NaN, 0, MOMENT_POWER );
		return target;

	}

	const centre = first / total; // in bins
	let second = 0, third = 0, fourth = 0;
	for ( let k = lo; k <= hi; k ++ ) {

		const d = k - centre, p = power[ k ];
		const d2 = d * d;
		second += d2 * p;
		third += d2 * d * p;
		fourth += d2 * d2 * p;

	}

	const variance = second / total;
	const sd = Math.sqrt( variance );
	target[ MOMENT_CENTROID ] = centre * binHz;
	target[ MOMENT_SPREAD ] = sd * binHz;
	target[ MOMENT_SKEW ] = sd > 0 ? third / total / ( variance * sd ) : 0;
	target[ MOMENT_KURTOSIS ] = sd > 0 ? fourth / total / ( variance * variance ) - 3 : 0;
	// The peak between bins: a parabola through the dB of the strongest bin and its neighbours.
	let shift = 0;
	if ( strongest > lo && strongest < hi && power[ strongest - 1 ] > 0 && power[ strongest + 1 ] > 0 ) {

		const a = Math.log( power[ strongest - 1 ] ), b = Math.log( power[ strongest ] ), c = Math.log( power[ strongest + 1 ] );
		const curvature = a - 2 * b + c;
		if ( curvature < 0 ) shift = Math.max( - 0.5, Math.min( 0.5, 0.5 * ( a - c ) / curvature ) );

	}

	target[ MOMENT_PEAK ] = ( strongest + shift ) * binHz;
	return target;

}

/**
 * Window, FFT and scratch for the moments of frames of `windowS` at `sampleRate`.
 * @param {{ sampleRate: number, windowS: number, band?: [ number, number ] }} options band in Hz
 *   (defaults to 0 .. Nyquist)
 * @returns {object} frameLength: samples a frame reads
 */
export function createMomentsAnalysis( { sampleRate, windowS, band = [ 0, sampleRate / 2 ] } ) {

	const frameLength = Math.max( 4, Math.round( windowS * sampleRate ) );
	const fft = createRealFft( nextPowerOfTwo( frameLength ) );
	const binHz = sampleRate / fft.size;
	const [ low, high ] = band;
	if ( ! ( low >= 0 && high > low && high <= sampleRate / 2 ) ) {

		throw new RangeError( `moments band ${ low }-${ high } Hz must lie within 0-${ sampleRate / 2 } Hz` );

	}

	return {
		sampleRate, frameLength, fft, binHz,
		lo: Math.ceil( low / binHz ), hi: Math.min( fft.bins - 1, Math.floor( high / binHz ) ),
		window: hannWindow( frameLength ),
		frame: new Float64Array( fft.size ),
		re: new Float64Array( fft.bins ), im: new Float64Array( fft.bins ),
		power: new Float64Array( fft.bins ),
		result: new Float64Array( MOMENT_SLOTS ),
	};

}

/**
 * Moments of samples[ start .. start + frameLength ) into analysis.result (MOMENT_* slots), which
 * is returned. Allocates nothing.
 */
export function analyseMoments( analysis, samples, start ) {

	const { frameLength, window, frame, fft, re, im, power } = analysis;
	let mean = 0;
	for ( let i = 0; i < frameLength; i ++ ) mean += samples[ start + i ];
	mean /= frameLength;
	for ( let i = 0; i < frameLength; i ++ ) frame[ i ] = ( samples[ start + i ] - mean ) * window[ i ];
	frame.fill( 0, frameLength );
	fft.forward( frame, re, im );
	for ( let k = 0; k < fft.bins; k ++ ) power[ k ] = re[ k ] * re[ k ] + im[ k ] * im[ k ];
	return spectralMoments( power, analysis.binHz, analysis.lo, analysis.hi, analysis.result );

}
