// The velum (soft palate) posed by velum_opening, and the nasal port's smallest cross-section.
// Twin of server/glasshead/geometry/velum.py; tests/vectors/velum.json keeps the two in
// agreement. The definition (GET /velum/rig, built by glasshead.pipeline.velum_rig; format in
// docs/velum.md) holds every number used here.
//
// Piecewise-linear blend of three measured poses of one mesh (raised at 0, rest at r, lowered
// at 1), vertex by vertex, as a morph target; the nasal port is the smallest cut across the
// passage between the posed velum and the posterior pharyngeal wall, the wall being the raised
// velum's posterior surface (where it closes the port) sampled at fixed points of that surface
// (docs/velum.md).
//
// createVelumRig() allocates everything once; poseVelum() and nasalPortArea() allocate nothing.

import { VELUM_PARAMETER, VELUM_POSES, VELUM_RIG_FORMAT_VERSION } from './constants.js';

/**
 * Build the real-time rig from its definition: the poses as Float32Arrays and the port's
 * samples, with the wall points and a scratch array for the cuts.
 * @param {object} definition the velum rig (GET /velum/rig)
 * @returns {object} the rig, for poseVelum() and nasalPortArea(): vertexCount, restShare,
 *   parameter (name, unit, min, max, neutral, group, description), raised, rest, lowered
 */
export function createVelumRig( definition ) {

	if ( definition?.format_version !== VELUM_RIG_FORMAT_VERSION ) {

		throw new Error( `velum rig format_version ${ definition?.format_version } is not ${ VELUM_RIG_FORMAT_VERSION }` );

	}

	const parameter = definition.parameters?.[ 0 ];
	if ( definition.parameters.length !== 1 || parameter.name !== VELUM_PARAMETER ) throw new Error( `the velum rig must have the one parameter ${ VELUM_PARAMETER }` );
	const poses = definition.poses;
	if ( poses?.names?.join() !== VELUM_POSES.join() ) throw new Error( `velum poses must be ${ VELUM_POSES.join( ', ' ) }` );
	const vertexCount = poses.vertex_count;
	const arrays = VELUM_POSES.map( ( name ) => {

		const positions = poses.positions[ name ];
		if ( ! positions || positions.length !== 3 * vertexCount ) throw new Error( `velum pose ${ name } must have ${ vertexCount } vertices` );
		return Float32Array.from( positions );

	} );
	const restShare = poses.at[ 1 ];
	if ( ! ( restShare > 0 && restShare < 1 ) || parameter.neutral !== restShare ) throw new Error( 'velum poses.at[1] (the rest share r) must lie in (0, 1) and be the neutral value' );

	const port = definition.port;
	const count = port.rows.length;
	if ( ! count || port.vertices.length !== 3 * count || port.weights.length !== 3 * count || port.normals.length !== 3 * count ) {

		throw new Error( 'velum port vertices, weights, normals and rows must have one entry per sample' );

	}

	const vertices = Int32Array.from( port.vertices );
	for ( let i = 0; i < vertices.length; i ++ ) {

		if ( vertices[ i ] < 0 || vertices[ i ] >= vertexCount ) throw new Error( `velum port vertex ${ vertices[ i ] } does not exist` );

	}

	const rows = Int32Array.from( port.rows );
	for ( let i = 0; i < count; i ++ ) {

		if ( rows[ i ] < 0 || rows[ i ] >= port.row_count ) throw new Error( `velum port row ${ rows[ i ] } is outside [0, ${ port.row_count })` );

	}

	if ( ! ( port.width_mm > 0 ) ) throw new Error( 'velum port width_mm must be positive' );

	const rig = {
		vertexCount,
		restShare,
		parameter: { ...parameter },
		raised: arrays[ 0 ],
		rest: arrays[ 1 ],
		lowered: arrays[ 2 ],
		poses: arrays,
		/** Scratch: the share u of the way between the two poses of the last segment(). */
		share: new Float64Array( 1 ),
		portVertices: vertices,
		portWeights: Float64Array.from( port.weights ),
		portNormals: Float64Array.from( port.normals ),
		portRows: rows,
		rowCount: port.row_count,
		widthMm: port.width_mm,
		portWall: new Float64Array( 3 * count ),
		cuts: new Float64Array( port.row_count ),
	};
	// The wall: each sample's point in the raised pose, computed as nasalPortArea() computes the
	// posed points, so that at opening 0 they agree bit for bit and every gap is exactly 0.
	for ( let k = 0; k < count; k ++ ) {

		for ( let c = 0; c < 3; c ++ ) rig.portWall[ 3 * k + c ] = samplePoint( rig, k, c, rig.raised, rig.raised, 0 );

	}

	return rig;

}

function checkOpening( opening ) {

	if ( typeof opening !== 'number' || ! Number.isFinite( opening ) ) throw new RangeError( `${ VELUM_PARAMETER } = ${ opening } is not a finite number` );
	if ( opening < 0 || opening > 1 ) throw new RangeError( `${ VELUM_PARAMETER } = ${ opening } is outside its range [0, 1] ratio` );

}

/**
 * The first of the two poses `opening` lies between (0: raised and rest, 1: rest and lowered);
 * its share u of the way from that pose goes into rig.share[ 0 ]. The twin of velum.py's
 * _segment. RangeError for an opening that is not a number in [0, 1].
 */
export function velumSegment( rig, opening ) {

	checkOpening( opening );
	const r = rig.restShare;
	if ( opening <= r ) {

		rig.share[ 0 ] = opening / r;
		return 0;

	}

	rig.share[ 0 ] = ( opening - r ) / ( 1 - r );
	return 1;

}

// Coordinate c of sample k with its three vertices at a (1 - u) + b u, in float64.
function samplePoint( rig, k, c, a, b, u ) {

	const v = rig.portVertices;
	const w = rig.portWeights;
	const i0 = 3 * v[ 3 * k ] + c;
	const i1 = 3 * v[ 3 * k + 1 ] + c;
	const i2 = 3 * v[ 3 * k + 2 ] + c;
	const p0 = a[ i0 ] * ( 1 - u ) + b[ i0 ] * u;
	const p1 = a[ i1 ] * ( 1 - u ) + b[ i1 ] * u;
	const p2 = a[ i2 ] * ( 1 - u ) + b[ i2 ] * u;
	return w[ 3 * k ] * p0 + w[ 3 * k + 1 ] * p1 + w[ 3 * k + 2 ] * p2;

}

// A morph-target (blend-shape) blend, piecewise linear through the three measured poses:
// p(o) = a (1 - u) + b u, with (a, b, u) = (raised, rest, o / r) for o <= r and
// (rest, lowered, (o - r) / (1 - r)) above; exact at o = 0, r and 1.
/**
 * Pose the velum: positions at `opening` into `out`.
 * @param {object} rig from createVelumRig()
 * @param {number} opening velum_opening in [0, 1] (RangeError otherwise)
 * @param {Float32Array} out 3 × vertexCount positions, mm (written)
 * @returns {Float32Array} out
 */
export function poseVelum( rig, opening, out ) {

	const first = velumSegment( rig, opening );
	const a = rig.poses[ first ], b = rig.poses[ first + 1 ], u = rig.share[ 0 ];
	const n = 3 * rig.vertexCount;
	for ( let i = 0; i < n; i ++ ) out[ i ] = a[ i ] * ( 1 - u ) + b[ i ] * u;
	return out;

}

/**
 * The nasal port's smallest cross-section at `opening`, mm²: over the cuts across the passage,
 * the smallest sum of gaps (how far the posed velum lies in front of the wall along its normal,
 * 0 where it touches) times the width a sample stands for. Exactly 0 at opening 0.
 * @param {object} rig from createVelumRig()
 * @param {number} opening velum_opening in [0, 1] (RangeError otherwise)
 * @returns {number} mm²
 */
export function nasalPortArea( rig, opening ) {

	const first = velumSegment( rig, opening );
	const a = rig.poses[ first ], b = rig.poses[ first + 1 ], u = rig.share[ 0 ];
	const cuts = rig.cuts;
	cuts.fill( 0 );
	const wall = rig.portWall;
	const normals = rig.portNormals;
	const count = rig.portRows.length;
	for ( let k = 0; k < count; k ++ ) {

		const gap = ( wall[ 3 * k ] - samplePoint( rig, k, 0, a, b, u ) ) * normals[ 3 * k ]
			+ ( wall[ 3 * k + 1 ] - samplePoint( rig, k, 1, a, b, u ) ) * normals[ 3 * k + 1 ]
			+ ( wall[ 3 * k + 2 ] - samplePoint( rig, k, 2, a, b, u ) ) * normals[ 3 * k + 2 ];
		if ( gap > 0 ) cuts[ rig.portRows[ k ] ] += gap * rig.widthMm;

	}

	let smallest = Infinity;
	for ( let j = 0; j < rig.rowCount; j ++ ) if ( cuts[ j ] < smallest ) smallest = cuts[ j ];
	return smallest;

}
