// The mid-sagittal panel of the workbench (the paper's Figure 4): the tongue's sagittal curve with
// its lettered control points and the hub, over the palate, jaw and lips cut at z = 0.
//
// Drawing goes through an injected canvas 2D context, so it runs (and is tested) in Node with a
// recording context; the data are plain typed arrays read from the articulation.

import { planeSectionSegments } from '../../core/section.js';
import { midlinePage, stationVertexOffset } from '../../core/tongue.js';

/** The panel's window on the mid-sagittal plane, mm (project frame): mouth, tongue and jaw. */
export const SAGITTAL_BOX = Object.freeze( { xMin: - 70, xMax: 46, yMin: - 62, yMax: 32 } );

export const PANEL_COLORS = Object.freeze( {
	background: '#fbfaf8',
	grid: '#e6e2dc',
	ink: '#2b2b2b',
	muted: '#77706a',
	tongue: '#c0353f',
	tongueFill: 'rgba(192, 53, 63, 0.22)',
	rest: '#9a928a',
	control: '#1f2328',
	palate: '#b85d66',
	jaw: '#a88a55',
	lip: '#d46f7a',
	contact: '#6b0f1a',
} );

/**
 * Map a box in mm onto a width x height canvas, keeping the aspect ratio, anterior (+x) to the
 * LEFT, as the profile view of the cutaway shows it. Returns { scale, x( mmX ), y( mmY ) }.
 */
export function fitTransform( box, width, height, margin = 8 ) {

	const scale = Math.min( ( width - 2 * margin ) / ( box.xMax - box.xMin ), ( height - 2 * margin ) / ( box.yMax - box.yMin ) );
	const cx = ( box.xMin + box.xMax ) / 2;
	const cy = ( box.yMin + box.yMax ) / 2;
	const flip = box.flipX === false ? 1 : - 1;
	return {
		scale,
		x: ( mm ) => width / 2 + flip * ( mm - cx ) * scale,
		y: ( mm ) => height / 2 - ( mm - cy ) * scale,
	};

}

/**
 * Trace a polyline of x y pairs (optionally closed) as the current path.
 * @param {CanvasRenderingContext2D} ctx
 * @param {ArrayLike<number>} points x y per point
 */
export function tracePolyline( ctx, points, view, closed = false ) {

	ctx.beginPath();
	for ( let k = 0; k < points.length; k += 2 ) {

		if ( k === 0 ) ctx.moveTo( view.x( points[ k ] ), view.y( points[ k + 1 ] ) );
		else ctx.lineTo( view.x( points[ k ] ), view.y( points[ k + 1 ] ) );

	}

	if ( closed ) ctx.closePath();

}

/** Stroke `count` segments x0 y0 x1 y1, each mapped through pose (3 x 4, row-major) when given. */
export function strokeSegments( ctx, segments, count, view, pose = null ) {

	ctx.beginPath();
	for ( let s = 0; s < count; s ++ ) {

		for ( let e = 0; e < 2; e ++ ) {

			let x = segments[ 4 * s + 2 * e ];
			let y = segments[ 4 * s + 2 * e + 1 ];
			if ( pose ) {

				const px = pose[ 0 ] * x + pose[ 1 ] * y + pose[ 3 ];
				y = pose[ 4 ] * x + pose[ 5 ] * y + pose[ 7 ];
				x = px;

			}

			if ( e === 0 ) ctx.moveTo( view.x( x ), view.y( y ) );
			else ctx.lineTo( view.x( x ), view.y( y ) );

		}

	}

	ctx.stroke();

}

/** Light 10 mm grid lines and a scale bar. */
export function drawGrid( ctx, box, view, width, height ) {

	ctx.strokeStyle = PANEL_COLORS.grid;
	ctx.lineWidth = 1;
	ctx.beginPath();
	for ( let x = Math.ceil( box.xMin / 10 ) * 10; x <= box.xMax; x += 10 ) {

		ctx.moveTo( view.x( x ), view.y( box.yMin ) );
		ctx.lineTo( view.x( x ), view.y( box.yMax ) );

	}

	for ( let y = Math.ceil( box.yMin / 10 ) * 10; y <= box.yMax; y += 10 ) {

		ctx.moveTo( view.x( box.xMin ), view.y( y ) );
		ctx.lineTo( view.x( box.xMax ), view.y( y ) );

	}

	ctx.stroke();
	const bar = 10 * view.scale;
	ctx.strokeStyle = PANEL_COLORS.ink;
	ctx.lineWidth = 2;
	ctx.beginPath();
	ctx.moveTo( width - 12 - bar, height - 12 );
	ctx.lineTo( width - 12, height - 12 );
	ctx.stroke();
	ctx.fillStyle = PANEL_COLORS.ink;
	ctx.font = '11px system-ui, sans-serif';
	ctx.textAlign = 'center';
	ctx.textBaseline = 'bottom';
	ctx.fillText( '10 mm', width - 12 - bar / 2, height - 15 );

}

/**
 * The tongue's mid-sagittal curve: the ring vertex at page angle 0 of every station.
 * @param {import('../../core/tongue.js').TongueRig} rig
 * @param {Float32Array} positions xyz per tongue vertex
 * @param {Float64Array} target 2 * rig.stationCount (x y per station)
 */
export function sagittalCurve( rig, positions, target ) {

	const middle = midlinePage( rig );
	for ( let i = 0; i < rig.stationCount; i ++ ) {

		const o = stationVertexOffset( rig, i, middle );
		target[ 2 * i ] = positions[ o ];
		target[ 2 * i + 1 ] = positions[ o + 1 ];

	}

	return target;

}

/**
 * The cut of one anatomy part by the mid-sagittal plane, for the panel: x y segments in the
 * part's own frame and the pose (3 x 4, row-major) of its group. Parts that move only about a
 * z-parallel axis (the jaw) or are deformed in place (the lips) keep their cut in z = 0.
 * Reallocates only when the part has more triangles than before.
 */
export class MidlineOutline {

	constructor( color ) {

		this.color = color;
		this.scratch = new Float32Array( 0 );
		this.segments = new Float64Array( 0 );
		this.count = 0;
		this.pose = Float64Array.of( 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 );

	}

	/**
	 * @param {Float32Array} positions xyz per vertex, the part's frame
	 * @param {Uint16Array|Uint32Array|null} index
	 * @param {ArrayLike<number>|null} matrix the group's 4 x 4 matrix, column-major (three.js
	 *   Matrix4.elements), or null for none
	 */
	update( positions, index, matrix = null ) {

		const triangles = index ? index.length / 3 : positions.length / 9;
		if ( this.scratch.length < 6 * triangles ) {

			this.scratch = new Float32Array( 6 * triangles );
			this.segments = new Float64Array( 4 * triangles );

		}

		this.count = planeSectionSegments( positions, index, 0, this.scratch );
		for ( let s = 0; s < this.count; s ++ ) {

			this.segments[ 4 * s ] = this.scratch[ 6 * s ];
			this.segments[ 4 * s + 1 ] = this.scratch[ 6 * s + 1 ];
			this.segments[ 4 * s + 2 ] = this.scratch[ 6 * s + 3 ];
			this.segments[ 4 * s + 3 ] = this.scratch[ 6 * s + 4 ];

		}

		if ( matrix ) {

			for ( let row = 0; row < 3; row ++ ) for ( let column = 0; column < 4; column ++ ) this.pose[ 4 * row + column ] = matrix[ 4 * column + row ];

		}

		return this;

	}

}

/**
 * Draw the panel.
 * @param {CanvasRenderingContext2D} ctx
 * @param {{ curve: Float64Array, restCurve?: Float64Array, rawCurve?: Float64Array, points: Float64Array, letters: string[],
 *   hub: ArrayLike<number>, origin?: ArrayLike<number>|null,
 *   outlines?: Array<{ segments: Float64Array, count: number, color: string, pose?: Float64Array|null }> }} scene
 *   curve, restCurve (neutral) and rawCurve (before collision correction): x y per station,
 *   closed; points: posed control points, x y each
 * @param {{ width: number, height: number, box?: object }} size CSS pixels
 */
export function drawSagittalPanel( ctx, scene, { width, height, box = SAGITTAL_BOX } ) {

	const view = fitTransform( box, width, height );
	ctx.save();
	ctx.fillStyle = PANEL_COLORS.background;
	ctx.fillRect( 0, 0, width, height );
	drawGrid( ctx, box, view, width, height );

	ctx.lineJoin = 'round';
	ctx.lineWidth = 1.6;
	for ( const outline of scene.outlines ?? [] ) {

		ctx.strokeStyle = outline.color;
		strokeSegments( ctx, outline.segments, outline.count, view, outline.pose ?? null );

	}

	if ( scene.restCurve ) {

		ctx.strokeStyle = PANEL_COLORS.rest;
		ctx.lineWidth = 1;
		ctx.setLineDash( [ 4, 3 ] );
		tracePolyline( ctx, scene.restCurve, view, true );
		ctx.stroke();
		ctx.setLineDash( [] );

	}

	if ( scene.rawCurve ) {

		// Where the tongue would be without collision correction: inside the palate.
		ctx.strokeStyle = PANEL_COLORS.tongue;
		ctx.lineWidth = 1;
		ctx.setLineDash( [ 1.5, 2.5 ] );
		tracePolyline( ctx, scene.rawCurve, view, true );
		ctx.stroke();
		ctx.setLineDash( [] );

	}

	ctx.fillStyle = PANEL_COLORS.tongueFill;
	ctx.strokeStyle = PANEL_COLORS.tongue;
	ctx.lineWidth = 2.2;
	tracePolyline( ctx, scene.curve, view, true );
	ctx.fill();
	ctx.stroke();

	// Control polygon (closed, like the curve) and its lettered points.
	ctx.strokeStyle = PANEL_COLORS.control;
	ctx.lineWidth = 0.8;
	ctx.setLineDash( [ 2, 2 ] );
	tracePolyline( ctx, scene.points, view, true );
	ctx.stroke();
	ctx.setLineDash( [] );
	ctx.font = 'bold 11px system-ui, sans-serif';
	ctx.textAlign = 'center';
	ctx.textBaseline = 'middle';
	for ( let k = 0; k < scene.letters.length; k ++ ) {

		const x = view.x( scene.points[ 2 * k ] );
		const y = view.y( scene.points[ 2 * k + 1 ] );
		ctx.fillStyle = PANEL_COLORS.control;
		ctx.fillRect( x - 2.5, y - 2.5, 5, 5 );
		// The letter sits outside the curve: away from the hub.
		const dx = x - view.x( scene.hub[ 0 ] );
		const dy = y - view.y( scene.hub[ 1 ] );
		const d = Math.hypot( dx, dy ) || 1;
		ctx.fillText( scene.letters[ k ], x + 10 * dx / d, y + 10 * dy / d );

	}

	drawMark( ctx, view.x( scene.hub[ 0 ] ), view.y( scene.hub[ 1 ] ), 'H', PANEL_COLORS.control );
	if ( scene.origin ) drawMark( ctx, view.x( scene.origin[ 0 ] ), view.y( scene.origin[ 1 ] ), 'O', PANEL_COLORS.muted );

	// The title on a band of its own: the raised tongue's letters may reach the top edge.
	ctx.fillStyle = PANEL_COLORS.background;
	ctx.fillRect( 0, 0, width, 22 );
	ctx.fillStyle = PANEL_COLORS.ink;
	ctx.font = '600 12px system-ui, sans-serif';
	ctx.textAlign = 'left';
	ctx.textBaseline = 'top';
	ctx.fillText( 'Mid-sagittal: control points A–S, hub H', 8, 6 );
	ctx.restore();
	return view;

}

/** A small cross with a label: the hub H or the collision origin O. */
function drawMark( ctx, x, y, label, color ) {

	ctx.strokeStyle = color;
	ctx.fillStyle = color;
	ctx.lineWidth = 1.4;
	ctx.beginPath();
	ctx.moveTo( x - 5, y );
	ctx.lineTo( x + 5, y );
	ctx.moveTo( x, y - 5 );
	ctx.lineTo( x, y + 5 );
	ctx.stroke();
	ctx.font = 'bold 11px system-ui, sans-serif';
	ctx.textAlign = 'left';
	ctx.textBaseline = 'bottom';
	ctx.fillText( label, x + 4, y - 3 );

}
