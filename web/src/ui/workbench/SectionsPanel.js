// The coronal panel of the workbench (the paper's Figure 4): the front, middle and back coronal
// sections of the tongue as they are now (over their rest shape, dashed), with their radial
// control values, and the blending functions that say where along the tongue each section applies.
//
// Drawing goes through an injected canvas 2D context (testable in Node); the data are typed
// arrays read from the articulation and the rig.

import { fitTransform, PANEL_COLORS, tracePolyline } from '../shared/SagittalPanel.js';
import { SECTION_COUNT } from '../../core/tongueStations.js';

export const SECTION_NAMES = Object.freeze( [ 'front', 'middle', 'back' ] );
export const SECTION_COLORS = Object.freeze( [ '#2f6db5', '#2e8b57', '#7b4ea3' ] );

/**
 * Window on a section, mm: lateral z (the subject's left to the right) by the distance from the
 * hub line, from `below` under the section's rest top to `above` over it: the upper surface,
 * where grooves, edges and widths show.
 */
export const SECTION_WINDOW = Object.freeze( { halfWidth: 33, below: 26, above: 9 } );

/** Share of the panel's height given to the sections (the rest shows the blending functions). */
const SECTIONS_SHARE = 0.5;

/**
 * The station where each section acts most: the largest blend of that section on the upper
 * surface (blend times coronal weight). Returns [front, middle, back] station indices.
 */
export function sectionStations( rig ) {

	const stations = [];
	for ( let s = 0; s < SECTION_COUNT; s ++ ) {

		let best = 0;
		for ( let i = 1; i < rig.stationCount; i ++ ) {

			if ( rig.stationOffsetBlend[ i * SECTION_COUNT + s ] > rig.stationOffsetBlend[ best * SECTION_COUNT + s ] ) best = i;

		}

		stations.push( best );

	}

	return stations;

}

/**
 * One coronal section in its page: lateral z and distance along the page direction from the hub
 * line, from the right pole through the ring to the left pole.
 * @param {object} rig TongueRig
 * @param {Float32Array} positions xyz per tongue vertex
 * @param {number} station
 * @param {ArrayLike<number>} hub posed hub x y
 * @param {ArrayLike<number>} directions page direction x y per station
 * @param {Float64Array} target 2 * ( rig.pageCount + 2 )
 */
export function coronalSection( rig, positions, station, hub, directions, target ) {

	const ex = directions[ 2 * station ];
	const ey = directions[ 2 * station + 1 ];
	const write = ( k, v ) => {

		const o = 3 * v;
		target[ 2 * k ] = positions[ o + 2 ];
		target[ 2 * k + 1 ] = ( positions[ o ] - hub[ 0 ] ) * ex + ( positions[ o + 1 ] - hub[ 1 ] ) * ey;

	};

	write( 0, 0 );
	for ( let j = 0; j < rig.pageCount; j ++ ) write( j + 1, 2 + station * rig.pageCount + j );
	write( rig.pageCount + 1, 1 );
	return target;

}

/**
 * The radial control values of a station drawn where they act: control k at its page angle,
 * lateral lambda sin( phi ) ( 1 + stretch fade ), radial lambda cos( phi ).
 * @param {Float64Array} controls lambda per station and control (rig.controls layout)
 * @param {Float64Array} stretch sideways stretch per station
 * @param {Float64Array} target 2 * controlCount
 */
export function sectionControls( rig, controls, stretch, station, target ) {

	const angles = rig.definition.coronal.control_angles_deg;
	for ( let k = 0; k < rig.controlCount; k ++ ) {

		const phi = angles[ k ] * Math.PI / 180;
		const s = Math.sin( phi );
		const lambda = controls[ station * rig.controlCount + k ];
		target[ 2 * k ] = lambda * s * ( 1 + stretch[ station ] * ( 1 - s * s * s * s ) );
		target[ 2 * k + 1 ] = lambda * Math.cos( phi );

	}

	return target;

}

/**
 * The blending functions along the tongue: for every station its parameter u, each section's
 * blend and the coronal weight (where coronal articulation acts at all), and the u where each
 * sagittal control point weighs most, for the letters.
 */
export function blendingFunctions( rig ) {

	const n = rig.stationCount;
	const u = Float64Array.from( rig.definition.surface.station_params );
	const curves = SECTION_NAMES.map( ( _, s ) => Float64Array.from( { length: n }, ( __, i ) => rig.stationBlend[ i * SECTION_COUNT + s ] ) );
	const coronal = Float64Array.from( { length: n }, ( _, i ) => {

		let sum = 0;
		for ( let s = 0; s < SECTION_COUNT; s ++ ) sum += rig.stationOffsetBlend[ i * SECTION_COUNT + s ];
		return sum;

	} );
	const best = new Float64Array( rig.pointCount );
	const letters = rig.definition.sagittal.control_points.map( ( p ) => ( { letter: p.name, u: 0 } ) );
	for ( let i = 0; i < n; i ++ ) {

		for ( let k = 0; k < rig.sagittalWidth; k ++ ) {

			const weight = rig.stationBasis[ i * rig.sagittalWidth + k ];
			const point = ( rig.stationFirst[ i ] + k ) % rig.pointCount;
			if ( weight > best[ point ] ) {

				best[ point ] = weight;
				letters[ point ].u = u[ i ];

			}

		}

	}

	return { u, curves, coronal, letters };

}

/**
 * Draw the panel.
 * @param {CanvasRenderingContext2D} ctx
 * @param {{ sections: Array<{ points: Float64Array, rest?: Float64Array, controls?: Float64Array }>,
 *   stations: number[], blends: ReturnType<typeof blendingFunctions> }} scene sections in
 *   SECTION_NAMES order
 * @param {{ width: number, height: number }} size CSS pixels
 * @returns the transforms used: { sections: [view], blends: { x( u ), y( weight ) } }
 */
export function drawSectionsPanel( ctx, scene, { width, height } ) {

	ctx.save();
	ctx.fillStyle = PANEL_COLORS.background;
	ctx.fillRect( 0, 0, width, height );
	const top = 20;
	const sectionHeight = Math.round( height * SECTIONS_SHARE ) - top;
	const cell = width / SECTION_COUNT;
	const views = [];
	ctx.font = '600 12px system-ui, sans-serif';
	ctx.textBaseline = 'top';
	ctx.textAlign = 'left';
	ctx.fillStyle = PANEL_COLORS.ink;
	ctx.fillText( 'Coronal sections (seen from the front)', 8, 4 );

	scene.sections.forEach( ( section, s ) => {

		const top0 = sectionTop( section.rest ?? section.points );
		const box = {
			xMin: - SECTION_WINDOW.halfWidth, xMax: SECTION_WINDOW.halfWidth, flipX: false,
			yMin: top0 - SECTION_WINDOW.below, yMax: top0 + SECTION_WINDOW.above,
		};
		const fit = fitTransform( box, cell, sectionHeight, 4 );
		const left = s * cell;
		const view = { scale: fit.scale, x: ( mm ) => left + fit.x( mm ), y: ( mm ) => top + fit.y( mm ) };
		views.push( view );

		ctx.save();
		ctx.beginPath();
		ctx.rect( left, top, cell, sectionHeight );
		ctx.clip();
		ctx.strokeStyle = PANEL_COLORS.grid;
		ctx.lineWidth = 1;
		ctx.beginPath();
		ctx.moveTo( view.x( 0 ), view.y( box.yMin ) );
		ctx.lineTo( view.x( 0 ), view.y( box.yMax ) );
		for ( let r = Math.ceil( box.yMin / 10 ) * 10; r <= box.yMax; r += 10 ) {

			ctx.moveTo( view.x( box.xMin ), view.y( r ) );
			ctx.lineTo( view.x( box.xMax ), view.y( r ) );

		}

		ctx.stroke();

		if ( section.rest ) {

			ctx.strokeStyle = PANEL_COLORS.rest;
			ctx.setLineDash( [ 4, 3 ] );
			tracePolyline( ctx, section.rest, view, false );
			ctx.stroke();
			ctx.setLineDash( [] );

		}

		ctx.fillStyle = PANEL_COLORS.tongueFill;
		ctx.strokeStyle = SECTION_COLORS[ s ];
		ctx.lineWidth = 2;
		tracePolyline( ctx, section.points, view, false );
		ctx.fill();
		ctx.stroke();

		if ( section.controls ) {

			ctx.fillStyle = PANEL_COLORS.control;
			for ( let k = 0; k < section.controls.length; k += 2 ) ctx.fillRect( view.x( section.controls[ k ] ) - 2, view.y( section.controls[ k + 1 ] ) - 2, 4, 4 );

		}

		ctx.restore();
		ctx.fillStyle = SECTION_COLORS[ s ];
		ctx.font = '600 12px system-ui, sans-serif';
		ctx.textAlign = 'center';
		ctx.textBaseline = 'top';
		ctx.fillText( SECTION_NAMES[ s ], left + cell / 2, top + sectionHeight + 2 );

	} );

	const blends = drawBlends( ctx, scene, { left: 34, right: width - 10, top: top + sectionHeight + 42, bottom: height - 22 } );
	ctx.restore();
	return { sections: views, blends };

}

/** The largest distance from the hub line of a section (its top, for the window). */
function sectionTop( points ) {

	let top = - Infinity;
	for ( let k = 1; k < points.length; k += 2 ) top = Math.max( top, points[ k ] );
	return top;

}

/** The blending functions with the chosen stations marked and the control points lettered below. */
function drawBlends( ctx, scene, area ) {

	const { u, curves, coronal, letters } = scene.blends;
	const x = ( value ) => area.left + value * ( area.right - area.left );
	const y = ( weight ) => area.bottom - weight * ( area.bottom - area.top );
	const view = { x, y };

	ctx.font = '600 12px system-ui, sans-serif';
	ctx.textAlign = 'left';
	ctx.textBaseline = 'bottom';
	ctx.fillStyle = PANEL_COLORS.ink;
	ctx.fillText( 'Blending functions along the tongue', 8, area.top - 8 );

	ctx.strokeStyle = PANEL_COLORS.muted;
	ctx.lineWidth = 1;
	ctx.beginPath();
	ctx.moveTo( area.left, area.top );
	ctx.lineTo( area.left, area.bottom );
	ctx.lineTo( area.right, area.bottom );
	ctx.stroke();
	ctx.font = '10px system-ui, sans-serif';
	ctx.textAlign = 'right';
	ctx.textBaseline = 'middle';
	ctx.fillStyle = PANEL_COLORS.muted;
	ctx.fillText( '1', area.left - 4, y( 1 ) );
	ctx.fillText( '0', area.left - 4, y( 0 ) );

	const line = ( values ) => {

		ctx.beginPath();
		for ( let i = 0; i < u.length; i ++ ) {

			if ( i === 0 ) ctx.moveTo( x( u[ i ] ), y( values[ i ] ) );
			else ctx.lineTo( x( u[ i ] ), y( values[ i ] ) );

		}

		ctx.stroke();

	};

	ctx.lineWidth = 1;
	ctx.strokeStyle = PANEL_COLORS.rest;
	ctx.setLineDash( [ 4, 3 ] );
	line( coronal );
	ctx.setLineDash( [] );
	curves.forEach( ( values, s ) => {

		ctx.strokeStyle = SECTION_COLORS[ s ];
		ctx.lineWidth = 2;
		line( values );
		const station = scene.stations[ s ];
		ctx.lineWidth = 1;
		ctx.beginPath();
		ctx.moveTo( x( u[ station ] ), area.top );
		ctx.lineTo( x( u[ station ] ), area.bottom );
		ctx.stroke();

	} );

	ctx.font = 'bold 10px system-ui, sans-serif';
	ctx.textAlign = 'center';
	ctx.textBaseline = 'top';
	ctx.fillStyle = PANEL_COLORS.control;
	for ( const { letter, u: at } of letters ) ctx.fillText( letter, x( at ), area.bottom + 3 );
	return view;

}
