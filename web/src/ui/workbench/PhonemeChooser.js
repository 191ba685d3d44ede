// The workbench's "Phoneme target" group: choose any phoneme's articulation target (GET
// /phonemes, docs/targets.md) and every parameter (tongue, jaw, lips, velum) is set to it, through
// the state the sliders and the pasted JSON go through, so the sliders move too; the group names
// the target until a slider moves it away. window.glasshead.phonemeTarget reports which.
//
// PhonemeTargetControl holds the logic and no DOM (tested in Node with a fake API);
// PhonemeChooser is its view.

import { api as pageApi } from '../../api.js';
import { registerDebug } from '../../debug.js';
import { h } from '../shared/dom.js';
import { loadPhonemeList, loadPhonemeTarget } from '../shared/loaders.js';
import { assignParams } from './ObservationControl.js';
import { epgBasisText, phonemeLabel } from '../shared/targets.js';

export class PhonemeTargetControl {

	/** @param {{ api?: object, state: import('../../core/paramState.js').ParamState }} options */
	constructor( { api = pageApi, state } ) {

		this.api = api;
		this.state = state;
		this.phonemes = [];
		this.current = null;
		this.appliedVersion = - 1;
		this.request = 0;

	}

	/** The inventory: [{ arpabet, ipa, kind, examples, source, ... }]. */
	async list() {

		const body = await loadPhonemeList( { api: this.api } );
		this.phonemes = body?.phonemes ?? [];
		return this.phonemes;

	}

	/**
	 * Fetch the target of `symbol` (ARPAbet) and set every parameter to it; '' or null forgets
	 * the choice and changes nothing. Resolves to the target (null when a later choice won).
	 * Names the state does not have are left out (`ignored`); a value outside its range is
	 * refused with a RangeError and changes nothing.
	 */
	async choose( symbol ) {

		const request = ++ this.request;
		if ( ! symbol ) {

			this.current = null;
			return null;

		}

		const target = await loadPhonemeTarget( symbol, { api: this.api } );
		if ( request !== this.request ) return null;
		this.current = null; // while the state changes, no target is named (and none is 'edited')
		const ignored = assignParams( this.state, target.params );
		this.appliedVersion = this.state.version;
		this.current = { symbol: target.arpabet ?? symbol, ipa: target.ipa ?? null, label: phonemeLabel( target ), ignored, source: target.source ?? null, features: target.features ?? null, epgBasis: target.epg_basis ?? null };
		return target;

	}

	/** The phoneme features ({ voiced, manner, ... }) of the target the sliders show, else null. */
	shownFeatures() {

		return this.current && this.state.version === this.appliedVersion ? this.current.features : null;

	}

	/** What window.glasshead.phonemeTarget reports: the target chosen and whether the sliders still show it. */
	report() {

		if ( ! this.current ) return { listed: this.phonemes.length, symbol: null, state: null };
		const { symbol, ipa, label, ignored } = this.current;
		return { listed: this.phonemes.length, symbol, ipa, label, ignored, state: this.state.version === this.appliedVersion ? 'target' : 'edited' };

	}

}

/** How the target was made, in a few words. */
function sourceText( source ) {

	if ( source?.shapes?.length ) return `fitted to ${ source.shapes.join( ', ' ) }`;
	return 'from phonetic reasoning';

}

export class PhonemeChooser {

	/** @param {{ api?: object, state: import('../../core/paramState.js').ParamState }} options */
	constructor( { api = pageApi, state } ) {

		this.control = new PhonemeTargetControl( { api, state } );
		this.select = h( 'select', { className: 'wb-select', 'aria-label': 'Phoneme target', onChange: () => this.choose( this.select.value ) },
			h( 'option', { value: '' }, 'Loading the phonemes…' ) );
		this.status = h( 'p', { className: 'status wb-inline', role: 'status', 'aria-live': 'polite' } );
		this.errorText = h( 'p', { className: 'error wb-inline', role: 'alert', hidden: '' } );
		this.element = h( 'fieldset', { className: 'wb-box wb-phoneme', 'aria-label': 'Phoneme target' },
			h( 'legend', {}, 'Phoneme target' ), this.select, this.status, this.errorText );
		this.unsubscribe = state.onChange( () => this.sync() );
		this.unregister = registerDebug( 'phonemeTarget', () => this.control.report() );
		this.load();

	}

	async load() {

		try {

			const phonemes = await this.control.list();
			// Grouped by kind (vowels, stops, ...), in the inventory's order.
			const groups = new Map();
			for ( const phoneme of phonemes ) {

				const kind = phoneme.kind ?? 'other';
				if ( ! groups.has( kind ) ) groups.set( kind, [] );
				groups.get( kind ).push( h( 'option', { value: phoneme.arpabet }, phonemeLabel( phoneme ) ) );

			}

			this.select.replaceChildren(
				h( 'option', { value: '' }, phonemes.length ? 'Choose a phoneme…' : 'No phoneme targets on this server' ),
				...[ ...groups ].map( ( [ kind, options ] ) => h( 'optgroup', { label: kind.charAt( 0 ).toUpperCase() + kind.slice( 1 ) }, ...options ) ),
			);

		} catch ( error ) {

			this.select.replaceChildren( h( 'option', { value: '' }, 'No phoneme targets' ) );
			this.showError( error.message );

		}

	}

	async choose( symbol ) {

		this.showError( null );
		try {

			await this.control.choose( symbol );

		} catch ( error ) {

			this.showError( error.message );

		}

		this.sync();

	}

	sync() {

		const report = this.control.report();
		if ( ! report.symbol ) {

			this.status.textContent = '';
			return;

		}

		const how = `${ sourceText( this.control.current.source ) }${ epgBasisText( this.control.current.epgBasis ) }`;
		this.status.textContent = report.state === 'target' ? `Showing ${ report.label }, ${ how }.` : `${ report.label }, edited since.`;
		if ( report.state === 'edited' && this.select.value !== '' ) this.select.value = '';

	}

	showError( message ) {

		this.errorText.textContent = message ?? '';
		this.errorText.hidden = ! message;

	}

	dispose() {

		this.unsubscribe();
		this.unregister();
		this.element.remove();

	}

}
