// The flat palatogram: the Reading layout drawn as EPG is printed, front (R1) at the top, column 1
// on the left (the palate seen from below, from the tongue); a contacted electrode is a filled
// square, an uncontacted one a dot (Cohen, Beskow and Massaro 1998, Figures 7 and 8).
//
// Drawing goes through an injected 2D context (drawPalatogram), so it can be tested without a
// browser; the Palatogram class owns a <canvas> and redraws it when given a new frame.

import {
	EPG_COLUMNS, EPG_COMPARE_BOTH_OFF, EPG_COMPARE_BOTH_ON, EPG_COMPARE_NO_ELECTRODE, EPG_COMPARE_ONLY_RECORDING,
	EPG_COMPARE_ONLY_REFERENCE, EPG_MISSING_CELLS, EPG_ROWS,
} from '../../core/constants.js';
import { HiDpiCanvas } from './hidpiCanvas.js';

/** Colours of the drawing (the app's ink and accent). */
export const PALATOGRAM_COLORS = Object.freeze( {
	outline: '#8c959f',
	palate: '#fbeff1',
	dot: '#8c959f',
	contact: '#1f2328',
	onlyRecording: '#b4384a',
	onlyReference: '#1f6feb',
	label: '#57606a',
} );

/** Comparison codes (as POST /epg/recordings/{id}/compare): both off, both on, one side only. */
export const CODE_BOTH_OFF = EPG_COMPARE_BOTH_OFF;
export const CODE_BOTH_ON = EPG_COMPARE_BOTH_ON;
export const CODE_ONLY_RECORDING = EPG_COMPARE_ONLY_RECORDING;
export const CODE_ONLY_REFERENCE = EPG_COMPARE_ONLY_REFERENCE;
export const CODE_NO_ELECTRODE = EPG_COMPARE_NO_ELECTRODE;

/** Reading layout: 8 x 8, R1 without columns 1 and 8. */
export const READING_GRID = Object.freeze( { rows: EPG_ROWS, columns: EPG_COLUMNS, missing: EPG_MISSING_CELLS } );

/**
 * Where the cells of a palatogram fall inside the box { x, y, width, height }: the cell pitch,
 * the top-left of the grid and the centre of any cell. Cells are square; the grid is centred.
 */
export function palatogramLayout( box, grid = READING_GRID ) {

	// Room around the grid for the outline of the palate (a quarter of a cell) and a margin.
	const pad = Math.min( box.width, box.height ) * 0.04;
	const pitch = Math.min( ( box.width - 2 * pad ) / ( grid.columns + 0.6 ), ( box.height - 2 * pad ) / ( grid.rows + 0.6 ) );
	const x0 = box.x + ( box.width - pitch * grid.columns ) / 2;
	const y0 = box.y + ( box.height - pitch * grid.rows ) / 2;
	return {
		pitch, x0, y0,
		centre: ( row, column ) => [ x0 + ( column + 0.5 ) * pitch, y0 + ( row + 0.5 ) * pitch ],
	};

}

/** The outline of the palate around the grid: narrow at the front, open at the back. */
function tracePalate( ctx, layout, grid ) {

	const { x0, y0, pitch } = layout;
	const x1 = x0 + grid.columns * pitch, y1 = y0 + grid.rows * pitch;
	const m = pitch * 0.25;
	ctx.beginPath();
	ctx.moveTo( x0 - m, y1 + m );
	ctx.lineTo( x0 - m, y0 + 1.5 * pitch );
	ctx.quadraticCurveTo( x0 - m, y0 - m, x0 + 1.5 * pitch, y0 - m );
	ctx.lineTo( x1 - 1.5 * pitch, y0 - m );
	ctx.quadraticCurveTo( x1 + m, y0 - m, x1 + m, y0 + 1.5 * pitch );
	ctx.lineTo( x1 + m, y1 + m );

}

/**
 * Draw one palatogram.
 * @param {CanvasRenderingContext2D} ctx any object with the 2D context's methods
 * @param {Uint8Array|number[]|null} frame rows * columns contacts (0/1), row-major, R1 first;
 *   null draws the empty palate
 * @param {{x?: number, y?: number, width: number, height: number, grid?: object,
 *   codes?: ArrayLike<number>, label?: string, colors?: object, offset?: number}} options
 *   `codes` (comparison codes per cell) replaces `frame`; `offset` is where the frame starts in
 *   `frame` (a frame of a longer Uint8Array)
 * @returns the layout used (palatogramLayout)
 */
export function drawPalatogram( ctx, frame, { x = 0, y = 0, width, height, grid = READING_GRID, codes = null, label = null, colors = PALATOGRAM_COLORS, offset = 0 } = {} ) {

	const labelHeight = label ? Math.max( 10, Math.min( 18, height * 0.09 ) ) : 0;
	const layout = palatogramLayout( { x, y: y + labelHeight, width, height: height - labelHeight }, grid );
	const { pitch } = layout;
	const missing = new Set( grid.missing );

	tracePalate( ctx, layout, grid );
	ctx.fillStyle = colors.palate;
	ctx.fill();
	ctx.strokeStyle = colors.outline;
	ctx.lineWidth = Math.max( 1, pitch * 0.06 );
	ctx.stroke();

	const square = pitch * 0.72;
	const dot = Math.max( 1, pitch * 0.09 );
	for ( let row = 0; row < grid.rows; row ++ ) {

		for ( let column = 0; column < grid.columns; column ++ ) {

			const cell = row * grid.columns + column;
			if ( missing.has( cell ) ) continue;
			const [ cx, cy ] = layout.centre( row, column );
			const code = codes ? codes[ offset + cell ] : ( frame && frame[ offset + cell ] ? CODE_BOTH_ON : CODE_BOTH_OFF );
			if ( code === CODE_BOTH_ON || code === CODE_ONLY_RECORDING ) {

				ctx.fillStyle = code === CODE_BOTH_ON ? colors.contact : colors.onlyRecording;
				ctx.fillRect( cx - square / 2, cy - square / 2, square, square );

			} else if ( code === CODE_ONLY_REFERENCE ) {

				ctx.strokeStyle = colors.onlyReference;
				ctx.lineWidth = Math.max( 1, pitch * 0.1 );
				ctx.strokeRect( cx - square / 2, cy - square / 2, square, square );

			} else {

				ctx.fillStyle = colors.dot;
				ctx.beginPath();
				ctx.arc( cx, cy, dot, 0, 2 * Math.PI );
				ctx.fill();

			}

		}

	}

	if ( label ) {

		ctx.fillStyle = colors.label;
		ctx.font = `${ Math.round( labelHeight * 0.8 ) }px system-ui, sans-serif`;
		ctx.textAlign = 'center';
		ctx.textBaseline = 'top';
		ctx.fillText( label, x + width / 2, y );

	}

	return layout;

}

/**
 * A palatogram on its own <canvas> (CSS size `width` x `height`, drawn at the device's pixel
 * ratio). `set( frame )` redraws it; `element` is the canvas.
 */
export class Palatogram extends HiDpiCanvas {

	constructor( { width = 180, height = 200, label = null, document = globalThis.document, grid = READING_GRID, ariaLabel = 'Palatogram' } = {} ) {

		super( { width, height, ariaLabel, className: 'palatogram', document } );
		this.label = label;
		this.grid = grid;
		this.frame = null;
		this.codes = null;
		this.draws = 0;
		this.set( null );

	}

	/** Show contacts (rows * columns 0/1, or null for none), or comparison `codes` instead. */
	set( frame, { codes = null, label = this.label, offset = 0 } = {} ) {

		this.frame = frame;
		this.codes = codes;
		this.label = label;
		const ctx = this.clear();
		if ( ! ctx ) return;
		drawPalatogram( ctx, frame, { width: this.width, height: this.height, label, codes, grid: this.grid, offset } );
		this.draws ++;

	}

}
