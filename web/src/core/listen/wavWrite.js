// Writing a RIFF WAVE file: 16-bit integer PCM, mono, the plain 16-byte format chunk, the
// simplest file every reader takes (wav.js's layout references; the server accepts just this).
// And the recording of a practice attempt as it is kept: resampled to RECORDING_RATE, then
// written so.

import { resampleSamples } from './resample.js';

/** Bytes before the samples: RIFF header (12), `fmt ` chunk (8 + 16), `data` chunk header (8). */
export const WAV_HEADER_BYTES = 12 + ( 8 + 16 ) + 8;
/** Bytes per sample of 16-bit mono PCM (the block align). */
const BYTES_PER_SAMPLE = 2;

/** The rate recordings are kept at, Hz: speech up to 8 kHz, a third of 48 kHz's bytes. */
export const RECORDING_RATE = 16000;
/**
 * The resampling filter's cut-off for recordings, as a fraction of the new Nyquist frequency.
 * At 0.94 (7.52 kHz), from 44.1 or 48 kHz, the response is flat (0.01 dB) to 7 kHz, -5 dB at
 * 7.5 kHz, and 70 dB down and more from 7.9 kHz: what lies above 8 kHz is stopped before it could
 * fold back below it. (The formant analysis cuts off at 1 instead, as Praat does, and lets a
 * little fold back just under its Nyquist frequency.)
 */
export const RECORDING_ROLLOFF = 0.94;

/**
 * A sample in [-1, 1] as a 16-bit integer: scaled by 32768, as wav.js reads it back, so that a
 * value on the 16-bit grid comes back exactly; beyond the range clipped to -32768 and 32767
 * (never wrapped round, which would turn a loud peak into a click), NaN as 0.
 */
export function pcm16( value ) {

	if ( ! ( value === value ) ) return 0; // NaN
	return Math.max( - 32768, Math.min( 32767, Math.round( value * 32768 ) ) );

}

/**
 * The bytes of a 16-bit PCM mono WAV file of `samples` at `sampleRate`.
 * @param {Float32Array | number[]} samples in [-1, 1]; beyond it clipped
 * @param {number} sampleRate Hz, a positive integer
 * @returns {Uint8Array} WAV_HEADER_BYTES + 2 per sample (a pad byte is never needed: the data is even)
 */
export function encodeWav16( samples, sampleRate ) {

	if ( ! Number.isInteger( sampleRate ) || sampleRate <= 0 ) throw new RangeError( `a WAV file needs a positive integer sample rate, got ${ sampleRate }` );
	const dataBytes = samples.length * BYTES_PER_SAMPLE;
	const bytes = new Uint8Array( WAV_HEADER_BYTES + dataBytes );
	const view = new DataView( bytes.buffer );
	const text = ( at, s ) => {

		for ( let k = 0; k < 4; k ++ ) view.setUint8( at + k, s.charCodeAt( k ) );

	};
	text( 0, 'RIFF' );
	view.setUint32( 4, bytes.length - 8, true );
	text( 8, 'WAVE' );
	text( 12, 'fmt ' );
	view.setUint32( 16, 16, true );
	view.setUint16( 20, 1, true ); // WAVE_FORMAT_PCM
	view.setUint16( 22, 1, true ); // channels
	view.setUint32( 24, sampleRate, true );
	view.setUint32( 28, sampleRate * BYTES_PER_SAMPLE, true ); // bytes per second
	view.setUint16( 32, BYTES_PER_SAMPLE, true ); // block align
	view.setUint16( 34, 16, true ); // bits per sample
	text( 36, 'data' );
	view.setUint32( 40, dataBytes, true );
	for ( let i = 0; i < samples.length; i ++ ) view.setInt16( WAV_HEADER_BYTES + i * BYTES_PER_SAMPLE, pcm16( samples[ i ] ), true );
	return bytes;

}

/**
 * The WAV file an attempt is kept as: `samples` (at `sampleRate`, the microphone's) resampled to
 * RECORDING_RATE and written as 16-bit PCM. At most `maxSeconds` are kept, the first ones.
 * @returns {Uint8Array}
 */
export function recordingWav( samples, sampleRate, { maxSeconds = Infinity } = {} ) {

	const kept = samples.length > maxSeconds * sampleRate ? samples.subarray( 0, Math.floor( maxSeconds * sampleRate ) ) : samples;
	return encodeWav16( resampleSamples( kept, sampleRate, RECORDING_RATE, { rolloff: RECORDING_ROLLOFF } ), RECORDING_RATE );

}
