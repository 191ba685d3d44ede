// The logic of the workbench's Observation group, without DOM (tested in Node with a fake API):
// the observations listed and fetched (GET /observations, /observations/{name}), the Before and
// After poses set through the state the sliders and the pasted JSON go through
// (ParamState.assign), and the ray error of the chosen shape recomputed in the articulation's
// hook, whenever the tongue changed and never in a still frame. ObservationOverlay.js is its view.

import { api as pageApi } from '../../api.js';
import { PART_OUTLINE, PART_SURFACE, STAT_MAX, STAT_MISSES, STAT_RMS, createRayError, rayError } from '../../core/rayError.js';

/**
 * Set every parameter of `state` to `params` (names it does not have are left out, the others
 * go back to neutral), as a paste does; returns the names left out. Throws a RangeError naming
 * a value outside its range, and then changes nothing.
 */
export function assignParams( state, params ) {

	const known = {};
	const unknown = [];
	for ( const [ name, value ] of Object.entries( params ?? {} ) ) {

		if ( state.index.has( name ) ) known[ name ] = value;
		else unknown.push( name );

	}

	state.assign( known );
	return unknown;

}

/** An error for display: "1.23 mm". */
export function formatMm( value ) {

	return Number.isFinite( value ) ? `${ value.toFixed( 2 ) } mm` : '–';

}

export class ObservationControl {

	/**
	 * @param {{ api?: object, articulation: object, onUpdate?: Function }} options the HTTP
	 *   client, the workbench's Articulation (its state, tongue and hook) and what to call after
	 *   every change of the errors or of the choice
	 */
	constructor( { api = pageApi, articulation, onUpdate = () => {} } ) {

		this.api = api;
		this.articulation = articulation;
		this.state = articulation.state;
		this.onUpdate = onUpdate;
		this.entries = [];
		this.current = null;
		this.model = null;
		this.which = null;
		this.appliedVersion = - 1;
		this.updates = 0;
		this.overlay = true;
		this.request = 0;
		this.unhook = articulation.onCorrected( () => this.recompute() );

	}

	/** GET /observations: [{ name, label, source, has_surface, rms_mm }]. */
	async list() {

		const body = await this.api.get( 'observations' );
		this.entries = body?.observations ?? [];
		return this.entries;

	}

	/** Fetch observation `name` and show its fitted pose ('' or null: none). Resolves to it (null when a later choice won). */
	async choose( name ) {

		const request = ++ this.request;
		if ( ! name ) {

			this.current = this.model = this.which = null;
			this.onUpdate();
			return null;

		}

		const observation = await this.api.get( `observations/${ encodeURIComponent( name ) }` );
		if ( request !== this.request ) return null;
		this.model = createRayError( observation.origin, observation.outline ?? [], observation.surface ?? [] );
		this.current = observation;
		this.show( 'after' );
		return observation;

	}

	/** Set every parameter to the observation's 'before' (the fit's start) or 'after' (its result). */
	show( which ) {

		const params = this.current?.[ which ]?.params;
		if ( ! params ) throw new Error( `The observation has no "${ which }" parameters.` );
		assignParams( this.state, params );
		this.which = which;
		this.appliedVersion = this.state.version;
		// Pose the tongue now (its hook recomputes the errors); the frame then finds nothing to do.
		if ( ! this.articulation.update() ) this.recompute();

	}

	/** 'before' or 'after' while the parameters are as the switch set them, 'edited' once anything moved; null with no observation. */
	get stateName() {

		if ( ! this.current ) return null;
		return this.which && this.state.version === this.appliedVersion ? this.which : 'edited';

	}

	setOverlay( on ) {

		this.overlay = Boolean( on );
		this.onUpdate();

	}

	/** The errors against the tongue as posed now. */
	recompute() {

		if ( ! this.model ) return;
		const a = this.articulation;
		rayError( this.model, a.positions, a.triangles, a.triangles.length / 3 );
		this.updates ++;
		this.onUpdate();

	}

	/** What window.glasshead.observation reports. */
	report() {

		const base = { listed: this.entries.length, overlay: this.overlay, updates: this.updates };
		if ( ! this.current || ! this.model ) return { ...base, name: null, state: null };
		const { stats, outlineCount, count } = this.model;
		const part = ( offset, rays ) => ( { rays, rmsMm: stats[ offset + STAT_RMS ], maxMm: stats[ offset + STAT_MAX ], misses: stats[ offset + STAT_MISSES ] } );
		return {
			...base, name: this.current.name, label: this.current.label ?? this.current.name, state: this.stateName,
			...part( PART_OUTLINE, outlineCount ),
			surface: count > outlineCount ? part( PART_SURFACE, count - outlineCount ) : null,
			fitRmsMm: this.current.after?.rms_mm ?? null,
		};

	}

	dispose() {

		this.unhook();

	}

}
