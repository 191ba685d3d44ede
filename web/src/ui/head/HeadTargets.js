// The head view's chooser of what to show: the rest posture, a saved pose (GET /poses) or a
// phoneme target (GET /phonemes). Choosing one poses the tongue, jaw, lips and velum with its
// parameters, so the live palatogram beside the head shows that target's contact.
//
// The lists come from the clinician's target sources (targets.js), so a new kind of target shows
// here as well once it is added there. Parameters of a rig the head has not loaded are left out.
//
// Phoneme targets are open to everyone; saved poses are the school's own and are listed only to
// an adult signed in (sourceShown), the lists made again when someone signs in or out.

import { registerDebug } from '../../debug.js';
import { clearSession, currentSession, onSessionChange } from '../../session.js';
import { h } from '../shared/dom.js';
import { isSignedOut } from '../shared/signIn.js';
import { PhonemeTargets, SavedPoseTargets } from '../shared/targets.js';

/** Kinds of target that only a signed-in adult may list. */
export const SIGNED_IN_KINDS = Object.freeze( [ 'pose' ] );

/** Whether the chooser lists the source of `kind` to `session` (session.js's, or null). */
export function sourceShown( kind, session ) {

	return ! SIGNED_IN_KINDS.includes( kind ) || session?.kind === 'user';

}

/** The chooser's value for the rest posture. */
export const REST = '';

/** The parameters of `params` that `state` knows ({ name: value }); the rest are dropped. */
export function knownParams( params, names ) {

	const known = new Set( names );
	return Object.fromEntries( Object.entries( params ?? {} ).filter( ( [ name, value ] ) => known.has( name ) && Number.isFinite( value ) ) );

}

export class HeadTargets {

	/**
	 * @param {{ articulation: import('../../scene/Articulation.js').Articulation, api?: object,
	 *   sources?: object[], onChange?: Function }} options `sources` as targets.js's
	 */
	constructor( { articulation, api, sources = [ new SavedPoseTargets( { api } ), new PhonemeTargets( { api } ) ], onChange = () => {}, win = globalThis.window } ) {

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
		this.window = win;
		this.stopSession = onSessionChange( () => this.load() );

	}

	/**
	 * Fill the chooser (again) with what the signed-in person may see; a source that cannot be
	 * listed is left out with a word in the status line.
	 */
	async load() {

		const loading = this.loading = ( this.loading ?? 0 ) + 1;
		const session = currentSession( { win: this.window } );
		const lists = [];
		const missing = [];
		for ( const source of this.sources ) {

			if ( ! sourceShown( source.kind, session ) ) continue;

			let entries;
			try {

				entries = await source.list();

			} catch ( error ) {

				// A token the server no longer takes: forgotten, and the lists made again without it.
				if ( isSignedOut( error ) ) return clearSession( { win: this.window } ) ?? this;
				missing.push( source.title.toLowerCase() );
				console.warn( `Glasshead: the head view lists no ${ source.title.toLowerCase() }: ${ error.message }` );
				continue;

			}

			if ( entries.length === 0 ) continue;
			const group = h( 'optgroup', { label: source.title } );
			for ( const entry of entries ) group.append( h( 'option', { value: `${ source.kind }:${ entry.id }` }, entry.label ) );
			lists.push( group );

		}

		if ( loading !== this.loading ) return this; // signed in or out meanwhile: a newer list comes
		const chosen = this.select.value;
		for ( const group of [ ...this.select.querySelectorAll( 'optgroup' ) ] ) group.remove();
		this.select.append( ...lists );
		this.select.value = chosen;
		if ( this.select.value !== chosen ) this.choose( REST ); // a saved pose shown to someone who signed out
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
		this.stopSession();

	}

}
