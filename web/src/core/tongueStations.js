// The tongue rig's sagittal curve at its stations (part of core/tongue.js): the tables that
// depend on no parameter (the sagittal basis at the stations, each station's blend of the three
// coronal sections, its rest radius from the hub and its rest ratios per coronal control), and
// step 3's first part, the stations S = sagittal basis * points. Cohen, Beskow and Massaro
// (1998), section 3: blending functions say where along the tongue each coronal section applies.

import { basisTable } from './bspline.js';

/** Sections blended along the tongue, in the order of each point's section_weights. */
export const SECTION_COUNT = 3;

/**
 * The station tables of a rig definition (the parsed rig JSON), with `hubRest` the hub's rest
 * position (x, y): the rest radius of a station is its distance from it.
 * @returns {object} the tables, named as the TongueRig's fields that hold them
 */
export function stationTables( definition, hubRest ) {

	const { sagittal, coronal, surface } = definition;
	const points = sagittal.control_points;
	const n = points.length;
	const degree = sagittal.degree;
	const restPoints = Float64Array.from( points.flatMap( ( p ) => p.position ) );
	const stationCount = surface.station_params.length;
	const sagittalWidth = degree + 1;
	const stations = basisTable( sagittal.knots, degree, surface.station_params );
	const stationFirst = stations.first;
	const stationBasis = stations.values;

	// Blends and rest ratios per station (constant: they depend on no parameter).
	const sections = coronal.sections;
	const c = coronal.controls.length;
	const stationBlend = new Float64Array( stationCount * SECTION_COUNT );
	const stationOffsetBlend = new Float64Array( stationCount * SECTION_COUNT );
	const stationRatios = new Float64Array( stationCount * c );
	const restRadius = new Float64Array( stationCount );
	const isPole = new Uint8Array( c );
	for ( const k of coronal.pole_controls ) isPole[ k ] = 1;
	for ( let i = 0; i < stationCount; i ++ ) {

		let sx = 0;
		let sy = 0;
		let coronalWeight = 0;
		for ( let k = 0; k < sagittalWidth; k ++ ) {

			const weight = stationBasis[ i * sagittalWidth + k ];
			const point = ( stationFirst[ i ] + k ) % n;
			sx += weight * restPoints[ 2 * point ];
			sy += weight * restPoints[ 2 * point + 1 ];
			coronalWeight += weight * points[ point ].coronal_weight;
			for ( let s = 0; s < SECTION_COUNT; s ++ ) {

				stationBlend[ i * SECTION_COUNT + s ] += weight * points[ point ].section_weights[ s ];

			}

		}

		for ( let s = 0; s < SECTION_COUNT; s ++ ) {

			stationOffsetBlend[ i * SECTION_COUNT + s ] = coronalWeight * stationBlend[ i * SECTION_COUNT + s ];

		}

		restRadius[ i ] = Math.hypot( sx - hubRest[ 0 ], sy - hubRest[ 1 ] );
		for ( let k = 0; k < c; k ++ ) {

			let ratio = 0;
			if ( ! isPole[ k ] ) {

				for ( let s = 0; s < SECTION_COUNT; s ++ ) ratio += stationBlend[ i * SECTION_COUNT + s ] * coronal.ratios[ sections[ s ] ][ k ];

			}

			stationRatios[ i * c + k ] = ratio;

		}

	}

	return {
		pointCount: n,
		restPoints,
		pointJawWeights: Float64Array.from( points, ( p ) => p.jaw_weight ),
		stationCount,
		sagittalWidth,
		stationFirst,
		stationBasis,
		controlCount: c,
		stationBlend,
		stationOffsetBlend,
		stationRatios,
		restRadius,
		poleHalfWidth: coronal.pole_half_width,
		isPole,
		follow: Float64Array.from( coronal.follow ),
	};

}

/** Step 3, first part: the rig's stations S = sagittal basis * points, into rig.stationXY. */
export function writeStations( rig ) {

	const n = rig.pointCount;
	const points = rig.points;
	const { stationBasis, stationFirst, sagittalWidth, stationXY } = rig;
	for ( let i = 0; i < rig.stationCount; i ++ ) {

		let sx = 0;
		let sy = 0;
		for ( let k = 0; k < sagittalWidth; k ++ ) {

			const weight = stationBasis[ i * sagittalWidth + k ];
			const point = ( stationFirst[ i ] + k ) % n;
			sx += weight * points[ 2 * point ];
			sy += weight * points[ 2 * point + 1 ];

		}

		stationXY[ 2 * i ] = sx;
		stationXY[ 2 * i + 1 ] = sy;

	}

}
