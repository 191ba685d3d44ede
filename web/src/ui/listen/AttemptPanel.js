// The last attempt for a clinician: its waveform (scaled to its loudest) over its wide-band
// spectrogram (0 to 8 kHz, darker is louder, over the 60 dB below its loudest), with its
// measures written under them.
// The samples stay in the page: nothing is sent.

import { HiDpiCanvas } from '../shared/hidpiCanvas.js';
import { spectrogram } from './spectrogram.js';

/** dB below the loudest cell that is drawn white. */
const RANGE_DB = 60;

export class AttemptPanel {

	constructor( { width = 420, height = 220, document: doc = globalThis.document } = {} ) {

		this.canvas = new HiDpiCanvas( { width, height, ariaLabel: 'The last attempt: waveform and spectrogram', className: 'ls-canvas' } );
		this.caption = doc.createElement( 'p' );
		this.caption.className = 'ls-attempt-measures';
		this.element = doc.createElement( 'div' );
		this.element.append( this.canvas.element, this.caption );

	}

	resize( width ) {

		this.canvas.resize( width );

	}

	/** Draw `samples` at `sampleRate` and write `words` (the measures) under them. */
	draw( samples, sampleRate, words ) {

		this.caption.textContent = words;
		const ctx = this.canvas.clear();
		if ( ! ctx || ! samples?.length ) return;
		const { width, height } = this.canvas;
		const waveHeight = Math.round( height * 0.3 );
		// The waveform: the extremes of the samples under each column, scaled to the loudest.
		let peak = 1e-6;
		for ( let i = 0; i < samples.length; i ++ ) peak = Math.max( peak, Math.abs( samples[ i ] ) );
		const half = waveHeight / 2 / peak;
		ctx.strokeStyle = '#1f2328';
		ctx.beginPath();
		for ( let x = 0; x < width; x ++ ) {

			const from = Math.floor( ( x / width ) * samples.length );
			const to = Math.max( from + 1, Math.floor( ( ( x + 1 ) / width ) * samples.length ) );
			let low = 0;
			let high = 0;
			for ( let i = from; i < to; i ++ ) {

				low = Math.min( low, samples[ i ] );
				high = Math.max( high, samples[ i ] );

			}

			ctx.moveTo( x + 0.5, waveHeight / 2 - high * half );
			ctx.lineTo( x + 0.5, waveHeight / 2 - low * half + 1 );

		}

		ctx.stroke();
		// The spectrogram, as an image of one cell per column and row.
		const columns = Math.min( 600, Math.round( width ) );
		const rows = 96;
		const { db, top } = spectrogram( samples, sampleRate, { columns, rows } );
		const image = ctx.createImageData( columns, rows );
		for ( let c = 0; c < columns; c ++ ) {

			for ( let r = 0; r < rows; r ++ ) {

				const level = Math.max( 0, Math.min( 1, ( db[ c * rows + r ] - top + RANGE_DB ) / RANGE_DB ) );
				const grey = Math.round( 255 * ( 1 - level ) );
				const at = ( ( rows - 1 - r ) * columns + c ) * 4;
				image.data.set( [ grey, grey, grey, 255 ], at );

			}

		}

		const staging = new OffscreenCanvas( columns, rows );
		staging.getContext( '2d' ).putImageData( image, 0, 0 );
		ctx.drawImage( staging, 0, waveHeight, width, height - waveHeight );

	}

}
