// The head's tract as a tube, every frame: the area function of the diagram's mid-sagittal
// section (core/areaFunction.js) and the formants of that tube (core/tubeAcoustics.js), as
// POST /tract/acoustics computes them on the server (docs/acoustics.md).
//
// The still parts and the stations come from tract-section.json; the moving ones (the tongue,
// the lower lip and the mandible below the air, the velum and the upper lip above it) are the
// DiagramSection's, recut each frame. Their segments are copied into buffers sized once, so a
// frame allocates nothing but the tube's subarray views.

import { areaFunction, chainPart, createAreaFunction, nasalBranch } from '../core/areaFunction.js';
import { VELUM_PARAMETER } from '../core/constants.js';
import { nasalPortArea } from '../core/velum.js';
import { chainSegmentCount } from '../core/midSection.js';
import { tubeFormants, FORMANT_COUNT } from '../core/tubeAcoustics.js';
import { registerDebug } from '../debug.js';

/** The diagram's parts that bound the air from below and from above, and move. */
export const MOVING_FLOOR = Object.freeze( [ 'tongue', 'lowerLip', 'mandible' ] );
export const MOVING_ROOF = Object.freeze( [ 'velum', 'upperLip' ] );
/** Where the built section is served. */
export const TRACT_SECTION_URL = '/assets/build/tract-section.json';

/** A part view of a section part: its chains' segments, a solid when every chain closes. */
function createView( section ) {

	return { section, segments: new Float64Array( 2 * section.points.length + 4 ), count: 0, solid: false };

}

function refreshView( view ) {

	const { points, starts, closed, chainCount } = view.section;
	const s = view.segments;
	let count = 0;
	let solid = chainCount > 0;
	for ( let c = 0; c < chainCount; c ++ ) {

		const first = starts[ c ], n = starts[ c + 1 ] - first;
		if ( closed[ c ] !== 1 ) solid = false;
		const segments = chainSegmentCount( view.section, c );
		for ( let k = 0; k < segments; k ++ ) {

			const a = 2 * ( first + k ), b = 2 * ( first + ( k + 1 ) % n );
			s[ 4 * count ] = points[ a ];
			s[ 4 * count + 1 ] = points[ a + 1 ];
			s[ 4 * count + 2 ] = points[ b ];
			s[ 4 * count + 3 ] = points[ b + 1 ];
			count ++;

		}

	}

	view.count = count;
	view.solid = solid;
	return view;

}

/** The largest x of a section part's points (-Infinity without points). */
function frontOf( section ) {

	let x = - Infinity;
	for ( let k = 0; k < section.pointCount; k ++ ) if ( section.points[ 2 * k ] > x ) x = section.points[ 2 * k ];
	return x;

}

export class TractAcoustics {

	/**
	 * @param {object} diagram a DiagramSection (recut by its owner before each update)
	 * @param {object} section tract-section.json
	 * @param {object} state the articulation's ParamState (for lip_rounding and velum_opening)
	 * @param {{ velumRig?: object|null }} options the velum rig (core/velum.js) whose port opens
	 *   the nose; without it the tube has no nasal branch
	 */
	constructor( diagram, section, state, { velumRig = null } = {} ) {

		this.diagram = diagram;
		this.state = state;
		this.stations = Float64Array.from( section.stations.flat() );
		this.incisorX = section.incisor_x;
		this.uvulaY = section.uvula_y;
		const still = ( list ) => list.map( ( p ) => chainPart( p.points.flat(), p.closed ) );
		const moving = ( keys ) => keys.flatMap( ( key ) => diagram.parts( key ).map( createView ) );
		this.movingFloor = moving( MOVING_FLOOR );
		this.movingRoof = moving( MOVING_ROOF );
		this.floor = [ ...this.movingFloor, ...still( section.still.floor ) ];
		this.roof = [ ...this.movingRoof, ...still( section.still.roof ) ];
		this.lips = [ ...diagram.parts( 'upperLip' ), ...diagram.parts( 'lowerLip' ) ];
		this.roundingIndex = state.indexOf( 'lip_rounding' );
		this.nose = section.nose;
		this.velumRig = velumRig;
		this.velumIndex = state.indexOf( VELUM_PARAMETER );
		this.portMm2 = 0;
		this.nasal = null;
		this.tube = createAreaFunction( this.stations.length / 2 );
		this.formants = { frequencies: new Float64Array( FORMANT_COUNT ), bandwidths: new Float64Array( FORMANT_COUNT ) };
		this.where = { incisorX: this.incisorX, uvulaY: this.uvulaY, lipFrontX: this.incisorX, lipRounding: 0 };
		this.updates = 0;
		this.lastMs = 0;

	}

	/** The area function and formants of the diagram's current section. */
	update() {

		const start = performance.now();
		this.updateAreaFunction();
		this.updateFormants();
		this.updates ++;
		this.lastMs = performance.now() - start;
		return this;

	}

	/** The area function of the diagram's current section (into this.tube). */
	updateAreaFunction() {

		for ( const view of this.movingFloor ) refreshView( view );
		for ( const view of this.movingRoof ) refreshView( view );
		let front = 0, lips = 0;
		for ( const lip of this.lips ) {

			const x = frontOf( lip );
			if ( Number.isFinite( x ) ) {

				front += x;
				lips ++;

			}

		}

		this.where.lipFrontX = lips ? front / lips : this.incisorX;
		this.where.lipRounding = this.roundingIndex >= 0 ? this.state.values[ this.roundingIndex ] : 0;
		return areaFunction( this.stations, this.floor, this.roof, this.where, this.tube );

	}

	/** The formants of this.tube with its nasal branch while the port is open (into this.formants). */
	updateFormants() {

		const n = this.tube.count;
		const opening = this.velumIndex >= 0 ? this.state.values[ this.velumIndex ] : 0;
		this.portMm2 = this.velumRig && opening > 0 ? nasalPortArea( this.velumRig, Math.min( opening, 1 ) ) : 0;
		this.nasal = this.nose ? nasalBranch( this.tube, this.nose, this.portMm2 ) : null;
		return tubeFormants( this.tube.lengths.subarray( 0, n ), this.tube.areas.subarray( 0, n ), { nasal: this.nasal }, this.formants );

	}

	/** What window.glasshead.tractAcoustics reports: formants (Hz), whether shut, the tube's length. */
	summary() {

		const round = ( v ) => ( Number.isNaN( v ) ? null : Math.round( v ) );
		let length = 0;
		for ( let k = 0; k < this.tube.count; k ++ ) length += this.tube.lengths[ k ];
		return {
			formants: Array.from( this.formants.frequencies, round ),
			bandwidths: Array.from( this.formants.bandwidths, round ),
			closed: this.tube.closed, sections: this.tube.count, lengthMm: Math.round( length * 10 ) / 10,
			nasalPortMm2: Math.round( this.portMm2 * 10 ) / 10, nasalAt: this.nasal?.at ?? null,
		};

	}

	/** Add window.glasshead.tractAcoustics; returns the function that removes it. */
	registerDebugField() {

		return registerDebug( 'tractAcoustics', () => this.summary() );

	}

}
