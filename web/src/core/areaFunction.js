// The tract's area function: the cross-sections of the air from the glottis to the lips, read
// off the mid-sagittal section of the posed head. The twin of
// server/glasshead/acoustics/area_function.py (its docstring gives the method and its sources),
// held to the same numbers by tests/vectors/area-function.json.
//
// A part is { segments, count, solid }: count segments x0 y0 x1 y1 in `segments` (mm), and
// whether they close round tissue, so that a station can lie inside it. At each station the
// air's width is the distance to the floor plus the distance to the roof (inside a solid: the
// distance to the other side less the depth; never below 0); each section between stations
// takes the mean width of its ends and an area by its region's law. A call allocates nothing
// once its output exists.

import {
	TRACT_AREA_LAWS, TRACT_CLOSURE_MM, TRACT_LARYNX_TUBE, TRACT_MIN_AREA_MM2, TRACT_STATION_STEP_MM,
} from './constants.js';

/** The regions of the sections, by the law that gives their areas (-1: the larynx tube). */
export const REGIONS = Object.freeze( [ 'pharynx', 'oral', 'lips' ] );

/** A polyline (x y pairs) as a part; a solid when it closes on its first point. Allocates. */
export function chainPart( points, closed ) {

	const n = points.length / 2;
	const count = closed ? n : n - 1;
	const segments = new Float64Array( 4 * Math.max( count, 0 ) );
	for ( let k = 0; k < count; k ++ ) {

		const j = ( k + 1 ) % n;
		segments.set( [ points[ 2 * k ], points[ 2 * k + 1 ], points[ 2 * j ], points[ 2 * j + 1 ] ], 4 * k );

	}

	return { segments, count, solid: closed };

}

// Nearest distance from (x, y) to the parts' segments and the nearest point; written into NEAR.
const NEAR = { distance: Infinity, x: 0, y: 0 };
function nearest( parts, x, y ) {

	let best = Infinity, bx = x, by = y;
	for ( const part of parts ) {

		const s = part.segments;
		for ( let k = 0; k < part.count; k ++ ) {

			const x0 = s[ 4 * k ], y0 = s[ 4 * k + 1 ];
			const dx = s[ 4 * k + 2 ] - x0, dy = s[ 4 * k + 3 ] - y0;
			const t = Math.min( 1, Math.max( 0, ( ( x - x0 ) * dx + ( y - y0 ) * dy ) / Math.max( dx * dx + dy * dy, 1e-12 ) ) );
			const ex = x - x0 - t * dx, ey = y - y0 - t * dy;
			const d2 = ex * ex + ey * ey;
			if ( d2 < best ) {

				best = d2;
				bx = x0 + t * dx;
				by = y0 + t * dy;

			}

		}

	}

	NEAR.distance = Math.sqrt( best );
	NEAR.x = bx;
	NEAR.y = by;
	return NEAR;

}

/** Whether (x, y) lies inside one of the parts' solids (ray crossings toward +x, per solid). */
function insideSolids( parts, x, y ) {

	for ( const part of parts ) {

		if ( ! part.solid ) continue;
		const s = part.segments;
		let crossings = 0;
		for ( let k = 0; k < part.count; k ++ ) {

			const x0 = s[ 4 * k ], y0 = s[ 4 * k + 1 ], x1 = s[ 4 * k + 2 ], y1 = s[ 4 * k + 3 ];
			const dy = y1 - y0;
			if ( ( y0 > y ) !== ( y1 > y ) && x < x0 + ( y - y0 ) * ( x1 - x0 ) / ( dy === 0 ? 1 : dy ) ) crossings ++;

		}

		if ( crossings % 2 === 1 ) return true;

	}

	return false;

}

/** The air's mid-sagittal width (mm) at (x, y) between the floor's and the roof's parts. */
export function tractWidth( floor, roof, x, y ) {

	const { distance: toFloor, x: fx, y: fy } = nearest( floor, x, y );
	const { distance: toRoof, x: rx, y: ry } = nearest( roof, x, y );
	const inFloor = insideSolids( floor, x, y ), inRoof = insideSolids( roof, x, y );
	let width;
	// Inside a solid, the other side's nearest point inside it too: the two overlap there.
	if ( ( inFloor && inRoof ) || ( inFloor && insideSolids( floor, rx, ry ) ) || ( inRoof && insideSolids( roof, fx, fy ) ) ) width = 0;
	else if ( inFloor ) width = toRoof - toFloor;
	else if ( inRoof ) width = toFloor - toRoof;
	else width = toFloor + toRoof;
	return Number.isFinite( width ) ? Math.max( 0, width ) : 0;

}

/** The mouth's width (mm) for a value of the lip_rounding parameter. */
export function lipWidthMm( lipRounding ) {

	const law = TRACT_AREA_LAWS.lips;
	return Math.max( law.min_mm, law.width_mm - law.narrowing_mm * lipRounding );

}

/**
 * A section's area (mm²) from its mean width (mm) and its region (an index of REGIONS); a
 * section narrower than TRACT_CLOSURE_MM is shut and passes TRACT_MIN_AREA_MM2.
 */
export function widthToArea( widthMm, region, lipWidth ) {

	const d = Math.max( 0, widthMm );
	if ( d < TRACT_CLOSURE_MM ) return TRACT_MIN_AREA_MM2;
	let area;
	if ( region === 2 ) area = Math.PI / 4 * d * lipWidth;
	else {

		const law = TRACT_AREA_LAWS[ REGIONS[ region ] ];
		area = 100 * law.alpha * Math.pow( d / 10, law.beta );

	}

	return Math.max( area, TRACT_MIN_AREA_MM2 );

}

/**
 * An area function's output, sized for `stations` midline stations and up to `lipStations` in
 * front of them.
 */
export function createAreaFunction( stations, lipStations = 32 ) {

	const sections = stations + lipStations;
	return {
		lengths: new Float64Array( sections ), areas: new Float64Array( sections ),
		positions: new Float64Array( sections ), widths: new Float64Array( sections ),
		regions: new Int8Array( sections ), count: 0, closed: false,
		stationWidths: new Float64Array( stations + lipStations ),
		/** x y of every station walked, the lips' ones after the midline's. */
		stationPoints: new Float64Array( 2 * ( stations + lipStations ) ),
	};

}

/**
 * The tube of a posed tract, glottis first (the larynx tube, then a section between each pair
 * of stations), written into out (createAreaFunction).
 * @param {Float64Array} stations x y per midline station, from the airway's lower end to the incisors
 * @param {Array<object>} floor parts below the air; roof: parts above it
 * @param {{ incisorX: number, uvulaY: number, lipFrontX: number, lipRounding: number }} where
 *   the lips' and the pharynx's sections begin, the lips' front (mm) and lip_rounding
 * @returns {object} out: count sections; lengths, areas (mm, mm²), positions (the middle of
 *   each from the glottis, mm), widths (mm, NaN for the larynx tube), regions; closed
 */
export function areaFunction( stations, floor, roof, { incisorX, uvulaY, lipFrontX, lipRounding }, out ) {

	const n = stations.length / 2;
	if ( n < 2 ) throw new RangeError( 'an area function needs at least two stations' );
	const lastX = stations[ 2 * n - 2 ], lastY = stations[ 2 * n - 1 ];
	const reach = lipFrontX - lastX;
	const extra = reach > 0 ? Math.ceil( reach / TRACT_STATION_STEP_MM ) : 0;
	const total = n + extra;
	if ( total > out.stationWidths.length || 2 * n > out.stationPoints.length ) throw new RangeError( `the lips reach ${ extra } stations ahead; the output holds ${ out.stationWidths.length - n }` );
	const walk = out.stationPoints;
	walk.set( stations );
	for ( let i = n; i < total; i ++ ) {

		walk[ 2 * i ] = lastX + reach * ( i - n + 1 ) / extra;
		walk[ 2 * i + 1 ] = lastY;

	}

	for ( let i = 0; i < total; i ++ ) out.stationWidths[ i ] = tractWidth( floor, roof, walk[ 2 * i ], walk[ 2 * i + 1 ] );

	const lipWidth = lipWidthMm( lipRounding );
	out.lengths[ 0 ] = TRACT_LARYNX_TUBE.length_mm;
	out.areas[ 0 ] = TRACT_LARYNX_TUBE.area_mm2;
	out.widths[ 0 ] = NaN;
	out.regions[ 0 ] = - 1;
	out.positions[ 0 ] = out.lengths[ 0 ] / 2;
	let end = out.lengths[ 0 ];
	let closed = false;
	for ( let i = 0; i + 1 < total; i ++ ) {

		const x0 = walk[ 2 * i ], y0 = walk[ 2 * i + 1 ], x1 = walk[ 2 * i + 2 ], y1 = walk[ 2 * i + 3 ];
		const length = Math.hypot( x1 - x0, y1 - y0 );
		const width = ( out.stationWidths[ i ] + out.stationWidths[ i + 1 ] ) / 2;
		const mx = ( x0 + x1 ) / 2, my = ( y0 + y1 ) / 2;
		const region = mx > incisorX ? 2 : ( my < uvulaY ? 0 : 1 );
		const k = i + 1;
		out.lengths[ k ] = length;
		out.widths[ k ] = width;
		out.regions[ k ] = region;
		out.areas[ k ] = widthToArea( width, region, lipWidth );
		out.positions[ k ] = end + length / 2;
		end += length;
		if ( width < TRACT_CLOSURE_MM ) closed = true;

	}

	out.count = total;
	out.closed = closed;
	return out;

}

/**
 * The nose as a side branch of an area function (createAreaFunction's output): { at: the
 * sections before the junction (the larynx's and the pharynx's), lengths, areas: the port
 * (nose.port_length_mm long, of portMm2) then the nose's sections }, or null while the port is
 * shut (under TRACT_MIN_AREA_MM2) or the tube has no mouth. Twin of area_function.nasal_branch.
 * @param {{ port_length_mm: number, length_mm: number[], area_mm2: number[] }} nose tract-section.json's
 */
export function nasalBranch( tube, nose, portMm2 ) {

	let at = - 1;
	for ( let k = 0; k < tube.count; k ++ ) {

		if ( tube.regions[ k ] >= REGIONS.indexOf( 'oral' ) ) {

			at = k;
			break;

		}

	}

	if ( ! ( portMm2 >= TRACT_MIN_AREA_MM2 ) || at <= 0 ) return null;
	return { at, lengths: [ nose.port_length_mm, ...nose.length_mm ], areas: [ portMm2, ...nose.area_mm2 ] };

}
