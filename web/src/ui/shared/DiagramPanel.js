// The flat mid-sagittal diagram of the vocal tract: a clean line drawing for a projector (air,
// tongue, palate and upper teeth, mandible and lower teeth, lips, velum, pharyngeal wall and
// larynx), drawn from the section of the current frame (scene/DiagramSection.js), with the
// narrowest constriction marked.
//
// Drawing goes through an injected canvas 2D context, so it runs (and is tested) in Node with a
// recording context. It is drawn when the articulation changes, never by the render loop.

import { fitTransform } from './SagittalPanel.js';

export const DIAGRAM_COLORS = Object.freeze( {
	background: '#ffffff',
	ink: '#1d1d1f',
	muted: '#6b6b70',
	air: '#d6ecfa',
	airLine: '#7fb4d8',
	tongue: '#f2aab3',
	lip: '#eea0aa',
	velum: '#f5c3c9',
	soft: '#f7dcd8',
	bone: '#f1e7d0',
	cartilage: '#dde8f0',
	constriction: '#d0202e',
} );

/** How each part is drawn: fill of its closed loops (null: lines only) and its line width. */
export const DIAGRAM_STYLES = Object.freeze( {
	pharynx: { fill: null, line: 2 },
	larynx: { fill: DIAGRAM_COLORS.cartilage, line: 1.6 },
	palate: { fill: DIAGRAM_COLORS.bone, line: 1.8 },
	mandible: { fill: DIAGRAM_COLORS.bone, line: 1.8 },
	velum: { fill: DIAGRAM_COLORS.velum, line: 1.8 },
	upperLip: { fill: DIAGRAM_COLORS.lip, line: 1.8 },
	lowerLip: { fill: DIAGRAM_COLORS.lip, line: 1.8 },
	tongue: { fill: DIAGRAM_COLORS.tongue, line: 2.2 },
} );

/** Drawing order, back to front (the air first, under everything). */
export const DIAGRAM_ORDER = Object.freeze( [ 'pharynx', 'larynx', 'palate', 'mandible', 'velum', 'upperLip', 'lowerLip', 'tongue' ] );

/** The diagram's window (mm): the tract from the lips to below the larynx. */
export const DIAGRAM_BOX = Object.freeze( { xMin: - 78, xMax: 50, yMin: - 86, yMax: 34 } );

/** Trace chain c of a section part ({ points, starts, closed }) as a sub-path of the current path. */
export function traceChain( ctx, part, c, view ) {

	const first = part.starts[ c ], end = part.starts[ c + 1 ];
	const p = part.points;
	for ( let k = first; k < end; k ++ ) {

		if ( k === first ) ctx.moveTo( view.x( p[ 2 * k ] ), view.y( p[ 2 * k + 1 ] ) );
		else ctx.lineTo( view.x( p[ 2 * k ] ), view.y( p[ 2 * k + 1 ] ) );

	}

	if ( part.closed[ c ] ) ctx.closePath();

}

/** Fill the closed loops of the parts, then stroke every chain. */
function drawPart( ctx, sections, style, view ) {

	if ( style.fill ) {

		ctx.fillStyle = style.fill;
		ctx.beginPath();
		for ( const part of sections ) for ( let c = 0; c < part.chainCount; c ++ ) if ( part.closed[ c ] ) traceChain( ctx, part, c, view );
		ctx.fill( 'evenodd' );

	}

	ctx.strokeStyle = DIAGRAM_COLORS.ink;
	ctx.lineWidth = style.line;
	ctx.beginPath();
	for ( const part of sections ) for ( let c = 0; c < part.chainCount; c ++ ) traceChain( ctx, part, c, view );
	ctx.stroke();

}

/**
 * Draw the diagram.
 * @param {CanvasRenderingContext2D} ctx
 * @param {{ parts: Object<string, object[]>, air?: { outline: Float64Array, holes: Float64Array[] }|null,
 *   constriction?: { widthMm: number, place: string|null, floor: number[], roof: number[] }|null }} scene
 *   parts: section parts (core/midSection.js) by DIAGRAM_ORDER key; air: the airway's polygon
 * @param {{ width: number, height: number, box?: object }} size CSS pixels
 * @returns {{ scale: number, x: Function, y: Function }} the mm to pixel transform
 */
export function drawDiagram( ctx, scene, { width, height, box = DIAGRAM_BOX } ) {

	const view = fitTransform( box, width, height, 10 );
	ctx.save();
	ctx.fillStyle = DIAGRAM_COLORS.background;
	ctx.fillRect( 0, 0, width, height );
	ctx.lineJoin = 'round';
	ctx.lineCap = 'round';

	if ( scene.air ) {

		ctx.fillStyle = DIAGRAM_COLORS.air;
		ctx.strokeStyle = DIAGRAM_COLORS.airLine;
		ctx.lineWidth = 1;
		ctx.beginPath();
		for ( const loop of [ scene.air.outline, ...scene.air.holes ] ) {

			for ( let k = 0; k < loop.length; k += 2 ) {

				if ( k === 0 ) ctx.moveTo( view.x( loop[ k ] ), view.y( loop[ k + 1 ] ) );
				else ctx.lineTo( view.x( loop[ k ] ), view.y( loop[ k + 1 ] ) );

			}

			ctx.closePath();

		}

		ctx.fill( 'evenodd' );

	}

	for ( const key of DIAGRAM_ORDER ) {

		const sections = scene.parts[ key ];
		if ( sections?.length ) drawPart( ctx, sections, DIAGRAM_STYLES[ key ], view );

	}

	if ( scene.constriction ) drawConstriction( ctx, scene.constriction, view, width, height );

	ctx.fillStyle = DIAGRAM_COLORS.ink;
	ctx.font = '600 13px system-ui, sans-serif';
	ctx.textAlign = 'left';
	ctx.textBaseline = 'top';
	ctx.fillText( 'Vocal tract, mid-sagittal', 10, 8 );
	ctx.restore();
	return view;

}

/** The narrowest gap: a red bar across it with a dot in its middle, and its width and place. */
function drawConstriction( ctx, { widthMm, place, floor, roof }, view, width, height ) {

	const fx = view.x( floor[ 0 ] ), fy = view.y( floor[ 1 ] );
	const rx = view.x( roof[ 0 ] ), ry = view.y( roof[ 1 ] );
	const mx = ( fx + rx ) / 2, my = ( fy + ry ) / 2;
	ctx.strokeStyle = DIAGRAM_COLORS.constriction;
	ctx.fillStyle = DIAGRAM_COLORS.constriction;
	ctx.lineWidth = 3;
	ctx.beginPath();
	ctx.moveTo( fx, fy );
	ctx.lineTo( rx, ry );
	ctx.stroke();
	ctx.beginPath();
	ctx.arc( mx, my, 5, 0, 2 * Math.PI );
	ctx.fill();
	ctx.font = '600 13px system-ui, sans-serif';
	ctx.textAlign = 'center';
	ctx.textBaseline = 'middle';
	const label = `${ widthMm.toFixed( 1 ) } mm${ place ? ` · ${ place }` : '' }`;
	// Below the gap, on a white band, kept inside the panel.
	const half = ( ctx.measureText ? ctx.measureText( label ).width : 7 * label.length ) / 2 + 4;
	const x = Math.min( Math.max( mx, half + 2 ), width - half - 2 );
	const y = Math.min( my + 22, height - 12 );
	ctx.fillStyle = 'rgba(255, 255, 255, 0.88)';
	ctx.fillRect( x - half, y - 9, 2 * half, 18 );
	ctx.fillStyle = DIAGRAM_COLORS.constriction;
	ctx.fillText( label, x, y );

}
