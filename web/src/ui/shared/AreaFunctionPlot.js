// The tract's area function drawn flat: the cross-section area of each section of the tube
// (core/areaFunction.js) along the tract, from the glottis (left) to the lips (right), as a filled
// outline of steps; a shut section is marked red; with the velum's port open, the nose as a dashed
// line of steps from where it leaves the tract. Drawn into a 2D context in CSS pixels.

import { TRACT_CLOSURE_MM } from '../../core/constants.js';

/** Colours of the plot. */
export const AREA_COLORS = Object.freeze( { air: '#9fc9ea', edge: '#2f6f9f', shut: '#c62828', nose: '#7b3fa0', ink: '#1f2328', muted: '#6a737d', grid: '#d0d7de' } );
/** The area at the top of the plot, mm² (a wide pharynx behind a fronted tongue passes 1000). */
export const AREA_TOP_MM2 = 1600;
/** The length at the right of the plot, mm (an adult's tract is 150 to 190). */
export const LENGTH_RIGHT_MM = 200;
const PAD = Object.freeze( { left: 40, right: 10, top: 12, bottom: 26 } );

/**
 * The plot's outline: for each section its left and right x and its top y (CSS pixels), from
 * the tube's lengths and areas (count sections, glottis first), in a box of width x height.
 * Areas are drawn on a square-root scale, so that a narrow constriction stays visible beside a
 * wide cavity (the scale of a width, as the section itself would show it).
 */
export function areaSteps( tube, width, height ) {

	const plotWidth = width - PAD.left - PAD.right, plotHeight = height - PAD.top - PAD.bottom;
	const x = ( mm ) => PAD.left + plotWidth * Math.min( mm, LENGTH_RIGHT_MM ) / LENGTH_RIGHT_MM;
	const y = ( mm2 ) => PAD.top + plotHeight * ( 1 - Math.sqrt( Math.min( Math.max( mm2, 0 ), AREA_TOP_MM2 ) / AREA_TOP_MM2 ) );
	const steps = [];
	let at = 0;
	for ( let k = 0; k < tube.count; k ++ ) {

		steps.push( { x0: x( at ), x1: x( at + tube.lengths[ k ] ), y: y( tube.areas[ k ] ), shut: tube.regions[ k ] >= 0 && tube.widths[ k ] < TRACT_CLOSURE_MM } );
		at += tube.lengths[ k ];

	}

	return { steps, baseline: PAD.top + plotHeight, lengthMm: at, x, y };

}

/**
 * Draw the area function of `tube` ({ count, lengths, areas, widths, regions }: createAreaFunction)
 * and its nasal branch, if any ({ at, lengths, areas }: areaFunction.js nasalBranch).
 * @param {CanvasRenderingContext2D} ctx
 * @param {object} tube
 * @param {{ width: number, height: number }} size CSS pixels
 * @param {object|null} [nasal]
 */
export function drawAreaFunction( ctx, tube, { width, height }, nasal = null ) {

	const { steps, baseline, lengthMm, x, y } = areaSteps( tube, width, height );
	ctx.clearRect( 0, 0, width, height );
	ctx.font = '11px system-ui, sans-serif';
	ctx.lineWidth = 1;
	ctx.strokeStyle = AREA_COLORS.grid;
	ctx.fillStyle = AREA_COLORS.muted;
	ctx.textAlign = 'right';
	ctx.textBaseline = 'middle';
	for ( const mm2 of [ 0, 100, 400, 900, 1600 ] ) {

		ctx.beginPath();
		ctx.moveTo( PAD.left, y( mm2 ) );
		ctx.lineTo( width - PAD.right, y( mm2 ) );
		ctx.stroke();
		ctx.fillText( `${ mm2 }`, PAD.left - 4, y( mm2 ) );

	}

	if ( ! steps.length ) return;
	ctx.beginPath();
	ctx.moveTo( steps[ 0 ].x0, baseline );
	for ( const step of steps ) {

		ctx.lineTo( step.x0, step.y );
		ctx.lineTo( step.x1, step.y );

	}

	ctx.lineTo( steps[ steps.length - 1 ].x1, baseline );
	ctx.closePath();
	ctx.fillStyle = AREA_COLORS.air;
	ctx.fill();
	ctx.strokeStyle = AREA_COLORS.edge;
	ctx.stroke();
	ctx.fillStyle = AREA_COLORS.shut;
	for ( const step of steps ) if ( step.shut ) ctx.fillRect( step.x0, baseline - 6, Math.max( 2, step.x1 - step.x0 ), 6 );

	if ( nasal ) drawNose( ctx, nasal, tube.lengths.slice( 0, nasal.at ).reduce( ( a, b ) => a + b, 0 ), x, y );

	ctx.fillStyle = AREA_COLORS.ink;
	ctx.textBaseline = 'alphabetic';
	ctx.textAlign = 'left';
	ctx.fillText( 'glottis', PAD.left, height - 6 );
	ctx.textAlign = 'right';
	ctx.fillText( `lips, ${ Math.round( lengthMm ) } mm`, x( lengthMm ), height - 6 );
	ctx.save();
	ctx.translate( 10, PAD.top + ( baseline - PAD.top ) / 2 );
	ctx.rotate( - Math.PI / 2 );
	ctx.textAlign = 'center';
	ctx.fillStyle = AREA_COLORS.muted;
	ctx.fillText( 'area, mm²', 0, 0 );
	ctx.restore();

}

/** The nose's sections as a dashed line of steps from the junction, `junctionMm` from the glottis. */
function drawNose( ctx, nasal, junctionMm, x, y ) {

	let at = junctionMm;
	ctx.save();
	ctx.setLineDash( [ 4, 3 ] );
	ctx.strokeStyle = AREA_COLORS.nose;
	ctx.lineWidth = 2;
	ctx.beginPath();
	ctx.moveTo( x( junctionMm ), y( 0 ) );
	nasal.lengths.forEach( ( length, k ) => {

		ctx.lineTo( x( at ), y( nasal.areas[ k ] ) );
		at += length;
		ctx.lineTo( x( at ), y( nasal.areas[ k ] ) );

	} );
	ctx.stroke();
	ctx.setLineDash( [] );
	ctx.fillStyle = AREA_COLORS.nose;
	ctx.textAlign = 'left';
	ctx.textBaseline = 'bottom';
	ctx.fillText( 'nose', x( at ) + 3, y( nasal.areas[ nasal.areas.length - 1 ] ) );
	ctx.restore();

}
