// The spectrogram of a stretch of samples, as a grid for drawing: `columns` analysis frames
// evenly spread over the samples, each a Hann-windowed FFT of about 10 ms (a wide-band
// spectrogram, which shows formants as dark bands and each glottal pulse as a stripe), its power
// in dB from 0 Hz to `maxHz` in `rows` rows. Pure: the listening page draws it (AttemptPanel.js).

import { createRealFft, nextPowerOfTwo } from '../../core/listen/fft.js';
import { hannWindow } from '../../core/listen/frames.js';

/** The analysis window, s: wide band, so formants show as bands, not harmonics. */
export const SPECTROGRAM_WINDOW_S = 0.008;

/**
 * { db: Float32Array (columns * rows, column-major, row 0 at 0 Hz), top } of `samples` at
 * `sampleRate`; `top` is the largest dB, for scaling. Empty input gives a grid of -Infinity.
 */
export function spectrogram( samples, sampleRate, { columns = 400, rows = 128, maxHz = 8000 } = {} ) {

	const length = Math.round( SPECTROGRAM_WINDOW_S * sampleRate );
	const size = nextPowerOfTwo( Math.max( 4, length ) );
	const fft = createRealFft( size );
	const window = hannWindow( length );
	const frame = new Float64Array( size );
	const re = new Float64Array( fft.bins );
	const im = new Float64Array( fft.bins );
	const db = new Float32Array( columns * rows ).fill( - Infinity );
	const hzPerBin = sampleRate / size;
	const top = Math.min( maxHz, sampleRate / 2 );
	let loudest = - Infinity;
	if ( samples.length < length ) return { db, top: loudest };
	for ( let c = 0; c < columns; c ++ ) {

		const start = Math.round( ( c / Math.max( 1, columns - 1 ) ) * ( samples.length - length ) );
		frame.fill( 0 );
		for ( let i = 0; i < length; i ++ ) frame[ i ] = samples[ start + i ] * window[ i ];
		fft.forward( frame, re, im );
		for ( let r = 0; r < rows; r ++ ) {

			const bin = Math.min( fft.bins - 1, Math.round( ( ( r + 0.5 ) / rows ) * top / hzPerBin ) );
			const power = re[ bin ] * re[ bin ] + im[ bin ] * im[ bin ];
			const value = 10 * Math.log10( power + 1e-20 );
			db[ c * rows + r ] = value;
			if ( value > loudest ) loudest = value;

		}

	}

	return { db, top: loudest };

}
