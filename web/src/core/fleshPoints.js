// Flesh points (twin of server/glasshead/geometry/flesh_points.py): where articulography glues
// its sensors, tracked on the posed rig. A sensor is a material point: it moves with the tissue.
//
// - tongue_tip, tongue_blade, tongue_dorsum, tongue_back: points of the tongue's upper
//   mid-sagittal outline (the page-angle-0 vertex of every station), fixed at rest by their arc
//   length from the apex (TONGUE_SENSOR_ARC_MM) as a segment between two stations and a weight
//   on it (tongueAnchors); in every pose the same interpolation of the posed outline, z = 0,
//   before the collision correction.
// - lower_incisor: the rest lower incisor edge moved by the jaw pose; upper_incisor: the rest
//   upper incisor edge, fixed.
// - upper_lip, lower_lip: the lip meshes' reference vertices (vermilion midpoints) as the face rig
//   posed them (faceRig.js poseFace).
// Placements: HPRC (Tiede et al.) puts the tongue tip sensor about 1 cm behind the apex, the
// others behind it at sensor spacing; MOCHA-TIMIT (Wrench) places tip, blade and dorsum alike.

import { midlinePage, stationVertexOffset } from './tongue.js';

/** Arc length from the apex along the upper mid-sagittal outline to each tongue sensor, mm. */
export const TONGUE_SENSOR_ARC_MM = Object.freeze( {
	tongue_tip: 10, tongue_blade: 25, tongue_dorsum: 40, tongue_back: 55,
} );
/** Every flesh point, in the order of fleshPoints()' output (xyz each). */
export const FLESH_POINT_NAMES = Object.freeze( [
	'tongue_tip', 'tongue_blade', 'tongue_dorsum', 'tongue_back',
	'lower_incisor', 'upper_lip', 'lower_lip', 'upper_incisor',
] );
/** Numbers in fleshPoints()' output: 8 points * 3. */
export const FLESH_POINTS_LENGTH = 8 * 3;
const TONGUE_POINTS = 4;

/**
 * Where the tongue sensors sit on the rest outline (allocates; once per rig).
 * @param {import('./tongue.js').TongueRig} rig
 * @param {Float32Array|Float64Array} positions the surface at the neutral parameters (xyz)
 * @param {ArrayLike<number>} [arcs] mm, default TONGUE_SENSOR_ARC_MM's values
 * @returns {{ page: number, first: Int32Array, second: Int32Array, weight: Float64Array }} the
 *   point k is ( 1 - weight[ k ] ) * outline[ first[ k ] ] + weight[ k ] * outline[ second[ k ] ]
 */
export function tongueAnchors( rig, positions, arcs = Object.values( TONGUE_SENSOR_ARC_MM ) ) {

	const page = midlinePage( rig );
	const n = rig.stationCount;
	const x = ( i ) => positions[ stationVertexOffset( rig, i, page ) ];
	const y = ( i ) => positions[ stationVertexOffset( rig, i, page ) + 1 ];
	let apex = 0;
	for ( let i = 1; i < n; i ++ ) if ( x( i ) > x( apex ) ) apex = i;
	const step = y( ( apex + 1 ) % n ) > y( ( apex - 1 + n ) % n ) ? 1 : n - 1;
	const count = arcs.length;
	const anchors = { page, first: new Int32Array( count ), second: new Int32Array( count ), weight: new Float64Array( count ) };
	for ( let k = 0; k < count; k ++ ) {

		let walked = 0, i = apex, found = false;
		for ( let s = 0; s < Math.floor( n / 2 ); s ++ ) {

			const j = ( i + step ) % n;
			const length = Math.hypot( x( j ) - x( i ), y( j ) - y( i ) );
			if ( arcs[ k ] >= 0 && arcs[ k ] < walked + length ) {

				anchors.first[ k ] = i; anchors.second[ k ] = j;
				anchors.weight[ k ] = ( arcs[ k ] - walked ) / length;
				found = true;
				break;

			}

			walked += length; i = j;

		}

		if ( ! found ) throw new RangeError( `sensor arc ${ arcs[ k ] } mm is outside [0, ${ walked.toFixed( 1 ) }) mm` );

	}

	return anchors;

}

/**
 * The flesh points of one frame, written into target (allocates nothing).
 * @param {import('./tongue.js').TongueRig} rig the tongue rig
 * @param {Float32Array|Float64Array} positions the posed tongue surface (xyz)
 * @param {ReturnType<typeof tongueAnchors>} anchors
 * @param {{ lower: ArrayLike<number>, upper: ArrayLike<number> }} incisors rest incisor edges, xyz
 * @param {ArrayLike<number>} pose the frame's jaw pose, row-major 3 x 4 (jaw.js jawPose())
 * @param {object} face the face rig (faceRig.js createFaceRig())
 * @param {Object<string, Float32Array|Float64Array>} facePosed poseFace()'s output for the frame
 * @param {Float32Array|Float64Array} target length FLESH_POINTS_LENGTH, FLESH_POINT_NAMES' order
 * @returns target
 */
export function fleshPoints( rig, positions, anchors, incisors, pose, face, facePosed, target ) {

	const { page, first, second, weight } = anchors;
	for ( let k = 0; k < TONGUE_POINTS; k ++ ) {

		const a = stationVertexOffset( rig, first[ k ], page ), b = stationVertexOffset( rig, second[ k ], page );
		const w = weight[ k ];
		target[ 3 * k ] = ( 1 - w ) * positions[ a ] + w * positions[ b ];
		target[ 3 * k + 1 ] = ( 1 - w ) * positions[ a + 1 ] + w * positions[ b + 1 ];
		target[ 3 * k + 2 ] = 0;

	}

	const lx = incisors.lower[ 0 ], ly = incisors.lower[ 1 ], lz = incisors.lower[ 2 ];
	target[ 12 ] = pose[ 0 ] * lx + pose[ 1 ] * ly + pose[ 2 ] * lz + pose[ 3 ];
	target[ 13 ] = pose[ 4 ] * lx + pose[ 5 ] * ly + pose[ 6 ] * lz + pose[ 7 ];
	target[ 14 ] = pose[ 8 ] * lx + pose[ 9 ] * ly + pose[ 10 ] * lz + pose[ 11 ];
	writeLip( face, facePosed, 'upper_lip', target, 15 );
	writeLip( face, facePosed, 'lower_lip', target, 18 );
	target[ 21 ] = incisors.upper[ 0 ]; target[ 22 ] = incisors.upper[ 1 ]; target[ 23 ] = incisors.upper[ 2 ];
	return target;

}

function writeLip( face, posed, name, target, offset ) {

	const o = 3 * face.meshes[ name ].reference;
	const points = posed[ name ];
	target[ offset ] = points[ o ]; target[ offset + 1 ] = points[ o + 1 ]; target[ offset + 2 ] = points[ o + 2 ];

}
