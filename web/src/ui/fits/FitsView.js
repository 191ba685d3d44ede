// The fit page (route `#/fits`): an author or a clinician chooses their own measurements (a tongue
// contour, EPG frames, one frame of EMA sensors, or a surface), weighs them when there are several,
// and starts a fit (POST /fits, docs/fits.md). The page follows the fit's progress (GET /fits/{id}
// until it is done), then says how closely the target matches each measurement and links to it
// among the clinician's targets. The recent fits are listed under the form.

import { mountForRoles } from '../shared/SignInPrompt.js';
import { h } from '../shared/dom.js';
import { fitErrorWords } from '../shared/targets.js';
import { View } from '../shared/View.js';
import { FIT_PARTS, fitForm, fitKindFor, progressWords } from './fitUpload.js';
import './fits.css';

/** Milliseconds between looks at a running fit. */
const POLL_MS = 400;
/** Fits listed under the form. */
const RECENT = 12;
/** What the chosen files make, in words. */
const KIND_WORDS = {
	contour: 'A fit to the tongue contour.',
	epg: 'A fit to the EPG frames.',
	ema: 'A fit to the sensors.',
	surface: 'A fit to the tongue surface.',
	combined: 'One fit to them all: each measurement counts as much as its weight.',
};

/** The clinician view's address with a fit chosen as its target. */
export function fitTargetHref( fit ) {

	return `#/clinician?target=fit:${ fit.id }`;

}

export class FitsView extends View {

	/** @param {{ api?: object, win?: Window, pollMs?: number }} options */
	constructor( { api, win, pollMs = POLL_MS } = {} ) {

		super( { api, win } );
		this.pollMs = pollMs;
		this.files = Object.fromEntries( FIT_PARTS.map( ( part ) => [ part.kind, null ] ) );
		this.state = { loaded: false, kind: null, fit: null, recent: [], message: '' };
		this.stopped = false;

	}

	mount( container ) {

		this.attach( container, h( 'div', { className: 'fits-view' } ) );
		this.onUnmount( () => ( this.stopped = true ) );
		this.debugFields( { loaded: () => this.state.loaded, fits: () => ( { ...this.state, fit: this.state.fit && { ...this.state.fit } } ) } );
		this.weights = {};
		this.name = h( 'input', { type: 'text', id: 'fit-name', maxlength: '200', placeholder: 'from the file names' } );
		this.start = h( 'button', { type: 'submit', className: 'fits-start' }, 'Start the fit' );
		this.message = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' } );
		this.progress = h( 'div', { className: 'fits-progress', hidden: '' } );
		this.list = h( 'ul', { className: 'fits-list', 'aria-label': 'Recent fits' } );
		const form = h( 'form', { className: 'fits-form', 'aria-label': 'Fit a target', onSubmit: ( event ) => {

			event.preventDefault();
			this.submit();

		} },
		h( 'p', { className: 'fits-note' }, 'Choose one measurement, or a contour, EPG frames and sensors together. Coordinates are in millimetres in the head’s frame (docs/fits.md).' ),
		...FIT_PARTS.map( ( part ) => this.partRow( part ) ),
		h( 'div', { className: 'fits-row' }, h( 'label', { for: 'fit-name' }, 'Target name' ), this.name ),
		h( 'div', { className: 'fits-actions' }, this.start, this.message ) );
		this.root.append( h( 'h1', { className: 'fits-title' }, 'Fit a target to your measurements' ), form, this.progress,
			h( 'h2', {}, 'Recent fits' ), this.list );
		this.update();
		this.loadRecent();
		return this;

	}

	/** One measurement: its file input, what the file holds, and its weight in a combined fit. */
	partRow( part ) {

		const id = `fit-file-${ part.kind }`;
		const input = h( 'input', { type: 'file', id, accept: part.accept, 'data-kind': part.kind } );
		input.addEventListener( 'change', () => {

			this.files[ part.kind ] = input.files?.[ 0 ] ?? null;
			this.update();

		} );
		const row = h( 'div', { className: 'fits-row', 'data-part': part.kind },
			h( 'label', { for: id }, part.label ), input, h( 'span', { className: 'fits-hint' }, part.hint ) );
		if ( part.kind !== 'surface' ) {

			const weight = h( 'input', { type: 'number', id: `fit-weight-${ part.kind }`, min: '0', max: '100', step: '0.5', value: '1', className: 'fits-weight' } );
			weight.addEventListener( 'input', () => ( this.weights[ part.kind ] = Number( weight.value ) ) );
			row.append( h( 'label', { for: weight.id, className: 'fits-weight-label' }, 'weight' ), weight );

		}

		return row;

	}

	/** The kind the chosen files make, the weights shown only for a combined fit. */
	update() {

		const { kind, problem } = fitKindFor( this.files );
		this.state.kind = kind;
		this.root.classList.toggle( 'fits-combined', kind === 'combined' );
		this.start.disabled = ! kind || this.running;
		this.say( problem ?? KIND_WORDS[ kind ] );

	}

	say( text ) {

		this.state.message = text;
		this.message.textContent = text;

	}

	async submit() {

		let form;
		try {

			form = fitForm( this.files, { weights: this.weights, name: this.name.value } );

		} catch ( error ) {

			this.say( error.message );
			return;

		}

		this.running = true;
		this.start.disabled = true;
		this.say( 'Sending the files…' );
		try {

			const fit = await this.api.post( 'fits', form );
			this.follow( fit );

		} catch ( error ) {

			this.running = false;
			this.update();
			this.fail( error );

		}

	}

	/** Show the fit's progress until it is done or failed. */
	async follow( fit ) {

		this.state.fit = fit;
		this.showProgress( fit );
		while ( ! this.stopped && ( fit.state === 'queued' || fit.state === 'running' ) ) {

			await new Promise( ( resolve ) => this.window.setTimeout( resolve, this.pollMs ) );
			if ( this.stopped ) return;
			try {

				fit = await this.api.get( `fits/${ fit.id }` );

			} catch ( error ) {

				this.running = false;
				this.update();
				this.fail( error );
				return;

			}

			this.state.fit = fit;
			this.showProgress( fit );

		}

		this.running = false;
		this.update();
		this.say( fit.state === 'done' ? `The fit is done: ${ fitErrorWords( fit.report ) }.` : `The fit failed: ${ fit.message }` );
		this.loadRecent();

	}

	showProgress( fit ) {

		const fraction = fit.state === 'done' ? 1 : fit.progress?.fraction ?? 0;
		const bar = h( 'progress', { max: '1', value: String( fraction ), 'aria-label': `Progress of ${ fit.name }` } );
		const words = fit.state === 'queued' ? 'waiting for a free worker' : fit.state === 'running' ? progressWords( fit.progress ) : fit.state;
		const children = [ h( 'p', { className: 'fits-progress-name' }, `${ fit.name } (${ fit.kind })` ), bar, h( 'p', {}, words ) ];
		if ( fit.state === 'done' ) children.push( this.resultBlock( fit ) );
		if ( fit.state === 'failed' ) children.push( h( 'p', { className: 'fits-failed' }, fit.message ?? 'The fit failed.' ) );
		this.progress.replaceChildren( ...children );
		this.progress.hidden = false;

	}

	/** A finished fit: each measurement's error and the link to it among the targets. */
	resultBlock( fit ) {

		const terms = Object.entries( fit.report?.terms ?? {} );
		const rows = terms.length ? terms.map( ( [ kind, term ] ) => h( 'li', {}, `${ fitErrorWords( { terms: { [ kind ]: term } } ) } (weight ${ term.weight })` ) )
			: [ h( 'li', {}, fitErrorWords( fit.report ) ) ];
		return h( 'div', { className: 'fits-result' },
			h( 'ul', { 'aria-label': 'How closely the target matches' }, ...rows ),
			h( 'a', { href: fitTargetHref( fit ), className: 'fits-open' }, 'Open it among the clinician’s targets' ) );

	}

	async loadRecent() {

		try {

			const body = await this.api.get( `fits?limit=${ RECENT }` );
			this.state.recent = body.fits.map( ( fit ) => ( { id: fit.id, name: fit.name, state: fit.state } ) );
			this.list.replaceChildren( ...body.fits.map( ( fit ) => h( 'li', { 'data-fit': String( fit.id ) },
				h( 'span', { className: 'fits-list-name' }, fit.name ),
				h( 'span', { className: `fits-state fits-${ fit.state }` }, fit.state ),
				h( 'span', {}, fit.state === 'done' ? `${ fit.kind }: ${ fitErrorWords( fit.report ) }` : fit.kind ),
				fit.state === 'done' ? h( 'a', { href: fitTargetHref( fit ) }, 'Open' ) : '' ) ) );
			if ( ! body.fits.length ) this.list.replaceChildren( h( 'li', { className: 'fits-note' }, 'No fits yet.' ) );

		} catch ( error ) {

			this.fail( error );

		}

		this.state.loaded = true;

	}

	fail( error ) {

		this.showFailure( error, this.message, ( words ) => this.say( words ) );

	}

}

/** Route entry for the view registry: authors, clinicians and admins fit targets. */
export function mountFitsView( container ) {

	return mountForRoles( container, { roles: [ 'author', 'clinician', 'admin' ], reason: 'as an author or a clinician to fit targets',
		debugName: 'fits', title: 'The fit page', mount: ( element ) => new FitsView().mount( element ) } );

}
