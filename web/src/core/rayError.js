// The paper's ray error of an observation against the tongue as posed now (Cohen, Beskow and
// Massaro 1998, part 5): for each observed point P, the ray from the origin O through P first
// crosses the tongue at Q (rayFirstHit.js); the error vector is P -> Q and its signed length
// (t - 1) |P - O|, positive when the tongue lies beyond P (it bulges past the observation),
// negative when it falls short. A ray that crosses nothing has Q = O (the error it would have if
// the tongue had shrunk onto the origin, as the 2D fit takes it). The observed points are the
// mid-sagittal outline (z = 0, the part the 2D fit compares) followed by the surface vertices;
// each part has its own RMS, largest |error| and count of misses.
//
// Built once per observation (createRayError); rayError() is called whenever the tongue changes
// and allocates nothing. Twin: server/glasshead/fitting/objective3d.py (RayError3D).

import { createRayFan, rayFirstHits } from './rayFirstHit.js';

/** Per part in `stats`: RMS (mm), largest |error| (mm), rays that cross nothing. */
export const STAT_RMS = 0;
export const STAT_MAX = 1;
export const STAT_MISSES = 2;
export const STATS_PER_PART = 3;
/** Offsets of the parts in `stats`. */
export const PART_OUTLINE = 0;
export const PART_SURFACE = STATS_PER_PART;

/**
 * @param {number[]} origin O, xyz (mm, project frame)
 * @param {number[][]} outline [[x, y], ...] mid-sagittal points (z = 0)
 * @param {number[][]} surface [[x, y, z], ...] surface vertices (may be empty)
 * @returns {{ origin: Float64Array, outlineCount: number, count: number, points: Float64Array,
 *   fan: object, t: Float64Array, q: Float64Array, signed: Float64Array, stats: Float64Array }}
 *   `points` P (xyz, outline first), and after rayError(): `t`, `q` (Q, xyz), `signed` (mm) per
 *   ray and `stats` (STATS_PER_PART per part, outline then surface; NaN for an empty part)
 */
export function createRayError( origin, outline, surface = [] ) {

	if ( ! Array.isArray( outline ) || ! Array.isArray( surface ) ) throw new TypeError( 'createRayError: the outline and the surface must be lists of points' );
	const outlineCount = outline.length;
	const count = outlineCount + surface.length;
	const points = new Float64Array( 3 * count );
	outline.forEach( ( p, k ) => {

		if ( ! Array.isArray( p ) || p.length < 2 ) throw new TypeError( `createRayError: outline point ${ k } is not [x, y]` );
		points[ 3 * k ] = p[ 0 ];
		points[ 3 * k + 1 ] = p[ 1 ];

	} );
	surface.forEach( ( p, k ) => {

		if ( ! Array.isArray( p ) || p.length < 3 ) throw new TypeError( `createRayError: surface point ${ k } is not [x, y, z]` );
		points.set( p.slice( 0, 3 ), 3 * ( outlineCount + k ) );

	} );
	const fan = createRayFan( origin, points, { count } );
	return {
		origin: fan.origin, outlineCount, count, points, fan,
		t: new Float64Array( count ), q: new Float64Array( 3 * count ), signed: new Float64Array( count ),
		stats: new Float64Array( 2 * STATS_PER_PART ).fill( NaN ),
	};

}

/**
 * The error of every ray against the mesh (positions xyz per vertex, triangles 3 indices each),
 * into the model's t, q, signed and stats. Returns the model. Allocates nothing.
 */
export function rayError( model, positions, triangles, triangleCount ) {

	const { fan, t, q, signed, stats } = model;
	rayFirstHits( fan, positions, triangles, triangleCount, t );
	const ox = fan.origin[ 0 ], oy = fan.origin[ 1 ], oz = fan.origin[ 2 ];
	const dirs = fan.directions, lengths = fan.lengths;
	for ( let k = 0; k < model.count; k ++ ) {

		const hit = t[ k ] < Infinity ? t[ k ] : 0;
		q[ 3 * k ] = hit === 0 ? ox : ox + hit * dirs[ 3 * k ];
		q[ 3 * k + 1 ] = hit === 0 ? oy : oy + hit * dirs[ 3 * k + 1 ];
		q[ 3 * k + 2 ] = hit === 0 ? oz : oz + hit * dirs[ 3 * k + 2 ];
		signed[ k ] = ( hit - 1 ) * lengths[ k ];

	}

	partStats( t, signed, 0, model.outlineCount, stats, PART_OUTLINE );
	partStats( t, signed, model.outlineCount, model.count, stats, PART_SURFACE );
	return model;

}

function partStats( t, signed, from, to, stats, offset ) {

	let sum = 0, max = 0, misses = 0;
	for ( let k = from; k < to; k ++ ) {

		const e = signed[ k ];
		sum += e * e;
		if ( Math.abs( e ) > max ) max = Math.abs( e );
		if ( t[ k ] === Infinity ) misses ++;

	}

	const n = to - from;
	stats[ offset + STAT_RMS ] = n > 0 ? Math.sqrt( sum / n ) : NaN;
	stats[ offset + STAT_MAX ] = n > 0 ? max : NaN;
	stats[ offset + STAT_MISSES ] = misses;

}
