// The tongue rig's surface (part of core/tongue.js): the coronal B-spline at the page angles,
// steps 3 to 5 (page directions, radial controls, vertices) and the fixed triangles.
//   4. radial controls: w + ( R0 - w ) * ratio + ( R - R0 ) * follow + offsets * coronal weight
//      , at least TONGUE_CONTROL_FLOOR_MM (poles: w);
//   5. vertex = H + lambda ( cos( phi ) e + sin( phi ) ( 1 + k ( 1 - sin( phi )^4 ) ) z ), lambda = page
//      basis * controls, k the blended sideways stretch (the sections' widths).
// Cohen, Beskow and Massaro (1998), section 3: a polygon surface from sagittal and coronal
// B-spline curves.

import { basisTable } from './bspline.js';
import { TONGUE_CONTROL_FLOOR_MM } from './constants.js';
import { SECTION_COUNT } from './tongueStations.js';

/**
 * The page tables of the coronal curve (its definition in the rig JSON) at `angles` (degrees, as
 * in the knots): the basis, and the cosine, sine and sideways fade of each page angle.
 * @returns {object} the tables, named as the TongueRig's fields that hold them
 */
export function pageTables( coronal, angles ) {

	const pages = basisTable( coronal.knots, coronal.degree, angles );
	const pageSin = Float64Array.from( angles, ( a ) => Math.sin( a * Math.PI / 180 ) );
	return {
		pageCount: angles.length,
		coronalWidth: coronal.degree + 1,
		pageFirst: pages.first,
		pageBasis: pages.values,
		pageCos: Float64Array.from( angles, ( a ) => Math.cos( a * Math.PI / 180 ) ),
		pageSin,
		pageFade: Float64Array.from( pageSin, ( x ) => 1 - x * x * x * x ),
	};

}

/**
 * Steps 3 to 5: the rig's page directions, radial controls and float64 vertices (rig.direction,
 * rig.radius, rig.controls, rig.stationStretch, rig.vertices) from its stations, hub, offsets
 * and stretch. The rig's arrays are read into locals first: the compiled loops then load no
 * property per step.
 */
export function writeVertices( rig ) {

	const c = rig.controlCount;
	const hx = rig.hub[ 0 ];
	const hy = rig.hub[ 1 ];
	const pole = rig.poleHalfWidth;
	const { stationXY, radius, direction, restRadius, stationBlend, stationStretch, stretch, stationOffsetBlend, controls, isPole, stationRatios, follow, offsets } = rig;
	for ( let i = 0; i < rig.stationCount; i ++ ) {

		const dx = stationXY[ 2 * i ] - hx;
		const dy = stationXY[ 2 * i + 1 ] - hy;
		const r = Math.sqrt( dx * dx + dy * dy );
		radius[ i ] = r;
		direction[ 2 * i ] = dx / r;
		direction[ 2 * i + 1 ] = dy / r;
		const rest = restRadius[ i ];
		const b0 = stationBlend[ i * SECTION_COUNT ];
		const b1 = stationBlend[ i * SECTION_COUNT + 1 ];
		const b2 = stationBlend[ i * SECTION_COUNT + 2 ];
		stationStretch[ i ] = b0 * stretch[ 0 ] + b1 * stretch[ 1 ] + b2 * stretch[ 2 ];
		const o0 = stationOffsetBlend[ i * SECTION_COUNT ];
		const o1 = stationOffsetBlend[ i * SECTION_COUNT + 1 ];
		const o2 = stationOffsetBlend[ i * SECTION_COUNT + 2 ];
		for ( let k = 0; k < c; k ++ ) {

			// No control nearer the hub than the floor: a deep groove where the curve has come
			// close to the hub would otherwise take the radius through it.
			controls[ i * c + k ] = isPole[ k ] ? pole
				: Math.max( TONGUE_CONTROL_FLOOR_MM, pole + ( rest - pole ) * stationRatios[ i * c + k ] + ( r - rest ) * follow[ k ]
					+ o0 * offsets[ k ] + o1 * offsets[ c + k ] + o2 * offsets[ 2 * c + k ] );

		}

	}

	const vertices = rig.vertices;
	vertices[ 0 ] = hx; vertices[ 1 ] = hy; vertices[ 2 ] = - pole;
	vertices[ 3 ] = hx; vertices[ 4 ] = hy; vertices[ 5 ] = pole;
	const width = rig.coronalWidth;
	const pageCount = rig.pageCount;
	const { pageFirst, pageBasis, pageCos, pageSin, pageFade } = rig;
	for ( let i = 0; i < rig.stationCount; i ++ ) {

		const ex = direction[ 2 * i ];
		const ey = direction[ 2 * i + 1 ];
		const along = stationStretch[ i ];
		const row = i * c;
		for ( let j = 0; j < pageCount; j ++ ) {

			let lambda = 0;
			const first = row + pageFirst[ j ];
			for ( let k = 0; k < width; k ++ ) lambda += pageBasis[ j * width + k ] * controls[ first + k ];
			const planar = lambda * pageCos[ j ];
			const o = 3 * ( 2 + i * pageCount + j );
			vertices[ o ] = hx + planar * ex;
			vertices[ o + 1 ] = hy + planar * ey;
			vertices[ o + 2 ] = lambda * pageSin[ j ] * ( 1 + along * pageFade[ j ] );

		}

	}

}

/**
 * Triangles of the surface layout (Uint32Array, 3 per triangle): vertex 0 is the right pole, 1
 * the left pole, ring vertex ( station i, page sample j ) is 2 + i * pageCount + j; winding
 * ( i, j ) -> ( i + 1, j ) -> ( i, j + 1 ) is counter-clockwise seen from outside.
 */
export function surfaceTriangles( stationCount, pageCount ) {

	const index = new Uint32Array( 3 * 2 * stationCount * pageCount );
	let t = 0;
	for ( let i = 0; i < stationCount; i ++ ) {

		const here = 2 + i * pageCount;
		const there = 2 + ( ( i + 1 ) % stationCount ) * pageCount;
		index[ t ++ ] = 0; index[ t ++ ] = there; index[ t ++ ] = here;

	}

	for ( let i = 0; i < stationCount; i ++ ) {

		const here = 2 + i * pageCount;
		const there = 2 + ( ( i + 1 ) % stationCount ) * pageCount;
		for ( let j = 0; j < pageCount - 1; j ++ ) {

			index[ t ++ ] = here + j; index[ t ++ ] = there + j; index[ t ++ ] = there + j + 1;
			index[ t ++ ] = here + j; index[ t ++ ] = there + j + 1; index[ t ++ ] = here + j + 1;

		}

	}

	const last = pageCount - 1;
	for ( let i = 0; i < stationCount; i ++ ) {

		const here = 2 + i * pageCount;
		const there = 2 + ( ( i + 1 ) % stationCount ) * pageCount;
		index[ t ++ ] = here + last; index[ t ++ ] = there + last; index[ t ++ ] = 1;

	}

	return index;

}
