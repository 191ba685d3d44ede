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
//      the hub by the sum of ( value - neutral ) * its turn, degrees (tongueMoves.js);
//   2. the jaw pose moves the sagittal control points and the hub, each by its jaw weight; then
//      the hub follows its parameters (their summed move, posed with the jaw) as far as every
//      turn between neighbouring stations keeps hub.keep of its cross product about the unmoved
//      hub (tongueHub.js);
//   3. stations S = sagittal basis * points (tongueStations.js); page direction
//      e = ( S - H ) / |S - H|;
//   4. radial controls: w + ( R0 - w ) * ratio + ( R - R0 ) * follow + offsets * coronal weight
//      , at least TONGUE_CONTROL_FLOOR_MM (poles: w);
//   5. vertex = H + lambda ( cos( phi ) e + sin( phi ) ( 1 + k ( 1 - sin( phi )^4 ) ) z ), lambda = page
//      basis * controls, k the blended sideways stretch (the sections' widths) (tongueSurface.js).
// Cohen, Beskow and Massaro (1998), section 3: sagittal and coronal B-splines whose control
// points move singly and in pairs under articulation parameters.

import { jawPose, applyJawPose, POSE_LENGTH } from './jaw.js';
import { TONGUE_RIG_FORMAT_VERSION } from './constants.js';
import { vertexNormals } from './meshVolume.js';
import { followWithHub, hubShare, hubTables, poseHub } from './tongueHub.js';
import { moveAlongRays, moveStraight, moveTables, sumCoronalMoves, turnAboutHub } from './tongueMoves.js';
import { SECTION_COUNT, stationTables, writeStations } from './tongueStations.js';
import { pageTables, surfaceTriangles, writeVertices } from './tongueSurface.js';

export class TongueRig {

	/** @param {object} definition the parsed rig JSON */
	constructor( definition ) {

		if ( definition?.format_version !== TONGUE_RIG_FORMAT_VERSION ) {

			throw new Error( `tongue rig format_version ${definition?.format_version} is not ${TONGUE_RIG_FORMAT_VERSION}` );

		}

		this.definition = definition;
		const { coronal, surface, parameters, hub, jaw } = definition;

		// Parameters.
		this.parameters = parameters;
		this.parameterCount = parameters.length;
		this.parameterIndex = new Map( parameters.map( ( p, k ) => [ p.name, k ] ) );
		this.neutral = Float64Array.from( parameters, ( p ) => p.neutral );
		this.minimum = Float64Array.from( parameters, ( p ) => p.min );
		this.maximum = Float64Array.from( parameters, ( p ) => p.max );

		// The hub, the sagittal curve at the stations, the coronal curve at the page angles, the moves.
		Object.assign( this, hubTables( hub, this.parameterIndex ) );
		Object.assign( this, stationTables( definition, this.hubRest ) );
		Object.assign( this, pageTables( coronal, surface.page_angles_deg ) );
		Object.assign( this, moveTables( definition ) );

		this.jaw = jaw;
		this.jawParameter = this.parameterIndex.get( jaw.parameter );
		if ( this.jawParameter === undefined ) throw new Error( `jaw parameter ${jaw.parameter} is not in the parameter table` );

		// Topology: fixed, so built once.
		this.vertexCount = 2 + this.stationCount * this.pageCount;
		this.triangleCount = 2 * this.stationCount * this.pageCount;
		this.index = surfaceTriangles( this.stationCount, this.pageCount );

		// Scratch for evaluate(): nothing is allocated per call.
		const c = this.controlCount;
		this.points = new Float64Array( 2 * this.pointCount );
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

		moveStraight( this, values );
		this.moveAlongRays( values );
		this.turnAboutHub( values );
		sumCoronalMoves( this, values );
		jawPose( values[ this.jawParameter ], this.jaw, this.pose );
		applyJawPose( this.pose, this.points, this.pointCount, 2, this.pointJawWeights, this.points );
		poseHub( this );
		this.writeStations();
		this.followWithHub( values );

	}

	/** Step 2, second part (tongueHub.js). */
	followWithHub( values ) {

		followWithHub( this, values );

	}

	/** The share of the move ( mx, my ) that the hub may take (tongueHub.js). */
	hubShare( mx, my ) {

		return hubShare( this, mx, my );

	}

	/** Step 1, second part: each control point along its own ray (tongueMoves.js). */
	moveAlongRays( values ) {

		moveAlongRays( this, values );

	}

	/** Step 1, third part: each control point turned about the rest hub (tongueMoves.js). */
	turnAboutHub( values ) {

		turnAboutHub( this, values );

	}

	/** Step 3, first part: the stations (tongueStations.js). */
	writeStations() {

		writeStations( this );

	}

	/** Steps 3 to 5: page directions, radial controls and the float64 vertices (tongueSurface.js). */
	writeVertices() {

		writeVertices( this );

	}

}

/** The page sample at angle 0: the mid-sagittal outline point of each station. */
export function midlinePage( rig ) {

	let best = 0;
	for ( let j = 1; j < rig.pageCount; j ++ ) if ( rig.pageCos[ j ] > rig.pageCos[ best ] ) best = j;
	return best;

}

/** Where the vertex of station `station` at page `page` starts in the surface's positions (xyz; two poles first). */
export function stationVertexOffset( rig, station, page ) {

	return 3 * ( 2 + station * rig.pageCount + page );

}
