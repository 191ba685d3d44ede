// The live preview of the author's editor: the speech player's head (SpeechView, without its own
// form) saying the selected item's target with the item's views, audio and speed, through the
// same ItemPresenter the teacher's runner and the child's practice use (LessonRunnerViews.js).
// A change to the item is shown again after a short pause in the typing, so the head follows
// the form without asking the server at every key.
//
//   const preview = new LessonPreview( { api } );
//   box.append( preview.element ); preview.start();
//   preview.show( item );   // after PREVIEW_DELAY_MS, the latest item wins
//   preview.play();         // say it (the item's own speed)

import { api as pageApi } from '../../api.js';
import { h } from '../shared/dom.js';
import { ItemPresenter } from '../lessons/LessonRunnerViews.js';
import { SpeechView } from '../speak/SpeechView.js';
import { LABEL_CHOICES } from './LessonEditorModel.js';

/** What the preview says when bone hides labels the item names (their words, joined). */
export function hiddenLabelsWarning( names ) {

	if ( ! names.length ) return '';
	const words = names.map( ( name ) => LABEL_CHOICES.find( ( c ) => c.value === name )?.label ?? name );
	const list = words.length > 1 ? `${ words.slice( 0, - 1 ).join( ', ' ) } and ${ words.at( - 1 ) }` : words[ 0 ];
	return `In this view, bone hides the ${ list }: a child would not see ${ words.length > 1 ? 'them' : 'it' }. Turn on the cutaway and see it from the profile.`;

}

/** How long the form must be still before the preview follows it, ms. */
export const PREVIEW_DELAY_MS = 600;

export class LessonPreview {

	/** @param {{ api?: object }} options */
	constructor( { api = pageApi } = {} ) {

		this.api = api;
		this.status = h( 'p', { className: 'status le-preview-status', role: 'status', 'aria-live': 'polite' }, 'Loading the head…' );
		this.playButton = h( 'button', { type: 'button', className: 'le-preview-play', disabled: '', onClick: () => this.play() }, 'Play the preview' );
		this.box = h( 'div', { className: 'le-preview-head' } );
		this.warning = h( 'p', { className: 'le-preview-warning', role: 'alert', hidden: '' } );
		this.element = h( 'section', { className: 'le-preview', 'aria-label': 'Preview' },
			h( 'div', { className: 'le-preview-bar' }, h( 'h2', { className: 'le-heading' }, 'Preview' ), this.playButton, this.status ),
			this.warning, this.box );
		this.hidden = [];
		this.pending = null;
		this.timer = null;
		this.shown = null;
		this.presented = 0;
		this.busy = false;
		this.waiting = false;

	}

	/** Mount the head (it loads in the background). */
	start() {

		this.view = new SpeechView( { api: this.api, sayOnLoad: false } ).mount( this.box );
		this.presenter = new ItemPresenter( this.view );
		this.view.ready.then( ( loaded ) => {

			if ( ! loaded ) this.say( `The head could not load: ${ this.view.state.error ?? 'unknown error' }` );
			else if ( this.pending ) this.flush();
			else this.say( '' );

		} );
		return this;

	}

	/** Show `item` (a normalised lesson item) after PREVIEW_DELAY_MS; `now` skips the wait. */
	show( item, { now = false } = {} ) {

		this.pending = structuredClone( item );
		clearTimeout( this.timer );
		this.waiting = true;
		if ( now ) this.flush();
		else this.timer = setTimeout( () => this.flush(), PREVIEW_DELAY_MS );

	}

	async flush() {

		clearTimeout( this.timer );
		const item = this.pending;
		this.waiting = ! this.view?.state.loaded; // once loaded, the item is shown now
		if ( ! item || ! this.view?.state.loaded ) return;
		if ( ! item.target.text.trim() ) {

			this.say( 'Type a target to hear it.' );
			this.playButton.disabled = true;
			return;

		}

		const presented = ++ this.presented;
		this.busy = true;
		this.playButton.disabled = true;
		this.say( 'Preparing the preview…' );
		this.warn( [] );
		const done = await this.presenter.present( item );
		if ( presented !== this.presented || ! this.view ) return;
		this.busy = false;
		if ( done ) {

			this.shown = item;
			this.playButton.disabled = false;
			this.say( `Ready: ${ item.target.kind === 'phoneme' ? `/${ item.target.text }/` : item.target.text }` );
			const hidden = Array.isArray( item.views.labels ) ? await this.presenter.hiddenLabels() : [];
			if ( presented === this.presented ) this.warn( hidden );

		} else {

			this.shown = null;
			const said = this.view.form?.error?.textContent || this.view.state.error || 'the server did not answer';
			this.say( `The head cannot say this item: ${ said }` );

		}

	}

	/** Say the shown item again from its start. */
	play() {

		if ( this.shown ) this.presenter.replay();

	}

	say( text ) {

		this.status.textContent = text;

	}

	/** Flag the labels the item names that bone hides in its view (none: the flag goes). */
	warn( names ) {

		this.hidden = names;
		this.warning.textContent = hiddenLabelsWarning( names );
		this.warning.hidden = names.length === 0;

	}

	/** What window.glasshead.author.preview reports. */
	report() {

		return {
			loaded: this.view?.state.loaded ?? false, busy: this.busy || Boolean( this.waiting ), target: this.shown?.target ?? null,
			settings: this.presenter?.settings ?? null, playing: this.view?.clock.playing ?? false,
			utterance: this.view?.utterance?.id ?? null, status: this.status.textContent, hidden: this.hidden,
		};

	}

	dispose() {

		clearTimeout( this.timer );
		this.presented += 1;
		this.view?.unmount();
		this.view = null;
		this.element.remove();

	}

}
