// Streaming sample-rate conversion by a polyphase windowed-sinc filter, for the formant analysis
// (which, as Praat's, runs at twice the formant ceiling).
//
// For rates in the ratio L / M (integers, reduced), output sample m sits at input position
// m M / L = n0 + p / L, and is sum_j x[ n0 + j ] h( j - p / L ) over the 2 H input samples around
// it, h a Kaiser-windowed sinc cut off just below the lower Nyquist frequency (Smith, "Digital
// audio resampling home page", bandlimited interpolation; Crochiere & Rabiner 1983, ch. 4). The L
// phases of h are tabled once, each normalised to a gain of exactly 1 at DC. Each output sample
// is computed from input values alone, so chunking the input never changes the output.

import { besselI0, SampleStream } from './frames.js';

/**
 * Zero crossings of the sinc on each side: the filter's length (140 taps per output sample from
 * 16 to 11 kHz, 462 from 48 to 10 kHz), hence its transition width (about 500 Hz, centred on the
 * new Nyquist frequency). 48 matched Praat's formants on Hillenbrand's vowels as well as 64 did,
 * at 3/4 of the cost; 32 moved a few more.
 */
const ZERO_CROSSINGS = 48;
/**
 * The cut-off as a fraction of the lower Nyquist frequency. 1, because Praat cuts off there with
 * a brick wall (Sound_resample), and an LPC of order 10 is sensitive to the top of its band: a
 * cut-off of 0.96 left a dip there that moved a weak pole, against Praat's formants, in one frame
 * in six of Hillenbrand's vowels, where 1 moves one in fifty.
 */
const ROLLOFF = 1;
/** Kaiser shape: about 70 dB of stop-band attenuation. */
const KAISER_BETA = 7;
/** More phases than this are quantised to this many (rates whose reduced ratio is unusual). */
const MAX_PHASES = 4096;

function gcd( a, b ) {

	while ( b ) [ a, b ] = [ b, a % b ];
	return a;

}

/**
 * A resampler from `fromRate` to `toRate` (integer rates, Hz).
 * @returns {{ fromRate: number, toRate: number, halfTaps: number, up: number, down: number,
 *   phases: number, taps: Float64Array, next: number }} `next` is the next output sample to make
 */
export function createResampler( fromRate, toRate, { zeroCrossings = ZERO_CROSSINGS, rolloff = ROLLOFF, beta = KAISER_BETA } = {} ) {

	if ( ! Number.isInteger( fromRate ) || ! Number.isInteger( toRate ) || fromRate <= 0 || toRate <= 0 ) {

		throw new RangeError( `resampling needs positive integer rates, got ${ fromRate } and ${ toRate } Hz` );

	}

	const g = gcd( fromRate, toRate );
	const up = toRate / g, down = fromRate / g;
	const phases = Math.min( up, MAX_PHASES );
	// Cut-off in cycles per input sample.
	const cutoff = 0.5 * Math.min( 1, up / down ) * rolloff;
	const halfTaps = Math.ceil( zeroCrossings / ( 2 * cutoff ) );
	const width = 2 * halfTaps;
	const taps = new Float64Array( phases * width );
	for ( let p = 0; p < phases; p ++ ) {

		const frac = p / phases;
		let sum = 0;
		for ( let j = - halfTaps + 1; j <= halfTaps; j ++ ) {

			const t = j - frac;
			const u = t / halfTaps;
			const arg = 2 * cutoff * t;
			const sinc = arg === 0 ? 1 : Math.sin( Math.PI * arg ) / ( Math.PI * arg );
			const w = Math.abs( u ) >= 1 ? 0 : besselI0( beta * Math.sqrt( 1 - u * u ) ) / besselI0( beta );
			const h = 2 * cutoff * sinc * w;
			taps[ p * width + j + halfTaps - 1 ] = h;
			sum += h;

		}

		for ( let j = 0; j < width; j ++ ) taps[ p * width + j ] /= sum;

	}

	return { fromRate, toRate, halfTaps, up, down, phases, taps, next: 0 };

}

/** The last input sample (absolute index) that output sample `m` reads. */
export function lastInputFor( resampler, m ) {

	return Math.floor( m * resampler.down / resampler.up ) + resampler.halfTaps;

}

/** The first input sample (absolute index) that output sample `m` reads. */
export function firstInputFor( resampler, m ) {

	return Math.floor( m * resampler.down / resampler.up ) - resampler.halfTaps + 1;

}

/**
 * Make every output sample whose input is held in `input` (a SampleStream with at least
 * halfTaps zeros of lead), appending them to `output` (a SampleStream). Allocates nothing
 * unless `output` must grow. Returns how many were made.
 */
export function resampleStream( resampler, input, output ) {

	const { up, down, phases, taps, halfTaps } = resampler;
	const width = 2 * halfTaps;
	let made = 0;
	while ( lastInputFor( resampler, resampler.next ) < input.end ) {

		const m = resampler.next;
		const position = m * down;
		const n0 = Math.floor( position / up );
		const p = phases === up ? position - n0 * up : Math.floor( ( position - n0 * up ) * phases / up );
		const first = input.offset( n0 - halfTaps + 1 );
		const row = p * width;
		const x = input.data;
		// Four running sums: independent additions pipeline (the width is even, not always a multiple of 4).
		let s0 = 0, s1 = 0, s2 = 0, s3 = 0, j = 0;
		for ( ; j + 3 < width; j += 4 ) {

			s0 += x[ first + j ] * taps[ row + j ];
			s1 += x[ first + j + 1 ] * taps[ row + j + 1 ];
			s2 += x[ first + j + 2 ] * taps[ row + j + 2 ];
			s3 += x[ first + j + 3 ] * taps[ row + j + 3 ];

		}

		for ( ; j < width; j ++ ) s0 += x[ first + j ] * taps[ row + j ];
		const sum = ( s0 + s1 ) + ( s2 + s3 );
		const at = output.reserve( 1 );
		output.data[ at ] = sum;
		output.end ++;
		resampler.next ++;
		made ++;

	}

	return made;

}

/**
 * A whole recording at another rate, through the same filter as the stream: the samples
 * before the first and after the last are taken as silence, and the output holds every sample
 * that falls within the input, ceil( n toRate / fromRate ) of them. `options` as createResampler's
 * (a `rolloff` under 1 keeps what lies just below the new Nyquist frequency from folding back).
 * @param {Float32Array} samples
 * @returns {Float32Array} a new array (a copy when the rates are equal)
 */
export function resampleSamples( samples, fromRate, toRate, options = {} ) {

	if ( fromRate === toRate ) return Float32Array.from( samples );
	const resampler = createResampler( fromRate, toRate, options );
	const count = Math.ceil( samples.length * resampler.up / resampler.down );
	const input = new SampleStream( resampler.halfTaps, samples.length + 2 * resampler.halfTaps + 16 );
	input.append( samples );
	input.appendZeros( resampler.halfTaps + 1 );
	const output = new SampleStream( 0, count + 16 );
	resampleStream( resampler, input, output );
	return output.data.slice( output.offset( 0 ), output.offset( 0 ) + count );

}
