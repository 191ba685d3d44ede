// The head view's chooser of what to show: the rest posture, a saved pose (GET /poses) or a
// phoneme target (GET /phonemes). Choosing one poses the tongue, jaw, lips and velum with its
// parameters, so the live palatogram beside the head shows that target's contact.
//
// The lists come from the clinician's target sources (targets.js), so a new kind of target shows
// here as well once it is added there. Parameters of a rig the head has not loaded are left out.

import { registerDebug } from '../debug.js';
import { h } from './Controls.js';
import { PhonemeTargets, SavedPoseTargets } from './targets.js';

/** The chooser's value for the rest posture. */
export const REST = '';

/** The parameters of `params` that `state` knows ({ name: value }); the rest are dropped. */
export function knownParams( params, names ) {

	const known = new Set( names );
	return Object.fromEntries( Object.entries( params ?? {} ).filter( ( [ name, value ] ) => known.has( name ) && Number.isFinite( value ) ) );

}

export class HeadTargets {

	/**
	 * @param {{ articulation: import('../scene/Articulation.js').Articulation, api?: object,
	 *   sources?: object[], onChange?: Function }} options `sources` as targets.js's
	 */
	constructor( { articulation, api, sources = [ new SavedPoseTargets( { api } ), new PhonemeTargets( { api } ) ], onChange = () => {} } ) {

		this.articulation = articulation;
		this.sources = sources;
		this.onChange = onChange;
		this.current = { name: REST, label: 'Rest' };
		this.select = h( 'select', { id: 'head-target', className: 'head-target', onChange: () => this.choose( this.select.value ) },
			h( 'option', { value: REST }, 'Rest (no target)' ) );
		this.status = h( 'p', { className: 'status head-target-status', role: 'status', 'aria-live': 'polite' } );
		this.element = h( 'div', { className: 'field' },
			h( 'label', { className: 'field-label', for: 'head-target' }, 'Show a pose or sound' ),
			this.select,
			this.status,
		);
		this.unregister = registerDebug( 'headTarget', () => ( { ...this.current } ) );

	}

	/** Fill the chooser; a source that cannot be listed is left out with a word in the status line. */
	async load() {

		const missing = [];
		for ( const source of this.sources ) {

			let entries;
			try {

				entries = await source.list();

			} catch ( error ) {

				missing.push( source.title.toLowerCase() );
				console.warn( `Glasshead: the head view lists no ${ source.title.toLowerCase() }: ${ error.message }` );
				continue;

			}

			if ( entries.length === 0 ) continue;
			const group = h( 'optgroup', { label: source.title } );
			for ( const entry of entries ) group.append( h( 'option', { value: `${ source.kind }:${ entry.id }` }, entry.label ) );
			this.select.append( group );

		}

		this.status.textContent = missing.length ? `Could not list the ${ missing.join( ' or ' ) }.` : '';
		return this;

	}

	/** Show the target named `name` ('phoneme:T', 'pose:3'), or the rest posture for REST. */
	async choose( name ) {

		this.select.value = name;
		if ( name === REST ) return this.apply( REST, 'Rest', {} );
		const [ kind, ...rest ] = name.split( ':' );
		const source = this.sources.find( ( candidate ) => candidate.kind === kind );
		if ( ! source ) throw new Error( `no target source "${ kind }"` );
		this.status.textContent = 'Loading…';
		try {

			const target = await source.frames( rest.join( ':' ) );
			if ( this.select.value !== name ) return null; // another choice came first
			this.status.textContent = '';
			return this.apply( name, target.label, target.params );

		} catch ( error ) {

			this.status.textContent = `Could not show this target: ${ error.message }`;
			return null;

		}

	}

	apply( name, label, params ) {

		const state = this.articulation.state;
		state.assign( knownParams( params, state.names ) );
		this.articulation.update();
		this.current = { name, label };
		this.onChange( this.current );
		return this.current;

	}

	setEnabled( enabled ) {

		this.select.disabled = ! enabled;

	}

	dispose() {

		this.unregister();

	}

}
