// The real-time tongue evaluator (twin of server/glasshead/geometry/tongue_surface.py): a generic
// interpreter of the rig definition that Python writes (assets/build/tongue-rig.json; its format
// is described in server/glasshead/geometry/tongue_rig.py).
//
// new TongueRig( definition ) builds every table that does not depend on the parameters (basis
// functions at the stations and page angles, the blended rest ratios, the triangles, scratch
// arrays). rig.evaluate( values, surface ) then writes positions and normals into the surface's
// preallocated Float32Arrays and allocates nothing:
//   1. control points = rest + sum over parameters of ( value - neutral ) * move; then each point
//      moves along its own ray from the hub by the sum of ( value - neutral ) * its radial move,
//      mm, keeping at least TONGUE_CONTROL_FLOOR_MM from the hub; then each point turns about
//      the hub by the sum of ( value - neutral ) * its turn, degrees;
//   2. the jaw pose moves the sagittal control points and the hub, each by its jaw weight; then
//      the hub follows its parameters (their summed move, posed with the jaw) as far as every
//      turn between neighbouring stations keeps hub.keep of its cross product about the unmoved
//      hub (hubShare);
//   3. stations S = sagittal basis * points; page direction e = ( S - H ) / |S - H|;
//   4. radial controls: w + ( R0 - w ) * ratio + ( R - R0 ) * follow + offsets * coronal weight
//      , at least TONGUE_CONTROL_FLOOR_MM (poles: w);
//   5. vertex = H + lambda ( cos( phi ) e + sin( phi ) ( 1 + k ( 1 - sin( phi )^4 ) ) z ), lambda = page
//      basis * controls, k the blended sideways stretch (the sections' widths).
// Cohen, Beskow and Massaro (1998), section 3: sagittal and coronal B-splines whose control
// points move singly and in pairs under articulation parameters.

import { basisTable } from './bspline.js';
import { jawPose, applyJawPose, POSE_LENGTH } from './jaw.js';
import { TONGUE_CONTROL_FLOOR_MM, TONGUE_RIG_FORMAT_VERSION } from './constants.js';
import { vertexNormals } from './meshVolume.js';

/** Sections blended along the tongue, in the order of each point's section_weights. */
export const SECTION_COUNT = 3;

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

export class TongueRig {

	/** @param {object} definition the parsed rig JSON */
	constructor( definition ) {

		if ( definition?.format_version !== TONGUE_RIG_FORMAT_VERSION ) {

			throw new Error( `tongue rig format_version ${definition?.format_version} is not ${TONGUE_RIG_FORMAT_VERSION}` );

		}

		this.definition = definition;
		const { sagittal, coronal, surface, parameters, hub, jaw } = definition;

		// Parameters.
		this.parameters = parameters;
		this.parameterCount = parameters.length;
		this.parameterIndex = new Map( parameters.map( ( p, k ) => [ p.name, k ] ) );
		this.neutral = Float64Array.from( parameters, ( p ) => p.neutral );
		this.minimum = Float64Array.from( parameters, ( p ) => p.min );
		this.maximum = Float64Array.from( parameters, ( p ) => p.max );

		// Sagittal curve at the stations.
		const points = sagittal.control_points;
		const n = points.length;
		const degree = sagittal.degree;
		this.pointCount = n;
		this.restPoints = Float64Array.from( points.flatMap( ( p ) => p.position ) );
		this.pointJawWeights = Float64Array.from( points, ( p ) => p.jaw_weight );
		this.stationCount = surface.station_params.length;
		this.sagittalWidth = degree + 1;
		const stations = basisTable( sagittal.knots, degree, surface.station_params );
		this.stationFirst = stations.first;
		this.stationBasis = stations.values;

		// Blends and rest ratios per station (constant: they depend on no parameter).
		const sections = coronal.sections;
		const controls = coronal.controls;
		const c = controls.length;
		this.controlCount = c;
		this.stationBlend = new Float64Array( this.stationCount * SECTION_COUNT );
		this.stationOffsetBlend = new Float64Array( this.stationCount * SECTION_COUNT );
		this.stationRatios = new Float64Array( this.stationCount * c );
		this.restRadius = new Float64Array( this.stationCount );
		this.poleHalfWidth = coronal.pole_half_width;
		this.isPole = new Uint8Array( c );
		for ( const k of coronal.pole_controls ) this.isPole[ k ] = 1;
		this.follow = Float64Array.from( coronal.follow );
		this.hubRest = Float64Array.from( hub.position );
		this.hubJawWeight = hub.jaw_weight;
		this.hubFollowParameter = Int32Array.from( hub.follows, ( f ) => {

			const k = this.parameterIndex.get( f.parameter );
			if ( k === undefined ) throw new Error( `the hub follows ${f.parameter}, which is not in the parameter table` );
			return k;

		} );
		this.hubFollowBy = Float64Array.from( hub.follows.flatMap( ( f ) => f.by ) );
		this.hubKeep = hub.keep;
		for ( let i = 0; i < this.stationCount; i ++ ) {

			let sx = 0;
			let sy = 0;
			let coronalWeight = 0;
			for ( let k = 0; k < this.sagittalWidth; k ++ ) {

				const weight = this.stationBasis[ i * this.sagittalWidth + k ];
				const point = ( this.stationFirst[ i ] + k ) % n;
				sx += weight * this.restPoints[ 2 * point ];
				sy += weight * this.restPoints[ 2 * point + 1 ];
				coronalWeight += weight * points[ point ].coronal_weight;
				for ( let s = 0; s < SECTION_COUNT; s ++ ) {

					this.stationBlend[ i * SECTION_COUNT + s ] += weight * points[ point ].section_weights[ s ];

				}

			}

			for ( let s = 0; s < SECTION_COUNT; s ++ ) {

				this.stationOffsetBlend[ i * SECTION_COUNT + s ] = coronalWeight * this.stationBlend[ i * SECTION_COUNT + s ];

			}

			this.restRadius[ i ] = Math.hypot( sx - this.hubRest[ 0 ], sy - this.hubRest[ 1 ] );
			for ( let k = 0; k < c; k ++ ) {

				let ratio = 0;
				if ( ! this.isPole[ k ] ) {

					for ( let s = 0; s < SECTION_COUNT; s ++ ) ratio += this.stationBlend[ i * SECTION_COUNT + s ] * coronal.ratios[ sections[ s ] ][ k ];

				}

				this.stationRatios[ i * c + k ] = ratio;

			}

		}

		// Coronal B-spline at the page angles (degrees, as in the knots).
		const angles = surface.page_angles_deg;
		this.pageCount = angles.length;
		this.coronalWidth = coronal.degree + 1;
		const pages = basisTable( coronal.knots, coronal.degree, angles );
		this.pageFirst = pages.first;
		this.pageBasis = pages.values;
		this.pageCos = Float64Array.from( angles, ( a ) => Math.cos( a * Math.PI / 180 ) );
		this.pageSin = Float64Array.from( angles, ( a ) => Math.sin( a * Math.PI / 180 ) );
		this.pageFade = Float64Array.from( this.pageSin, ( x ) => 1 - x * x * x * x );

		// Moves, as flat lists: sagittal (parameter, point, dx, dy); coronal (parameter, section * c + control, by).
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
		this.sagittalMoveParameter = Int32Array.from( sagittalMoves, ( m ) => m[ 0 ] );
		this.sagittalMovePoint = Int32Array.from( sagittalMoves, ( m ) => m[ 1 ] );
		this.sagittalMoveX = Float64Array.from( sagittalMoves, ( m ) => m[ 2 ] );
		this.sagittalMoveY = Float64Array.from( sagittalMoves, ( m ) => m[ 3 ] );
		this.coronalMoveParameter = Int32Array.from( coronalMoves, ( m ) => m[ 0 ] );
		this.coronalMoveTarget = Int32Array.from( coronalMoves, ( m ) => m[ 1 ] );
		this.coronalMoveBy = Float64Array.from( coronalMoves, ( m ) => m[ 2 ] );
		this.stretchMoveParameter = Int32Array.from( stretchMoves, ( m ) => m[ 0 ] );
		this.stretchMoveSection = Int32Array.from( stretchMoves, ( m ) => m[ 1 ] );
		this.stretchMoveBy = Float64Array.from( stretchMoves, ( m ) => m[ 2 ] );
		this.pointTurns = pointMoves( turnMoves, points.length );
		this.pointRadials = pointMoves( radialMoves, points.length );

		this.jaw = jaw;
		this.jawParameter = this.parameterIndex.get( jaw.parameter );
		if ( this.jawParameter === undefined ) throw new Error( `jaw parameter ${jaw.parameter} is not in the parameter table` );

		// Topology: fixed, so built once.
		this.vertexCount = 2 + this.stationCount * this.pageCount;
		this.triangleCount = 2 * this.stationCount * this.pageCount;
		this.index = surfaceTriangles( this.stationCount, this.pageCount );

		// Scratch for evaluate(): nothing is allocated per call.
		this.points = new Float64Array( 2 * n );
		this.hub = new Float64Array( 2 );
		this.stationXY = new Float64Array( 2 * this.stationCount );
		this.offsets = new Float64Array( SECTION_COUNT * c );
		this.stretch = new Float64Array( SECTION_COUNT );
		this.stationStretch = new Float64Array( this.stationCount );
		this.pose = new Float64Array( POSE_LENGTH );
		this.direction = new Float64Array( 2 * this.stationCount );
		this.radius = new Float64Array( this.stationCount );
		this.controls = new Float64Array( this.stationCount * c );
		this.vertices = new Float64Array( 3 * this.vertexCount );
		this.normalSums = new Float64Array( 3 * this.vertexCount );

	}

	/** Preallocated output: positions and normals (Float32Array, xyz per vertex) and the shared index. */
	createSurface() {

		return {
			positions: new Float32Array( 3 * this.vertexCount ),
			normals: new Float32Array( 3 * this.vertexCount ),
			index: this.index,
			vertexCount: this.vertexCount,
			triangleCount: this.triangleCount,
		};

	}

	/**
	 * Parameter values from a { name: value } object; missing names are neutral. Throws a
	 * RangeError naming the parameter for an unknown name or a value that is not finite or is
	 * outside its range (the API's 422 messages, word for word).
	 * @param {Object<string, number>} params
	 * @param {Float64Array} [target] length parameterCount
	 * @returns {Float64Array}
	 */
	valuesFrom( params, target = new Float64Array( this.parameterCount ) ) {

		target.set( this.neutral );
		for ( const [ name, value ] of Object.entries( params ?? {} ) ) {

			const k = this.parameterIndex.get( name );
			if ( k === undefined ) throw new RangeError( `unknown parameter '${name}'; known: ${[ ...this.parameterIndex.keys() ].join( ', ' )}` );
			const p = this.parameters[ k ];
			if ( typeof value !== 'number' || ! Number.isFinite( value ) ) throw new RangeError( `${name} = ${value} is not a finite number` );
			if ( value < p.min || value > p.max ) throw new RangeError( `${name} = ${value} is outside its range [${p.min}, ${p.max}] ${p.unit}` );
			target[ k ] = value;

		}

		return target;

	}

	/**
	 * Write the surface for parameter values into surface.positions and surface.normals.
	 * @param {Float64Array} values length parameterCount (see valuesFrom())
	 * @param {ReturnType<TongueRig['createSurface']>} surface from createSurface()
	 * @param {boolean} [normals] false leaves surface.normals as they were: for a caller that
	 *   recomputes them after moving the vertices (collision) anyway
	 * @returns the surface
	 */
	evaluate( values, surface, normals = true ) {

		this.posedControls( values );
		this.writeVertices();
		const vertices = this.vertices;
		const positions = surface.positions;
		for ( let k = 0; k < vertices.length; k ++ ) positions[ k ] = vertices[ k ];
		if ( normals ) vertexNormals( vertices, this.index, this.normalSums, surface.normals );
		return surface;

	}

	/** Steps 1 and 2: control points, coronal offsets and the hub, posed with the jaw. */
	posedControls( values ) {

		const points = this.points;
		points.set( this.restPoints );
		for ( let m = 0; m < this.sagittalMoveParameter.length; m ++ ) {

			const k = this.sagittalMoveParameter[ m ];
			const delta = values[ k ] - this.neutral[ k ];
			const o = 2 * this.sagittalMovePoint[ m ];
			points[ o ] += delta * this.sagittalMoveX[ m ];
			points[ o + 1 ] += delta * this.sagittalMoveY[ m ];

		}

		this.moveAlongRays( values );
		this.turnAboutHub( values );

		const offsets = this.offsets;
		offsets.fill( 0 );
		for ( let m = 0; m < this.coronalMoveParameter.length; m ++ ) {

			const k = this.coronalMoveParameter[ m ];
			offsets[ this.coronalMoveTarget[ m ] ] += ( values[ k ] - this.neutral[ k ] ) * this.coronalMoveBy[ m ];

		}

		const stretch = this.stretch;
		stretch.fill( 0 );
		for ( let m = 0; m < this.stretchMoveParameter.length; m ++ ) {

			const k = this.stretchMoveParameter[ m ];
			stretch[ this.stretchMoveSection[ m ] ] += ( values[ k ] - this.neutral[ k ] ) * this.stretchMoveBy[ m ];

		}

		jawPose( values[ this.jawParameter ], this.jaw, this.pose );
		applyJawPose( this.pose, points, this.pointCount, 2, this.pointJawWeights, points );
		this.hub.set( this.hubRest );
		const w = this.hubJawWeight;
		const pose = this.pose;
		const hx = this.hub[ 0 ];
		const hy = this.hub[ 1 ];
		this.hub[ 0 ] = hx + w * ( pose[ 0 ] * hx + pose[ 1 ] * hy + pose[ 3 ] - hx );
		this.hub[ 1 ] = hy + w * ( pose[ 4 ] * hx + pose[ 5 ] * hy + pose[ 7 ] - hy );
		this.writeStations();
		this.followWithHub( values );

	}

	/** Step 2, second part: the hub takes what hubShare allows of its parameters' move. */
	followWithHub( values ) {

		let fx = 0;
		let fy = 0;
		for ( let m = 0; m < this.hubFollowParameter.length; m ++ ) {

			const k = this.hubFollowParameter[ m ];
			fx += ( values[ k ] - this.neutral[ k ] ) * this.hubFollowBy[ 2 * m ];
			fy += ( values[ k ] - this.neutral[ k ] ) * this.hubFollowBy[ 2 * m + 1 ];

		}

		if ( fx === 0 && fy === 0 ) return;
		// The move posed with the jaw: the hub's pose is affine, so only its linear part acts.
		const w = this.hubJawWeight;
		const pose = this.pose;
		const mx = fx + w * ( pose[ 0 ] * fx + pose[ 1 ] * fy - fx );
		const my = fy + w * ( pose[ 4 ] * fx + pose[ 5 ] * fy - fy );
		const share = this.hubShare( mx, my );
		this.hub[ 0 ] += share * mx;
		this.hub[ 1 ] += share * my;

	}

	/**
	 * The share of the move ( mx, my ) that the hub may take: at most 1, and so much that the
	 * cross product of every two neighbouring stations seen from the hub keeps hubKeep of its
	 * value about the present hub. With a = S_i - H and b = S_i+1 - H, the cross product from
	 * H + t * move is a x b - t ( a - b ) x move: linear in t, so its bound is exact.
	 */
	hubShare( mx, my ) {

		const hx = this.hub[ 0 ];
		const hy = this.hub[ 1 ];
		const stationXY = this.stationXY;
		const count = this.stationCount;
		let bound = Infinity;
		for ( let i = 0; i < count; i ++ ) {

			const j = ( i + 1 ) % count;
			const ax = stationXY[ 2 * i ] - hx;
			const ay = stationXY[ 2 * i + 1 ] - hy;
			const bx = stationXY[ 2 * j ] - hx;
			const by = stationXY[ 2 * j + 1 ] - hy;
			const cross = ax * by - ay * bx;
			const loss = ( ax - bx ) * my - ( ay - by ) * mx;
			if ( loss > 0 && cross > 0 ) bound = Math.min( bound, cross / loss );

		}

		return Math.min( 1, ( 1 - this.hubKeep ) * bound );

	}

	/**
	 * Step 1, second part: moves each control point along its own ray from the rest hub by its
	 * summed radial move, at least TONGUE_CONTROL_FLOOR_MM from the hub (its direction stays).
	 */
	moveAlongRays( values ) {

		const radial = sumPointMoves( this.pointRadials, values, this.neutral );
		if ( radial === null ) return;
		const points = this.points;
		const hx = this.hubRest[ 0 ];
		const hy = this.hubRest[ 1 ];
		for ( let i = 0; i < this.pointCount; i ++ ) {

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
	turnAboutHub( values ) {

		const turn = sumPointMoves( this.pointTurns, values, this.neutral );
		if ( turn === null ) return;
		const points = this.points;
		const hx = this.hubRest[ 0 ];
		const hy = this.hubRest[ 1 ];
		for ( let i = 0; i < this.pointCount; i ++ ) {

			if ( turn[ i ] === 0 ) continue;
			const cos = Math.cos( turn[ i ] );
			const sin = Math.sin( turn[ i ] );
			const x = points[ 2 * i ] - hx;
			const y = points[ 2 * i + 1 ] - hy;
			points[ 2 * i ] = hx + cos * x - sin * y;
			points[ 2 * i + 1 ] = hy + sin * x + cos * y;

		}

	}

	/** Step 3, first part: the stations S = sagittal basis * points, posed with the jaw. */
	writeStations() {

		const n = this.pointCount;
		const points = this.points;
		const { stationBasis, stationFirst, sagittalWidth, stationXY } = this;
		for ( let i = 0; i < this.stationCount; i ++ ) {

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

	/**
	 * Steps 3 to 5: page directions, radial controls and the float64 vertices. The rig's arrays
	 * are read into locals first: the compiled loops then load no property per step.
	 */
	writeVertices() {

		const c = this.controlCount;
		const hx = this.hub[ 0 ];
		const hy = this.hub[ 1 ];
		const pole = this.poleHalfWidth;
		const { stationXY, radius, direction, restRadius, stationBlend, stationStretch, stretch, stationOffsetBlend, controls, isPole, stationRatios, follow, offsets } = this;
		for ( let i = 0; i < this.stationCount; i ++ ) {

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

		const vertices = this.vertices;
		vertices[ 0 ] = hx; vertices[ 1 ] = hy; vertices[ 2 ] = - pole;
		vertices[ 3 ] = hx; vertices[ 4 ] = hy; vertices[ 5 ] = pole;
		const width = this.coronalWidth;
		const pageCount = this.pageCount;
		const { pageFirst, pageBasis, pageCos, pageSin, pageFade } = this;
		for ( let i = 0; i < this.stationCount; i ++ ) {

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
