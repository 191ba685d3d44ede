// The child's practice (route `#/practice`), for a tablet held either way (768 x 1024, 1024 x 768)
// and with nothing to read: the class code (an adult may type it), then the child taps their own
// picture and name from the class's roster (POST /auth/class-roster, POST /auth/child-sessions),
// then a lesson assigned to them (GET /lessons gives only theirs), then one target at a time: the
// head says it (the speech player, set up by the item as in the lesson runner), a big button
// hears it again, "Say it" listens to the child (the microphone asked for then) and shows at once,
// with a face and a colour, how close the try was to the item's target zone, "I tried it" asks how it
// went with three faces (or an arrow to go on without), and the try is recorded (POST /practice,
// with the replays counted and what the voice measured) before the next target. The sound of a
// try stays on the device unless a clinician has switched recording on for the child: then a red
// dot in the corner says so, and each try's sound is kept with its record (PracticeAudio.js).
// Every button is 64 px and more, with a picture and an accessible name. The class code and the
// roster are in ChildPracticeSignIn.js.

import { currentSession } from '../../session.js';
import { h } from '../shared/dom.js';
import { joinCodeFromHash, PracticeRound } from './ChildPracticeFlow.js';
import { bigButton, signInMethods } from './ChildPracticeSignIn.js';
import { GROWN_UP_LOCK, grownUpLock } from './grownUpLock.js';
import { KEEPING_LABEL, PracticeAudio, uploadFailureMessage } from './PracticeAudio.js';
import { picture, RATINGS } from '../shared/ChildPracticePictures.js';
import { soundPicture } from '../shared/soundPictures.js';
import { targetLabel } from '../lessons/LessonRunnerItems.js';
import { ItemPresenter, phonemeInventory } from '../lessons/LessonRunnerViews.js';
import { SpeechView } from '../speak/SpeechView.js';
import { View } from '../shared/View.js';
import { ListenError } from '../listen/audioInput.js';
import { listenMessage, messagePicture } from '../listen/listenMessages.js';
import { attemptMeasures, attemptZone, itemTarget, NORMS_URL } from '../listen/listenScales.js';
import { PracticeListener } from './PracticeListener.js';
import './childPractice.css';

/** The face the verdict on a spoken try shows (no words): in the target, near it, try again. */
const VERDICT_FACES = Object.freeze( { in: 'happy', near: 'meh', off: 'sad' } );
const VERDICT_LABELS = Object.freeze( { in: 'In the target', near: 'Nearly', off: 'Try again' } );

export class ChildPractice extends View {

	/** @param {{ api?: object, win?: Window }} options */
	constructor( options ) {

		super( options );
		this.screen = null;
		this.roster = null;
		this.joinCode = null;
		this.round = null;
		this.error = null;
		/** Every message said aloud, in order (what window.glasshead.practice reports). */
		this.spoken = [];
		this.audio = new PracticeAudio( { api: this.api } );

	}

	mount( container ) {

		this.attach( container, h( 'div', { className: 'child-practice' } ) );
		// A kiosk: no adult navigation while a child practises; a grown-up holds the lock to leave.
		this.window.document.body.classList.add( 'cp-kiosk' );
		this.onUnmount( () => this.window.document.body.classList.remove( 'cp-kiosk' ) );
		this.debugFields( { practice: () => this.report() } );
		this.start();
		return this;

	}

	/** What window.glasshead.practice reports. */
	report() {

		const round = this.round;
		return {
			screen: this.screen, error: this.error, child: this.child ? { id: this.child.id, display_name: this.child.display_name } : null,
			roster: this.roster?.children.map( ( c ) => c.display_name ) ?? null, lessons: this.lessons?.map( ( l ) => l.id ) ?? null,
			lesson: round?.lesson.id ?? null, item: round ? round.index : null, items: round?.lesson.items.length ?? 0,
			replays: round?.replays ?? 0, recorded: round?.records.map( ( r ) => r.id ) ?? [], ready: this.ready ?? false,
			listening: this.listener?.listening ?? false, attempt: this.attempt ? { zone: this.attempt.zone, measures: this.attempt.measures } : null,
			audio: this.audio.report(), spoken: [ ...this.spoken ],
		};

	}

	get child() {

		const session = currentSession( { win: this.window } );
		return session?.kind === 'child' ? session.child : null;

	}

	/**
	 * A child already signed in goes to their lessons; anyone else starts at the class code, or,
	 * come by a class's join link (its QR code), at the class's pictures.
	 */
	start() {

		if ( this.child ) return this.showLessons();
		this.showCode();
		const code = joinCodeFromHash( this.window.location.hash );
		if ( code ) this.findClass( code );

	}

	/**
	 * Show `screen`: a fresh element with the child's picture in the corner once signed in, and
	 * the sign that their tries are kept when they are.
	 */
	setScreen( screen, ...content ) {

		this.screen = screen;
		this.closeHead();
		const child = this.child;
		const top = h( 'div', { className: 'cp-top' } );
		if ( child ) {

			this.keepingSign = h( 'p', { className: 'cp-keeping', role: 'status' }, h( 'span', { className: 'cp-keeping-dot', 'aria-hidden': 'true' } ), h( 'span', {}, KEEPING_LABEL ) );
			this.keepingSign.hidden = ! this.audio.enabled;
			top.append( h( 'span', { className: 'cp-me' }, picture( child.avatar, { label: child.avatar } ), h( 'span', {}, child.display_name ) ),
				this.keepingSign, bigButton( 'notme', 'Not me: sign out', () => this.signOut(), { className: 'cp-button cp-small' } ) );

		}

		top.append( grownUpLock( () => this.leave(), () => this.showError( GROWN_UP_LOCK ), this.window ) );
		this.errorLine = h( 'p', { className: 'cp-error', role: 'alert', hidden: '' } );
		this.root.replaceChildren( top, ...content, this.errorLine );

	}

	/**
	 * Say what is wrong, or nothing for ''/null: the words with their picture (`icon`, one of the
	 * practice's pictures, or `picture`, one of the listening page's; plain words get the picture
	 * of asking a grown-up), and aloud.
	 */
	showError( message ) {

		// A message without a picture of its own (the server's words) asks for a grown-up.
		const { text = '', icon = null, picture: drawn = null } = typeof message === 'string' ? { text: message, icon: 'ask-adult' } : ( message ?? {} );
		this.error = text || null;
		if ( this.errorLine ) {

			const art = icon ? picture( icon, { className: 'cp-error-picture' } ) : drawn ? messagePicture( drawn, text, { className: 'cp-error-picture' } ) : null;
			this.errorLine.replaceChildren( ...( art ? [ art ] : [] ), h( 'span', {}, text ) );
			this.errorLine.hidden = ! text;

		}

		if ( text ) this.sayAloud( text );

	}

	/** Say `text` in the head's voice (POST /utterances); the words stay on screen if it cannot. */
	async sayAloud( text ) {

		this.spoken.push( text );
		try {

			const said = await this.api.post( 'utterances', { text, audio: { kind: 'natural' } } );
			if ( said.audio_url ) await new this.window.Audio( said.audio_url ).play();

		} catch {

			// No voice (no espeak-ng, or the browser refused to play): the words and picture remain.

		}

	}

	/** Out of the kiosk, to the start page (a grown-up held the lock). */
	leave() {

		this.window.location.hash = '#/';

	}

	/** Whether the child's tries are kept, read afresh (the sign follows). */
	async readRecordingSwitch() {

		const child = this.child;
		if ( ! child ) return this.audio.reset();
		await this.audio.read( child.id );
		if ( this.keepingSign ) this.keepingSign.hidden = ! this.audio.enabled;

	}

	/** The lessons assigned to the child: one starts at once; several are big buttons. */
	async showLessons() {

		this.round = null;
		this.setScreen( 'lessons' );
		try {

			[ this.lessons ] = await Promise.all( [ this.api.get( 'lessons?limit=100' ).then( ( body ) => body.lessons ?? [] ), this.readRecordingSwitch() ] );

		} catch ( error ) {

			if ( error.status === 401 ) return this.signOut();
			return this.showError( error.message );

		}

		if ( this.lessons.length === 1 ) return this.startLesson( this.lessons[ 0 ].id );
		const list = h( 'div', { className: 'cp-lessons', role: 'group', 'aria-label': 'Lessons' },
			...this.lessons.map( ( lesson, k ) => h( 'button', { type: 'button', className: 'cp-person cp-lesson', 'aria-label': lesson.title, onClick: () => this.startLesson( lesson.id ) },
				h( 'span', { className: 'cp-number', 'aria-hidden': 'true' }, String( k + 1 ) ), h( 'span', { className: 'cp-words' }, lesson.title ) ) ) );
		this.setScreen( 'lessons', this.lessons.length ? list : h( 'div', { className: 'cp-empty' }, picture( 'star', { label: 'Nothing to practise yet' } ) ) );

	}

	async startLesson( id ) {

		let lesson;
		try {

			// The switch read again: a clinician may have changed it since the child signed in.
			[ lesson ] = await Promise.all( [ this.api.get( `lessons/${ id }` ), this.readRecordingSwitch() ] );

		} catch ( error ) {

			return this.showError( error.message );

		}

		this.round = new PracticeRound( lesson, this.child );
		this.showPractice();

	}

	showPractice() {

		this.target = h( 'p', { className: 'cp-target', 'aria-live': 'polite' } );
		this.dots = h( 'div', { className: 'cp-dots', 'aria-hidden': 'true' }, ...this.round.lesson.items.map( () => h( 'span', { className: 'cp-dot' } ) ) );
		this.headBox = h( 'div', { className: 'cp-head' } );
		this.sayButton = h( 'button', { type: 'button', className: 'cp-button cp-say', 'aria-label': 'Say it', 'aria-pressed': 'false', onClick: () => this.sayIt() },
			messagePicture( 'microphone', 'Say it', { className: 'cp-picture' } ) );
		this.verdict = h( 'div', { className: 'cp-verdict', role: 'img', hidden: '' } );
		this.askNote = h( 'div', { className: 'cp-ask', role: 'status', hidden: '' } );
		this.actions = h( 'div', { className: 'cp-actions', role: 'group', 'aria-label': 'Practice' },
			bigButton( 'replay', 'Hear it again', () => this.replay(), { className: 'cp-button cp-replay' } ),
			this.sayButton,
			bigButton( 'tried', 'I tried it', () => this.tried(), { words: 'I tried it', className: 'cp-button cp-tried' } ) );
		this.faces = h( 'div', { className: 'cp-actions cp-faces', role: 'group', 'aria-label': 'How did it go?', hidden: '' },
			...RATINGS.map( ( r ) => bigButton( r.face, r.label, () => this.record( r.rating ), { className: 'cp-button cp-face' } ) ),
			bigButton( 'next', 'Next', () => this.record( null ), { className: 'cp-button cp-face' } ) );
		this.setScreen( 'practice', h( 'div', { className: 'cp-stage' }, this.headBox, this.target, this.dots ), this.askNote, this.verdict, this.actions, this.faces );
		this.speech = new SpeechView( { api: this.api, sayOnLoad: false } ).mount( this.headBox );
		this.presenter = new ItemPresenter( this.speech, { obstacles: () => [ this.target ] } );
		this.presentItem();

	}

	/** The current target: shown, said once, ready for another go. */
	async presentItem() {

		const round = this.round;
		const item = round.item;
		this.ready = false;
		this.showTarget( item );
		[ ...this.dots.children ].forEach( ( dot, k ) => {

			dot.classList.toggle( 'done', k < round.index );
			dot.classList.toggle( 'now', k === round.index );

		} );
		this.actions.hidden = false;
		this.faces.hidden = true;
		this.attempt = null;
		this.verdict.hidden = true;
		const shown = await this.presenter.present( item );
		if ( ! shown || this.round !== round || round.item !== item ) return;
		this.ready = true;
		this.presenter.replay(); // the head says it once by itself

	}

	/** The target: a sound as its picture (a child need not read IPA), anything else as written. */
	async showTarget( item ) {

		this.target.replaceChildren( targetLabel( item ) );
		if ( item.target.kind !== 'phoneme' ) return;
		const code = ( await phonemeInventory() ).get( item.target.text )?.arpabet;
		const pictured = code ? soundPicture( code, { doc: this.window.document } ) : null;
		if ( pictured && this.round?.item === item ) this.target.replaceChildren( pictured );

	}

	replay() {

		if ( ! this.ready ) return;
		this.round.replayed();
		this.presenter.replay();

	}

	tried() {

		this.listener?.stop();
		this.actions.hidden = true;
		this.faces.hidden = false;

	}

	/**
	 * Listen to the child saying the target (the microphone asked for now, on their press), and
	 * show at once, with a face and a colour, how close it was; then the faces to rate it.
	 */
	async sayIt() {

		if ( this.listener?.listening ) return this.listener.stop();
		const round = this.round;
		const item = round.item;
		this.norms ??= await this.api.get( NORMS_URL ).catch( () => null );
		const target = itemTarget( item, this.norms?.groups?.child ?? {} );
		this.listener = new PracticeListener( { win: this.window, group: 'child', onOpen: () => ( this.askNote.hidden = true ) } );
		this.sayButton.setAttribute( 'aria-pressed', 'true' );
		this.showError( '' );
		// Why the browser is about to ask, in a picture and words, until the microphone is open.
		const asking = listenMessage( 'asking' );
		this.askNote.replaceChildren( messagePicture( asking.picture, asking.text, { className: 'cp-picture' } ), h( 'span', {}, asking.text ) );
		this.askNote.hidden = false;
		let summary;
		try {

			summary = await this.listener.listen();

		} catch ( error ) {

			this.askNote.hidden = true;
			this.sayButton.setAttribute( 'aria-pressed', 'false' );
			return this.showError( listenMessage( error instanceof ListenError ? error.kind : 'unsupported' ) );

		}

		this.sayButton.setAttribute( 'aria-pressed', 'false' );
		if ( this.round !== round || round.item !== item ) return;
		const zone = attemptZone( summary, target, this.norms?.groups?.child ?? {}, 'child' );
		this.attempt = { zone, measures: attemptMeasures( summary, zone, target ), recording: this.listener.recording };
		if ( ! summary.vowel && ! summary.fricative ) return this.showError( listenMessage( 'silent' ) );
		this.verdict.replaceChildren( ...( zone ? [ picture( VERDICT_FACES[ zone ], { label: VERDICT_LABELS[ zone ] } ) ] : [] ) );
		this.verdict.dataset.zone = zone ?? '';
		this.verdict.setAttribute( 'aria-label', zone ? VERDICT_LABELS[ zone ] : 'Heard' );
		this.verdict.hidden = ! zone;
		this.tried();

	}

	/** POST /practice for this try, then the next target (or the end); its sound kept after, if it is kept. */
	async record( rating ) {

		const round = this.round;
		const recording = this.attempt?.recording ?? null;
		for ( const button of this.faces.querySelectorAll( 'button' ) ) button.disabled = true;
		let saved;
		try {

			saved = await this.api.post( 'practice', round.record( rating, this.attempt?.measures ) );

		} catch ( error ) {

			this.showError( error.message );
			return;

		} finally {

			for ( const button of this.faces.querySelectorAll( 'button' ) ) button.disabled = false;

		}

		this.keepSound( saved.id, recording );
		if ( this.round !== round ) return;
		this.showError( '' );
		if ( round.next( saved ) ) this.presentItem();
		else this.showDone();

	}

	/** The try's sound, when recording is on; a failure is said, and the try stays saved. */
	async keepSound( recordId, recording ) {

		if ( ! this.audio.enabled ) return;
		// The next target is shown first: resampling and writing the WAV take a moment on a tablet.
		await new Promise( ( resolve ) => setTimeout( resolve, 0 ) );
		try {

			await this.audio.keep( recordId, recording );

		} catch ( error ) {

			this.showError( uploadFailureMessage( error ) );
			if ( this.keepingSign ) this.keepingSign.hidden = ! this.audio.enabled;

		}

	}

	showDone() {

		this.setScreen( 'done', h( 'div', { className: 'cp-empty' }, picture( 'star', { label: 'Well done' } ) ),
			h( 'div', { className: 'cp-actions' },
				bigButton( 'replay', 'Again', () => this.startLesson( this.round.lesson.id ), { className: 'cp-button cp-replay' } ),
				bigButton( 'lessons', 'My lessons', () => this.showLessons(), { className: 'cp-button' } ) ) );

	}

	closeHead() {

		this.listener?.stop();
		this.speech?.unmount();
		this.speech = null;
		this.presenter = null;
		this.ready = false;

	}

	unmount() {

		this.closeHead();
		super.unmount();

	}

}

// The class code, the roster and signing out live in ChildPracticeSignIn.js.
Object.assign( ChildPractice.prototype, signInMethods );

/** Route entry for the view registry. */
export function mountChildPractice( container ) {

	return new ChildPractice().mount( container );

}
