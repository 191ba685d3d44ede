// Test signals for the listening kernels, made from first principles so that their pitch and
// formants are known: sines, seeded noise, filtered noise and vowels synthesised as a glottal
// pulse train through formant resonators; and WAV files written byte by byte.

import { random } from '../../../bench/support/stats.mjs';

export { random };

/** Gaussian noise of standard deviation `sd` (Box-Muller on a seeded generator). */
export function noise( length, seed, sd = 0.1 ) {

	const next = random( seed );
	const out = new Float32Array( length );
	for ( let i = 0; i < length; i ++ ) out[ i ] = sd * Math.sqrt( - 2 * Math.log( 1 - next() ) ) * Math.cos( 2 * Math.PI * next() );
	return out;

}

/** A sine of `hz` and `amplitude`. */
export function sine( length, sampleRate, hz, amplitude = 0.5 ) {

	const out = new Float32Array( length );
	for ( let i = 0; i < length; i ++ ) out[ i ] = amplitude * Math.sin( 2 * Math.PI * hz * i / sampleRate );
	return out;

}

/**
 * Klatt's digital resonator (Klatt 1980, "Software for a cascade/parallel formant synthesizer",
 * JASA 67(3), eq. 1): y[n] = A x[n] + B y[n-1] + C y[n-2], unit gain at DC. In place.
 */
export function resonate( signal, sampleRate, hz, bandwidth ) {

	const t = 1 / sampleRate;
	const c = - Math.exp( - 2 * Math.PI * bandwidth * t );
	const b = 2 * Math.exp( - Math.PI * bandwidth * t ) * Math.cos( 2 * Math.PI * hz * t );
	const a = 1 - b - c;
	let y1 = 0, y2 = 0;
	for ( let i = 0; i < signal.length; i ++ ) {

		const y = a * signal[ i ] + b * y1 + c * y2;
		y2 = y1;
		y1 = y;
		signal[ i ] = y;

	}

	return signal;

}

/**
 * A vowel: Rosenberg glottal pulses (Rosenberg 1971, shape B: opening 40 %, closing 16 % of the
 * period) at f0, through resonators in cascade, then lip radiation (a first difference), scaled
 * to a peak of `peak`.
 * @param {{ sampleRate: number, seconds: number, f0: number, formants: number[], bandwidths: number[], peak?: number }} options
 * @returns {Float32Array}
 */
export function vowel( { sampleRate, seconds, f0, formants, bandwidths, peak = 0.5 } ) {

	const length = Math.round( seconds * sampleRate );
	const signal = new Float64Array( length );
	const period = sampleRate / f0;
	for ( let i = 0; i < length; i ++ ) {

		const phase = ( i % period ) / period;
		signal[ i ] = phase < 0.4 ? 0.5 * ( 1 - Math.cos( Math.PI * phase / 0.4 ) )
			: phase < 0.56 ? Math.cos( Math.PI * ( phase - 0.4 ) / ( 2 * 0.16 ) ) : 0;

	}

	formants.forEach( ( hz, k ) => resonate( signal, sampleRate, hz, bandwidths[ k ] ) );
	for ( let i = length - 1; i > 0; i -- ) signal[ i ] -= signal[ i - 1 ];
	signal[ 0 ] = 0;
	let max = 0;
	for ( const v of signal ) max = Math.max( max, Math.abs( v ) );
	return Float32Array.from( signal, ( v ) => v * peak / max );

}

/** A one-pole low-pass (coefficient from its -3 dB frequency) or, with `high`, its complement. */
export function onePole( signal, sampleRate, hz, high = false ) {

	const a = Math.exp( - 2 * Math.PI * hz / sampleRate );
	const out = new Float32Array( signal.length );
	let y = 0;
	for ( let i = 0; i < signal.length; i ++ ) {

		y = ( 1 - a ) * signal[ i ] + a * y;
		out[ i ] = high ? signal[ i ] - y : y;

	}

	return out;

}

/**
 * The bytes of a WAV file.
 * @param {{ sampleRate: number, channels: number, bits: number, float?: boolean, extensible?: boolean,
 *   frames: number[][] }} options frames[ i ][ c ]: sample of channel c at frame i, in [-1, 1)
 * @returns {Uint8Array}
 */
export function writeWav( { sampleRate, channels, bits, float = false, extensible = false, frames } ) {

	const bytes = bits / 8;
	const blockAlign = channels * bytes;
	const dataBytes = frames.length * blockAlign;
	const fmtBytes = extensible ? 40 : 16;
	const total = 12 + 8 + fmtBytes + 8 + dataBytes + ( dataBytes & 1 );
	const view = new DataView( new ArrayBuffer( total ) );
	const text = ( at, s ) => [ ...s ].forEach( ( ch, k ) => view.setUint8( at + k, ch.charCodeAt( 0 ) ) );
	text( 0, 'RIFF' );
	view.setUint32( 4, total - 8, true );
	text( 8, 'WAVE' );
	text( 12, 'fmt ' );
	view.setUint32( 16, fmtBytes, true );
	const code = float ? 3 : 1;
	view.setUint16( 20, extensible ? 0xFFFE : code, true );
	view.setUint16( 22, channels, true );
	view.setUint32( 24, sampleRate, true );
	view.setUint32( 28, sampleRate * blockAlign, true );
	view.setUint16( 32, blockAlign, true );
	view.setUint16( 34, bits, true );
	if ( extensible ) {

		view.setUint16( 36, 22, true ); // cbSize
		view.setUint16( 38, bits, true ); // valid bits
		view.setUint32( 40, channels === 1 ? 4 : 3, true ); // channel mask
		view.setUint16( 44, code, true ); // the sub-format GUID's first two bytes
		[ 0x00, 0x00, 0x00, 0x00, 0x10, 0x00, 0x80, 0x00, 0x00, 0xAA, 0x00, 0x38, 0x9B, 0x71 ].forEach( ( b, k ) => view.setUint8( 46 + k, b ) );

	}

	const data = 12 + 8 + fmtBytes;
	text( data, 'data' );
	view.setUint32( data + 4, dataBytes, true );
	let at = data + 8;
	for ( const frame of frames ) for ( let c = 0; c < channels; c ++ ) {

		const v = frame[ c ];
		// Integers: rounded and held to the format's range (full scale is 2^(bits - 1)).
		const full = 2 ** ( bits - 1 );
		const n = Math.max( - full, Math.min( full - 1, Math.round( v * full ) ) );
		if ( float && bits === 32 ) view.setFloat32( at, v, true );
		else if ( float ) view.setFloat64( at, v, true );
		else if ( bits === 8 ) view.setUint8( at, n + 128 );
		else if ( bits === 16 ) view.setInt16( at, n, true );
		else if ( bits === 24 ) {

			view.setUint8( at, n & 0xFF );
			view.setUint8( at + 1, ( n >> 8 ) & 0xFF );
			view.setUint8( at + 2, ( n >> 16 ) & 0xFF );

		} else view.setInt32( at, n, true );
		at += bytes;

	}

	return new Uint8Array( view.buffer );

}
