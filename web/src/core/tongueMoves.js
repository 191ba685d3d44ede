// The tongue rig's parameter moves (part of core/tongue.js), read once from the rig definition
// into flat arrays, and step 1 with them: control points = rest + sum over parameters of
// ( value - neutral ) * move; then each point moves along its own ray from the rest hub by the
// sum of ( value - neutral ) * its radial move, mm, keeping at least TONGUE_CONTROL_FLOOR_MM
// from the hub; then each point turns about the rest hub by the sum of ( value - neutral ) * its
// turn, degrees. The coronal offsets and the sections' sideways stretch are summed the same way.
// Cohen, Beskow and Massaro (1998), section 3: control points move singly and in pairs under
// articulation parameters.

import { TONGUE_CONTROL_FLOOR_MM } from './constants.js';

/**
 * Moves of single control points by parameter, (parameter, point, amount) as flat arrays, and
 * the per-point sums that sumPointMoves fills in place (nothing is allocated per frame).
 */
function pointMoves( moves, pointCount ) {

	return {
		parameter: Int32Array.from( moves, ( m ) => m[ 0 ] ),
		point: Int32Array.from( moves, ( m ) => m[ 1 ] ),
		amount: Float64Array.from( moves, ( m ) => m[ 2 ] ),
		sum: new Float64Array( pointCount ),
	};

}

/** Each point's summed move for parameter values, or null when no parameter moves points so. */
function sumPointMoves( moves, values, neutral ) {

	if ( moves.parameter.length === 0 ) return null;
	const sum = moves.sum;
	sum.fill( 0 );
	for ( let m = 0; m < moves.parameter.length; m ++ ) {

		const k = moves.parameter[ m ];
		sum[ moves.point[ m ] ] += ( values[ k ] - neutral[ k ] ) * moves.amount[ m ];

	}

	return sum;

}

/**
 * The moves of a rig definition as flat lists: sagittal (parameter, point, dx, dy); coronal
 * (parameter, section * c + control, by); stretch (parameter, section, by); and the turns
 * (radians) and radial moves (mm) of single points.
 * @returns {object} the tables, named as the TongueRig's fields that hold them
 */
export function moveTables( { parameters, sagittal, coronal } ) {

	const points = sagittal.control_points;
	const sections = coronal.sections;
	const controls = coronal.controls;
	const c = controls.length;
	const pointIndex = new Map( points.map( ( p, k ) => [ p.name, k ] ) );
	const controlIndex = new Map( controls.map( ( name, k ) => [ name, k ] ) );
	const sagittalMoves = [];
	const coronalMoves = [];
	const stretchMoves = [];
	const turnMoves = [];
	const radialMoves = [];
	parameters.forEach( ( p, k ) => {

		for ( const move of p.moves ) {

			if ( move.turn !== undefined ) turnMoves.push( [ k, pointIndex.get( move.point ), move.turn * Math.PI / 180 ] );
			else if ( move.radial !== undefined ) radialMoves.push( [ k, pointIndex.get( move.point ), move.radial ] );
			else if ( move.point !== undefined ) sagittalMoves.push( [ k, pointIndex.get( move.point ), move.by[ 0 ], move.by[ 1 ] ] );
			else if ( move.stretch !== undefined ) stretchMoves.push( [ k, sections.indexOf( move.section ), move.stretch ] );
			else coronalMoves.push( [ k, sections.indexOf( move.section ) * c + controlIndex.get( move.control ), move.by ] );

		}

	} );
	return {
		sagittalMoveParameter: Int32Array.from( sagittalMoves, ( m ) => m[ 0 ] ),
		sagittalMovePoint: Int32Array.from( sagittalMoves, ( m ) => m[ 1 ] ),
		sagittalMoveX: Float64Array.from( sagittalMoves, ( m ) => m[ 2 ] ),
		sagittalMoveY: Float64Array.from( sagittalMoves, ( m ) => m[ 3 ] ),
		coronalMoveParameter: Int32Array.from( coronalMoves, ( m ) => m[ 0 ] ),
		coronalMoveTarget: Int32Array.from( coronalMoves, ( m ) => m[ 1 ] ),
		coronalMoveBy: Float64Array.from( coronalMoves, ( m ) => m[ 2 ] ),
		stretchMoveParameter: Int32Array.from( stretchMoves, ( m ) => m[ 0 ] ),
		stretchMoveSection: Int32Array.from( stretchMoves, ( m ) => m[ 1 ] ),
		stretchMoveBy: Float64Array.from( stretchMoves, ( m ) => m[ 2 ] ),
		pointTurns: pointMoves( turnMoves, points.length ),
		pointRadials: pointMoves( radialMoves, points.length ),
	};

}

/** Step 1, first part: rig.points = rest + the straight moves of the parameter values. */
export function moveStraight( rig, values ) {

	const points = rig.points;
	points.set( rig.restPoints );
	for ( let m = 0; m < rig.sagittalMoveParameter.length; m ++ ) {

		const k = rig.sagittalMoveParameter[ m ];
		const delta = values[ k ] - rig.neutral[ k ];
		const o = 2 * rig.sagittalMovePoint[ m ];
		points[ o ] += delta * rig.sagittalMoveX[ m ];
		points[ o + 1 ] += delta * rig.sagittalMoveY[ m ];

	}

}

/**
 * Step 1, second part: moves each control point along its own ray from the rest hub by its
 * summed radial move, at least TONGUE_CONTROL_FLOOR_MM from the hub (its direction stays).
 */
export function moveAlongRays( rig, values ) {

	const radial = sumPointMoves( rig.pointRadials, values, rig.neutral );
	if ( radial === null ) return;
	const points = rig.points;
	const hx = rig.hubRest[ 0 ];
	const hy = rig.hubRest[ 1 ];
	for ( let i = 0; i < rig.pointCount; i ++ ) {

		if ( radial[ i ] === 0 ) continue;
		const x = points[ 2 * i ] - hx;
		const y = points[ 2 * i + 1 ] - hy;
		const distance = Math.hypot( x, y );
		const scale = Math.max( distance + radial[ i ], TONGUE_CONTROL_FLOOR_MM ) / distance;
		points[ 2 * i ] = hx + x * scale;
		points[ 2 * i + 1 ] = hy + y * scale;

	}

}

/** Step 1, third part: turns each control point about the rest hub by its summed turn. */
export function turnAboutHub( rig, values ) {

	const turn = sumPointMoves( rig.pointTurns, values, rig.neutral );
	if ( turn === null ) return;
	const points = rig.points;
	const hx = rig.hubRest[ 0 ];
	const hy = rig.hubRest[ 1 ];
	for ( let i = 0; i < rig.pointCount; i ++ ) {

		if ( turn[ i ] === 0 ) continue;
		const cos = Math.cos( turn[ i ] );
		const sin = Math.sin( turn[ i ] );
		const x = points[ 2 * i ] - hx;
		const y = points[ 2 * i + 1 ] - hy;
		points[ 2 * i ] = hx + cos * x - sin * y;
		points[ 2 * i + 1 ] = hy + sin * x + cos * y;

	}

}

/** The coronal offsets (rig.offsets, section * c + control) and the sections' stretch (rig.stretch). */
export function sumCoronalMoves( rig, values ) {

	const offsets = rig.offsets;
	offsets.fill( 0 );
	for ( let m = 0; m < rig.coronalMoveParameter.length; m ++ ) {

		const k = rig.coronalMoveParameter[ m ];
		offsets[ rig.coronalMoveTarget[ m ] ] += ( values[ k ] - rig.neutral[ k ] ) * rig.coronalMoveBy[ m ];

	}

	const stretch = rig.stretch;
	stretch.fill( 0 );
	for ( let m = 0; m < rig.stretchMoveParameter.length; m ++ ) {

		const k = rig.stretchMoveParameter[ m ];
		stretch[ rig.stretchMoveSection[ m ] ] += ( values[ k ] - rig.neutral[ k ] ) * rig.stretchMoveBy[ m ];

	}

}
