// The teacher's lesson runner (route `#/teach`): the lessons to choose from, then one lesson item
// by item (`#/teach?lesson=ID&item=N`) on the speech player's head, each item with its own views,
// audio, speed and presentation (LessonRunnerViews.js). A side panel gives the lesson to a class
// and lists the class's practice of it; presentation mode, for a projector at 1366 x 768, hides
// the panel, the transport and the navigation bar, so that the head fills the screen under the
// target in big letters and a thin strip of item dots. Keys: Space plays or pauses, the left and
// right arrows move between items, S slows to SLOW_SPEED and back, F goes full screen (and into
// presentation mode), Esc leaves full screen, then presentation mode, then the lesson.

import { currentSession, onSessionChange } from '../../session.js';
import { h } from '../shared/dom.js';
import { LessonRunnerPanel } from './LessonRunnerPanel.js';
import {
	itemSettings, listenHref, parseRunnerHash, runnerAction, runnerHref, runnerSpeed, stepItem, targetKindLabel, targetLabel,
} from './LessonRunnerItems.js';
import { signedOutPrompt, signInPrompt } from '../shared/SignInPrompt.js';
import { ItemPresenter, phonemeInventory } from './LessonRunnerViews.js';
import { soundPicture } from '../shared/soundPictures.js';
import { SpeechView } from '../speak/SpeechView.js';
import { View } from '../shared/View.js';
import './lessonRunner.css';

/** How long the presentation bar stays after the pointer or a key last moved, ms. */
const BAR_REST_MS = 3000;

export class LessonRunner extends View {

	/** @param {{ api?: object, win?: Window }} options */
	constructor( options ) {

		super( options );
		this.lesson = null;
		this.index = 0;
		this.slow = false;
		this.presenting = false;
		this.shows = 0;

	}

	mount( container ) {

		this.attach( container, h( 'div', { className: 'lesson-runner' } ) );
		this.listen( this.window, 'hashchange', () => this.route() );
		this.listen( this.window, 'keydown', ( event ) => this.key( event ) );
		this.listen( this.window.document, 'fullscreenchange', () => this.fullscreenChanged() );
		this.onUnmount( onSessionChange( () => this.route( true ) ) );
		this.debugFields( { runner: () => this.report() } );
		this.route();
		return this;

	}

	/** What window.glasshead.runner reports. */
	report() {

		return {
			screen: this.screen ?? null, lesson: this.lesson?.id ?? null, item: this.lesson ? this.index : null,
			items: this.lesson?.items.length ?? 0, target: this.item ? targetLabel( this.item ) : null,
			settings: this.presenter?.settings ?? null, slow: this.slow, presenting: this.presenting,
			ready: this.ready ?? false, panel: this.panel?.report() ?? null, lessons: this.lessons?.map( ( l ) => l.id ) ?? [],
		};

	}

	get item() {

		return this.lesson?.items[ this.index ] ?? null;

	}

	/** Show what the address names: the list, or a lesson's item; a sign-in link without a session. */
	async route( force = false ) {

		const { lesson, item, present } = parseRunnerHash( this.window.location.hash );
		const session = currentSession( { win: this.window } );
		if ( session?.kind !== 'user' ) return this.showSignIn();
		if ( lesson === null ) return this.showList();
		if ( force || this.lesson?.id !== lesson ) await this.openLesson( lesson );
		if ( this.lesson?.id !== lesson ) return;
		if ( present ) {

			// Presented from the list: the address drops the request, so a reload shows the lesson.
			this.window.history.replaceState( null, '', runnerHref( lesson, item ) );
			this.setPresenting( true );

		}

		this.showItem( stepItem( item, 0, this.lesson.items.length ) );

	}

	clear( screen ) {

		this.screen = screen;
		this.closeLesson();
		this.root.className = `lesson-runner lr-on-${ screen }`;
		this.root.replaceChildren();

	}

	showSignIn() {

		this.clear( 'sign-in' );
		this.root.append( h( 'div', { className: 'lr-message' },
			h( 'h1', { className: 'lr-page-title' }, 'Lessons' ),
			signInPrompt( { reason: 'as a teacher to run a lesson with a class', win: this.window } ) ) );

	}

	async showList() {

		this.clear( 'list' );
		const shown = ++ this.shows;
		const status = h( 'p', { className: 'status', role: 'status' }, 'Loading the lessons…' );
		const list = h( 'ul', { className: 'lr-lessons', 'aria-label': 'Lessons' } );
		this.root.append( h( 'div', { className: 'lr-message lr-list' }, h( 'h1', { className: 'lr-page-title' }, 'Lessons' ), status, list ) );
		try {

			this.lessons = ( await this.api.get( 'lessons?limit=100' ) ).lessons ?? [];

		} catch ( error ) {

			status.textContent = '';
			status.after( signedOutPrompt( error, { win: this.window } ) ?? h( 'p', { className: 'error', role: 'alert' }, `The lessons could not be loaded: ${ error.message }` ) );
			return;

		}

		if ( shown !== this.shows ) return;
		status.textContent = this.lessons.length ? 'Choose a lesson to run.' : 'There are no lessons yet.';
		list.replaceChildren( ...this.lessons.map( ( lesson ) => h( 'li', { className: 'lr-lesson-row' },
			h( 'a', { className: 'lr-lesson', href: runnerHref( lesson.id, 0 ) },
				h( 'span', { className: 'lr-lesson-title' }, lesson.title ),
				h( 'span', { className: 'lr-lesson-about' }, `${ lesson.n_items } items. ${ lesson.description }` ) ),
			h( 'a', { className: 'lr-lesson-present', href: runnerHref( lesson.id, 0, { present: true } ), 'aria-label': `Present ${ lesson.title }` }, 'Present' ) ) ) );

	}

	/** Load lesson `id` and build its screen: the bar, the head, the panel. */
	async openLesson( id ) {

		this.clear( 'loading' );
		const shown = ++ this.shows;
		let lesson;
		try {

			lesson = await this.api.get( `lessons/${ id }` );

		} catch ( error ) {

			if ( shown !== this.shows ) return;
			const prompt = signedOutPrompt( error, { win: this.window } ) ?? h( 'p', { className: 'error', role: 'alert' }, `The lesson could not be opened: ${ error.message }` );
			this.root.append( h( 'div', { className: 'lr-message' }, prompt, h( 'a', { className: 'lr-link', href: runnerHref() }, 'All lessons' ) ) );
			return;

		}

		if ( shown !== this.shows ) return;
		this.screen = 'lesson';
		this.root.className = 'lesson-runner lr-on-lesson';
		this.lesson = lesson;
		this.index = - 1;
		this.buildLesson();

	}

	buildLesson() {

		const lesson = this.lesson;
		const button = ( label, onClick, extra = {} ) => h( 'button', { type: 'button', onClick, ...extra }, label );
		this.dots = lesson.items.map( ( item, index ) => h( 'a', {
			className: 'lr-dot', href: runnerHref( lesson.id, index ), 'aria-label': `Item ${ index + 1 }: ${ targetLabel( item ) }`,
		} ) );
		this.playButton = button( 'Play', () => this.act( 'play' ), { className: 'lr-play' } );
		this.slowButton = button( 'Slow (S)', () => this.act( 'slow' ), { 'aria-pressed': 'false' } );
		this.toolbar = h( 'div', { className: 'lr-toolbar', role: 'group', 'aria-label': 'Lesson' },
			h( 'a', { className: 'lr-link', href: runnerHref() }, 'All lessons' ),
			button( 'Previous', () => this.act( 'previous' ) ), this.playButton, button( 'Next', () => this.act( 'next' ) ),
			this.slowButton, button( 'Present', () => this.setPresenting( true ) ), button( 'Full screen (F)', () => this.act( 'fullscreen' ) ),
			this.liveLink = h( 'a', { className: 'lr-link', target: '_blank', rel: 'noopener', href: listenHref( null ) }, 'Live chart' ) );
		this.kind = h( 'span', { className: 'lr-kind' } );
		this.target = h( 'span', { className: 'lr-target-text' } );
		this.picture = h( 'span', { className: 'lr-target-picture' } );
		this.targetBox = h( 'div', { className: 'lr-target', role: 'status', 'aria-live': 'polite' }, this.kind, h( 'span', { className: 'lr-target-line' }, this.target, this.picture ) );
		this.how = h( 'p', { className: 'lr-how', hidden: '' } );
		this.dotStrip = h( 'div', { className: 'lr-itembar' }, h( 'h1', { className: 'lr-title' }, lesson.title ), h( 'nav', { className: 'lr-dots', 'aria-label': 'Items' }, ...this.dots ) );
		this.headBox = h( 'div', { className: 'lr-head' } );
		this.panel = new LessonRunnerPanel( { api: this.api } );
		this.presentPlay = button( 'Play', () => this.act( 'play' ), { className: 'lr-play' } );
		this.presentSlow = button( 'Slow (S)', () => this.act( 'slow' ), { 'aria-pressed': 'false' } );
		this.presentBar = h( 'div', { className: 'lr-present-bar', role: 'toolbar', 'aria-label': 'Presenting' },
			button( 'Previous', () => this.act( 'previous' ) ), this.presentPlay, button( 'Next', () => this.act( 'next' ) ), this.presentSlow,
			button( 'Leave (Esc)', () => this.act( 'leave' ) ),
			h( 'p', { className: 'lr-present-hint' }, 'Space plays, the arrows change items, Esc leaves.' ) );
		this.panel.element.prepend( this.how );
		this.root.append( this.toolbar, this.dotStrip, h( 'div', { className: 'lr-main' }, this.headBox, this.targetBox ), this.panel.element, this.presentBar );
		this.listen( this.root, 'pointermove', () => this.wake() );
		this.listen( this.root, 'pointerdown', () => this.wake() );
		this.speech = new SpeechView( { api: this.api, sayOnLoad: false } ).mount( this.headBox );
		this.presenter = new ItemPresenter( this.speech, { obstacles: () => [ this.targetBox ] } );
		this.unwatch = this.speech.viewer?.onFrame( () => this.syncPlay() );
		this.panel.setLesson( lesson );

	}

	closeLesson() {

		this.setPresenting( false );
		this.unwatch?.();
		this.speech?.unmount();
		this.speech = null;
		this.presenter = null;
		this.panel = null;
		this.lesson = null;
		this.ready = false;

	}

	/** Show item `index`: its target, its dot, and the head set up for it. */
	async showItem( index ) {

		if ( index === this.index ) return;
		this.index = index;
		this.ready = false;
		const item = this.item;
		this.kind.textContent = targetKindLabel( item );
		this.target.textContent = targetLabel( item );
		this.showSound( item );
		this.liveLink.href = listenHref( item );
		this.dots.forEach( ( dot, k ) => ( k === index ? dot.setAttribute( 'aria-current', 'step' ) : dot.removeAttribute( 'aria-current' ) ) );
		const shown = await this.presenter.present( item );
		if ( ! shown || this.index !== index ) return;
		this.presenter.setSpeed( runnerSpeed( itemSettings( item ), this.slow ) );
		this.ready = true;

	}

	/**
	 * A sound's picture beside its symbol, for the children who cannot read it, and how it is
	 * made, for the teacher to say (GET /phonemes); neither for a word.
	 */
	async showSound( item ) {

		this.picture.replaceChildren();
		this.how.hidden = true;
		if ( item.target.kind !== 'phoneme' ) return;
		const phoneme = ( await phonemeInventory( this.api ) ).get( item.target.text );
		if ( ! phoneme || this.item !== item ) return;
		const pictured = soundPicture( phoneme.arpabet, { className: 'lr-sound-picture', doc: this.window.document } );
		if ( pictured ) this.picture.append( pictured );
		this.how.replaceChildren( h( 'strong', {}, `How ${ targetLabel( item ) } is made: ` ), phoneme.how ?? '' );
		this.how.hidden = ! phoneme.how;

	}

	/** The Play button says Pause while playing. */
	syncPlay() {

		const label = this.speech?.clock.playing ? 'Pause' : 'Play';
		for ( const button of [ this.playButton, this.presentPlay ] ) if ( button.textContent !== label ) button.textContent = label;
		return false;

	}

	key( event ) {

		if ( this.screen !== 'lesson' ) return;
		const action = runnerAction( event );
		if ( this.presenting ) this.wake();
		if ( ! action ) return;
		event.preventDefault();
		this.act( action );

	}

	act( action ) {

		const lesson = this.lesson;
		if ( ! lesson ) return;
		if ( action === 'play' ) this.presenter.togglePlay();
		else if ( action === 'previous' || action === 'next' ) {

			const index = stepItem( this.index, action === 'next' ? 1 : - 1, lesson.items.length );
			if ( index !== this.index ) this.window.location.hash = runnerHref( lesson.id, index );

		} else if ( action === 'slow' ) {

			this.slow = ! this.slow;
			for ( const button of [ this.slowButton, this.presentSlow ] ) button.setAttribute( 'aria-pressed', String( this.slow ) );
			if ( this.presenter.settings ) this.presenter.setSpeed( runnerSpeed( this.presenter.settings, this.slow ) );

		} else if ( action === 'fullscreen' ) this.toggleFullscreen();
		else if ( action === 'leave' ) {

			if ( this.window.document.fullscreenElement ) this.window.document.exitFullscreen?.();
			else if ( this.presenting ) this.setPresenting( false );
			else this.window.location.hash = runnerHref();

		}

	}

	toggleFullscreen() {

		const doc = this.window.document;
		if ( doc.fullscreenElement ) {

			doc.exitFullscreen?.();
			return;

		}

		this.setPresenting( true );
		doc.documentElement.requestFullscreen?.()?.catch?.( () => {} ); // refused: presentation mode in the window

	}

	fullscreenChanged() {

		if ( ! this.window.document.fullscreenElement ) this.setPresenting( false );

	}

	/**
	 * Presentation mode on or off: the head fills the screen, the panel and the bars hide, and a
	 * small bar of controls with a hint shows until the pointer rests. The runner takes the focus
	 * (the Present button it came from is hidden), so that Space and the arrows work at once.
	 */
	setPresenting( on ) {

		const was = this.presenting;
		this.presenting = Boolean( on ) && this.screen === 'lesson';
		this.root?.classList.toggle( 'presenting', this.presenting );
		this.window.document.body.classList.toggle( 'lr-presenting', this.presenting );
		this.speech?.viewer?.requestRender();
		if ( this.presenting && ! was ) {

			this.root.tabIndex = - 1;
			this.root.focus( { preventScroll: true } );
			this.wake();

		}

	}

	/** Show the presentation bar, and hide it again once nothing has moved for BAR_REST_MS. */
	wake() {

		if ( ! this.presentBar ) return;
		this.presentBar.classList.remove( 'lr-resting' );
		this.window.clearTimeout( this.restTimer );
		this.restTimer = this.window.setTimeout( () => this.presentBar?.classList.add( 'lr-resting' ), BAR_REST_MS );

	}

	unmount() {

		this.window.clearTimeout( this.restTimer );
		if ( this.window.document.fullscreenElement ) this.window.document.exitFullscreen?.();
		this.closeLesson();
		super.unmount();

	}

}

/** Route entry for the view registry. */
export function mountLessonRunner( container ) {

	return new LessonRunner().mount( container );

}
