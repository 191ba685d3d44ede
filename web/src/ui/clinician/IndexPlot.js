// EPG index curves over time: one panel per index (percent contact, centre of gravity,
// anteriority, centrality, dorsopalatal), each with its fixed range, a shared time axis, one line
// per track (the recording solid, the target dashed: the caption around the canvas says so) and a
// cursor at the current time.
//
// Drawing goes through an injected 2D context (drawIndexPlot), so it can be tested without a
// browser; scaleLinear is the one mapping every line and the cursor use.

import { EPG_PLOT_DEFAULT_PANELS, EPG_PLOT_PANELS } from '../../core/constants.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';

// The panels (each index's label and fixed range, and the default choice) are the server's plot
// spec, EPG_PLOT_PANELS and EPG_PLOT_DEFAULT_PANELS of constants.py.

const COLORS = Object.freeze( { axis: '#8c959f', text: '#57606a', cursor: '#b4384a', grid: '#e4e8ec' } );
const LEFT = 92;

/** The linear map of [d0, d1] onto [r0, r1] (a flat domain maps to the middle). */
export function scaleLinear( d0, d1, r0, r1 ) {

	const span = d1 - d0;
	return span === 0 ? () => ( r0 + r1 ) / 2 : ( value ) => r0 + ( value - d0 ) * ( r1 - r0 ) / span;

}

/**
 * @param {CanvasRenderingContext2D} ctx
 * @param {{width: number, height: number, t_s: ArrayLike<number>, tracks: Array<{label: string,
 *   indices: Object<string, ArrayLike<number>>, color: string, dash?: number[]}>,
 *   panels?: string[], current?: number|null}} options every track has one value per time;
 *   `current` is a frame index
 * @returns {{panelHeight: number, x: Function}} the geometry used
 */
export function drawIndexPlot( ctx, { width, height, t_s, tracks, panels = EPG_PLOT_DEFAULT_PANELS, current = null } ) {

	const n = t_s.length;
	const t0 = n ? t_s[ 0 ] : 0;
	const t1 = n > 1 ? t_s[ n - 1 ] : t0 + 1;
	const bottom = 18;
	const panelHeight = ( height - bottom ) / panels.length;
	const x = scaleLinear( t0, t1, LEFT, width - 8 );
	ctx.font = '12px system-ui, sans-serif';
	ctx.textBaseline = 'middle';

	panels.forEach( ( name, p ) => {

		const top = p * panelHeight + 4;
		const [ lo, hi ] = EPG_PLOT_PANELS[ name ]?.range ?? [ 0, 1 ];
		const y = scaleLinear( lo, hi, top + panelHeight - 8, top );
		ctx.strokeStyle = COLORS.grid;
		ctx.lineWidth = 1;
		ctx.setLineDash( [] );
		ctx.strokeRect( LEFT, top, width - 8 - LEFT, panelHeight - 8 );
		ctx.fillStyle = COLORS.text;
		ctx.textAlign = 'right';
		ctx.fillText( EPG_PLOT_PANELS[ name ]?.short_label ?? name, LEFT - 8, top + ( panelHeight - 8 ) / 2 );
		ctx.fillText( String( hi ), LEFT - 8, top + 6 );
		for ( const track of tracks ) {

			const values = track.indices[ name ];
			if ( ! values || values.length !== n ) continue;
			ctx.strokeStyle = track.color;
			ctx.lineWidth = 2;
			ctx.setLineDash( track.dash ?? [] );
			ctx.beginPath();
			for ( let i = 0; i < n; i ++ ) {

				// Sample and hold: EPG frames are held until the next one.
				const xi = x( t_s[ i ] ), yi = y( values[ i ] );
				if ( i === 0 ) ctx.moveTo( xi, yi );
				else {

					ctx.lineTo( xi, y( values[ i - 1 ] ) );
					ctx.lineTo( xi, yi );

				}

			}

			ctx.stroke();

		}

	} );

	ctx.setLineDash( [] );
	ctx.fillStyle = COLORS.text;
	ctx.textAlign = 'left';
	ctx.fillText( '0 ms', LEFT, height - bottom / 2 );
	ctx.textAlign = 'right';
	ctx.fillText( `${ Math.round( ( t1 - t0 ) * 1000 ) } ms`, width - 8, height - bottom / 2 );
	if ( current !== null && current >= 0 && current < n ) {

		ctx.strokeStyle = COLORS.cursor;
		ctx.lineWidth = 2;
		ctx.beginPath();
		ctx.moveTo( x( t_s[ current ] ), 0 );
		ctx.lineTo( x( t_s[ current ] ), height - bottom );
		ctx.stroke();

	}

	ctx.setLineDash( [] );
	return { panelHeight, x };

}

/** A plot on its own <canvas>; `set( { t_s, tracks, current } )` redraws it. */
export class IndexPlot extends HiDpiCanvas {

	constructor( { width = 640, height = 300, document = globalThis.document, panels = EPG_PLOT_DEFAULT_PANELS } = {} ) {

		super( { width, height, document, className: 'index-plot', ariaLabel: 'EPG indices over time' } );
		this.panels = panels;

	}

	set( { t_s, tracks, current = null } ) {

		const ctx = this.clear();
		if ( ! ctx ) return null;
		return drawIndexPlot( ctx, { width: this.width, height: this.height, t_s, tracks, panels: this.panels, current } );

	}

}
