// The learner's result beside the head: a mid-sagittal drawing of the target's tongue (filled)
// and the tongue estimated from the learner's sound (a dashed outline in another colour), under
// the palate and upper teeth, with a legend a child can read: a colour and a word for each.
//
// Drawing goes through an injected canvas 2D context, so it runs (and is tested) in Node with a
// recording context. Anterior is on the left, as in the head's profile beside it.

import { fitTransform, strokeSegments, tracePolyline } from '../shared/SagittalPanel.js';

/** The drawing's window on the mid-sagittal plane, mm: the tongue, the palate and the lips. */
export const MOUTH_BOX = Object.freeze( { xMin: - 66, xMax: 34, yMin: - 46, yMax: 30 } );

export const MOUTH_COLORS = Object.freeze( {
	background: '#ffffff',
	ink: '#1f2328',
	muted: '#6a737d',
	target: '#c0353f',
	targetFill: 'rgba(192, 53, 63, 0.32)',
	yours: '#1565c0',
	palate: '#9a8a6e',
} );

/** The legend's words: what a child reads. */
export const MOUTH_WORDS = Object.freeze( { target: 'Target', yours: 'Yours', front: 'lips', back: 'throat', noTarget: 'Choose a target vowel' } );

/** The legend's band at the top, CSS pixels. */
const LEGEND_PX = 40;
/** The words at the front and back under the drawing, CSS pixels. */
const FOOT_PX = 22;
const YOURS_DASH = Object.freeze( [ 9, 6 ] );

/**
 * Draw the mouth.
 * @param {CanvasRenderingContext2D} ctx
 * @param {{ target?: Float64Array|null, estimate?: Float64Array|null,
 *   outlines?: Array<{ segments: Float64Array, count: number, color?: string, pose?: Float64Array|null }> }} scene
 *   target and estimate: x y per station of the tongue's closed mid-sagittal curve (null: not shown)
 * @param {{ width: number, height: number }} size CSS pixels
 * @returns the transform from mm to the canvas
 */
export function drawMouth( ctx, { target = null, estimate = null, outlines = [] }, { width, height } ) {

	ctx.save();
	ctx.fillStyle = MOUTH_COLORS.background;
	ctx.fillRect( 0, 0, width, height );
	const inner = fitTransform( MOUTH_BOX, width, Math.max( 1, height - LEGEND_PX - FOOT_PX ) );
	const view = { scale: inner.scale, x: inner.x, y: ( mm ) => LEGEND_PX + inner.y( mm ) };

	ctx.lineJoin = 'round';
	ctx.lineCap = 'round';
	ctx.lineWidth = 2;
	for ( const outline of outlines ) {

		ctx.strokeStyle = outline.color ?? MOUTH_COLORS.palate;
		strokeSegments( ctx, outline.segments, outline.count, view, outline.pose ?? null );

	}

	if ( target ) {

		ctx.fillStyle = MOUTH_COLORS.targetFill;
		ctx.strokeStyle = MOUTH_COLORS.target;
		ctx.lineWidth = 2.5;
		tracePolyline( ctx, target, view, true );
		ctx.fill();
		ctx.stroke();

	}

	if ( estimate ) {

		ctx.strokeStyle = MOUTH_COLORS.yours;
		ctx.lineWidth = 3.5;
		ctx.setLineDash( YOURS_DASH );
		tracePolyline( ctx, estimate, view, true );
		ctx.stroke();
		ctx.setLineDash( [] );

	}

	drawLegend( ctx, { target: Boolean( target ), estimate: Boolean( estimate ) }, width );
	ctx.fillStyle = MOUTH_COLORS.muted;
	ctx.font = '14px system-ui, sans-serif';
	ctx.textBaseline = 'bottom';
	ctx.textAlign = 'left';
	ctx.fillText( `◀ ${ MOUTH_WORDS.front }`, 8, height - 4 );
	ctx.textAlign = 'right';
	ctx.fillText( `${ MOUTH_WORDS.back } ▶`, width - 8, height - 4 );
	if ( ! target ) {

		// In the middle of an empty drawing; under the learner's tongue when there is one.
		ctx.fillStyle = MOUTH_COLORS.ink;
		ctx.font = '600 16px system-ui, sans-serif';
		ctx.textAlign = 'center';
		ctx.textBaseline = estimate ? 'bottom' : 'middle';
		ctx.fillText( MOUTH_WORDS.noTarget, width / 2, estimate ? height - 3 : LEGEND_PX + ( height - LEGEND_PX - FOOT_PX ) / 2 );

	}

	ctx.restore();
	return view;

}

/** A swatch and a word for each tongue shown, on the band at the top: filled red, dashed blue. */
function drawLegend( ctx, shown, width ) {

	const entries = [];
	if ( shown.target ) entries.push( 'target' );
	if ( shown.estimate ) entries.push( 'yours' );
	ctx.font = 'bold 18px system-ui, sans-serif';
	ctx.textBaseline = 'middle';
	ctx.textAlign = 'left';
	const y = LEGEND_PX / 2;
	const swatch = 30;
	const gap = 22;
	const widths = entries.map( ( entry ) => swatch + 8 + ctx.measureText( MOUTH_WORDS[ entry ] ).width );
	let x = Math.max( 8, ( width - widths.reduce( ( a, b ) => a + b + gap, - gap ) ) / 2 );
	entries.forEach( ( entry, k ) => {

		if ( entry === 'target' ) {

			ctx.fillStyle = MOUTH_COLORS.targetFill;
			ctx.strokeStyle = MOUTH_COLORS.target;
			ctx.lineWidth = 2.5;
			ctx.beginPath();
			ctx.rect( x, y - 9, swatch, 18 );
			ctx.fill();
			ctx.stroke();

		} else {

			ctx.strokeStyle = MOUTH_COLORS.yours;
			ctx.lineWidth = 3.5;
			ctx.setLineDash( [ 7, 4 ] );
			ctx.beginPath();
			ctx.rect( x, y - 9, swatch, 18 );
			ctx.stroke();
			ctx.setLineDash( [] );

		}

		ctx.fillStyle = entry === 'target' ? MOUTH_COLORS.target : MOUTH_COLORS.yours;
		ctx.fillText( MOUTH_WORDS[ entry ], x + swatch + 8, y );
		x += widths[ k ] + gap;

	} );

}
