// A strip of palatograms over time: the frames of an utterance or a recording side by side, the
// current one framed, each labelled with its time. A long recording shows the window of frames
// around the current one that fits the width.
//
// Drawing goes through an injected 2D context (drawPalatogramStrip); stripWindow and frameAtX are
// the pure geometry the canvas's clicks use.

import { drawPalatogram, PALATOGRAM_COLORS, READING_GRID } from '../shared/Palatogram.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';

/** Width of one palatogram of the strip against its height. */
const ASPECT = 0.85;

/**
 * Which frames fit: { first, count, size } for `total` frames in a strip `width` x `height`,
 * centred on `current` where it can be.
 */
export function stripWindow( total, current, width, height ) {

	const size = Math.max( 1, height * ASPECT );
	const fit = Math.max( 1, Math.floor( width / size ) );
	const count = Math.min( total, fit );
	let first = Math.max( 0, Math.min( total - count, current - Math.floor( count / 2 ) ) );
	if ( ! Number.isFinite( first ) ) first = 0;
	return { first, count, size };

}

/** The frame under x (strip coordinates), or -1 outside the drawn frames. */
export function frameAtX( x, total, current, width, height ) {

	const { first, count, size } = stripWindow( total, current, width, height );
	const k = Math.floor( x / size );
	return k >= 0 && k < count ? first + k : - 1;

}

/**
 * @param {CanvasRenderingContext2D} ctx
 * @param {Uint8Array} frames cells per frame, frame after frame (64 each for the Reading palate)
 * @param {number} total how many frames
 * @param {{width: number, height: number, current?: number, t_s?: ArrayLike<number>|null,
 *   codes?: Uint8Array|null, grid?: object, colors?: object}} options
 * @returns {{first: number, count: number, size: number}} the frames drawn
 */
export function drawPalatogramStrip( ctx, frames, total, { width, height, current = 0, t_s = null, codes = null, grid = READING_GRID, colors = PALATOGRAM_COLORS } = {} ) {

	const cells = grid.rows * grid.columns;
	const window = stripWindow( total, current, width, height );
	const { first, count, size } = window;
	const t0 = t_s && t_s.length ? t_s[ 0 ] : 0;
	for ( let k = 0; k < count; k ++ ) {

		const frame = first + k;
		const label = t_s ? `${ Math.round( ( t_s[ frame ] - t0 ) * 1000 ) } ms` : `${ frame + 1 }`;
		drawPalatogram( ctx, codes ? null : frames, {
			x: k * size, y: 0, width: size, height, grid, label, colors,
			codes, offset: frame * cells,
		} );
		if ( frame === current ) {

			ctx.strokeStyle = colors.onlyRecording;
			ctx.lineWidth = 2;
			ctx.strokeRect( k * size + 1, 1, size - 2, height - 2 );

		}

	}

	return window;

}

/**
 * A strip on its own <canvas>; `set( frames, total, current, t_s )` redraws it and `onSelect( i )`
 * is called with the frame a click lands on.
 */
export class PalatogramStrip extends HiDpiCanvas {

	constructor( { width = 640, height = 96, document = globalThis.document, onSelect = () => {} } = {} ) {

		super( { width, height, document, className: 'palatogram-strip', ariaLabel: 'Palatograms over time (click a frame, or focus and step with the arrow keys)' } );
		// Reachable with Tab: the view's keys step the frames while the strip has the focus.
		this.element.tabIndex = 0;
		this.state = { frames: null, total: 0, current: 0, t_s: null, codes: null };
		this.element.addEventListener( 'click', ( event ) => {

			const rect = this.element.getBoundingClientRect();
			const frame = frameAtX( event.clientX - rect.left, this.state.total, this.state.current, this.width, this.height );
			if ( frame >= 0 ) onSelect( frame );

		} );

	}

	set( frames, total, current, t_s = null, codes = null ) {

		this.state = { frames, total, current, t_s, codes };
		const ctx = this.clear();
		if ( ! ctx ) return null;
		return drawPalatogramStrip( ctx, frames, total, { width: this.width, height: this.height, current, t_s, codes } );

	}

}
