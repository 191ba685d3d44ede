// The speech player (route `#/speak`): type text, or choose a phoneme, an open syllable, a word or
// a phrase, and the head says it (POST /utterances). One clock (ui/speak/speechClock.js: the audio's
// currentTime while it plays) drives everything: the head with its cutaway, the 2D diagram, the
// cue layer, the live palatogram, the phoneme strip and the dominance plot. Play, pause, loop,
// scrub, step frame by frame, slow down to 0.1x with the sound in step, or hold the target of one
// phoneme (static mode, GET /phonemes/{symbol}).

import { getAnatomy } from '../../api.js';
import { packTracks, sampleTracks } from '../../core/trackSampling.js';
import { zoomedPose } from '../../scene/viewPresets.js';
import { h } from '../shared/dom.js';
import { loadAnatomy, loadArticulation, loadLandmarks, loadPhonemeTarget } from '../shared/loaders.js';
import { PhonemeStrip } from './PhonemeStrip.js';
import { SpeechPanels } from './SpeechPanels.js';
import { SpeechForm, Transport } from './SpeechControls.js';
import { phoneIndexAt, SpeechClock } from './speechClock.js';
import { View } from '../shared/View.js';
import './speech.css';

/** The voicing cue (0..1) above which the voice is shown sounding. */
const VOICED = 0.5;

export class SpeechView extends View {

	/**
	 * @param {{ api?: object, audio?: HTMLAudioElement, sayOnLoad?: boolean }} options
	 *   `sayOnLoad`: say the example in the box once the head has loaded (the lesson runner and
	 *   the child's practice say their own targets instead); `ready` resolves then, true when loaded
	 */
	constructor( { api, audio = null, sayOnLoad = true } = {} ) {

		super( { api } );
		this.sayOnLoad = sayOnLoad;
		this.ready = new Promise( ( resolve ) => ( this.resolveReady = resolve ) );
		/** Skin transparency when the skin is see-through, percent (a lesson item sets its own). */
		this.state = { loaded: false, error: null, skin: false, transparency: 70, cutaway: true, hold: null };
		this.utterance = null;
		this.audio = audio ?? Object.assign( document.createElement( 'audio' ), { preload: 'auto' } );
		this.clock = new SpeechClock( { audio: this.audio } );
		this.phone = - 1;
		this.requests = 0;

	}

	mount( container ) {

		this.form = new SpeechForm( { onSay: ( body ) => this.say( body ) } );
		this.transport = new Transport( {
			onPlay: () => this.togglePlay(),
			onLoop: () => this.setLoop( ! this.clock.loop ),
			onStep: ( frames ) => this.step( frames ),
			onScrub: ( frame ) => this.seek( frame / this.clock.rateHz ),
			onSpeed: ( speed ) => this.setSpeed( speed ),
			onHold: () => this.setHold( this.state.hold === null ),
		} );
		this.strip = new PhonemeStrip( { onChoose: ( index ) => this.goToPhone( index ) } );
		this.stage = h( 'div', { className: 'stage sp-stage' } );
		this.viewButtons = new Map( [ [ 'skin', 'See-through skin' ], [ 'cutaway', 'Cutaway' ] ].map( ( [ key, label ] ) => [ key, h( 'button', {
			type: 'button', className: 'toggle', 'aria-pressed': String( this.state[ key ] ), onClick: () => this.toggle( key ),
		}, label ) ] ) );
		this.side = h( 'aside', { className: 'sp-side', 'aria-label': 'Views' }, h( 'div', { className: 'sp-buttons', role: 'group', 'aria-label': 'Show' }, ...this.viewButtons.values() ) );
		this.left = h( 'div', { className: 'sp-left' }, h( 'h1', { className: 'title' }, 'Say it' ), this.form.element );
		this.bottom = h( 'div', { className: 'sp-bottom' }, this.transport.element, this.strip.element );
		this.attach( container, h( 'div', { className: 'speech' }, this.left, this.stage, this.side, this.bottom ) );
		this.registerDebugFields();
		this.form.showStatus( 'Loading the head…' );
		this.form.setBusy( true );

		if ( ! this.mountStage( this.stage ) ) return this;
		this.load();
		return this;

	}

	registerDebugFields() {

		this.debugFields( {
			loaded: () => this.state.loaded,
			error: () => this.state.error,
			...this.stageDebugFields(),
			speech: () => this.report(),
		} );

	}

	/** What window.glasshead.speech reports. */
	report() {

		const u = this.utterance;
		const clock = this.clock;
		// The clock as it is now, between frames too (a software-rendered page draws seldom): its
		// time and phone; `shownTime` is the time the head, the strip and the palatogram show.
		const time = u ? clock.update() : 0;
		const index = u ? phoneIndexAt( u.phones, time ) : - 1;
		const phone = index >= 0 ? u.phones[ index ] : null;
		return {
			id: u?.id ?? null, busy: this.busy ?? false, requests: this.requests,
			duration: u?.duration_s ?? 0, rateHz: clock.rateHz, frames: u?.n_frames ?? 0,
			playing: clock.playing, time, shownTime: this.shownTime ?? 0, frame: clock.frame, speed: clock.speed, loop: clock.loop,
			source: clock.source, audioUrl: u?.audio_url ?? null, voice: u?.voice ?? null, audioKind: u?.audio?.kind ?? null,
			audioTime: clock.hasAudio ? this.audio.currentTime : null, audioPaused: clock.hasAudio ? this.audio.paused : null,
			audioRate: clock.hasAudio ? this.audio.playbackRate : null, preservesPitch: clock.hasAudio ? this.audio.preservesPitch : null,
			audioError: clock.audioError, phoneIndex: index,
			phone: phone ? { symbol: phone.symbol, ipa: phone.ipa, word: phone.word, start_s: phone.start_s, end_s: phone.end_s } : null,
			phones: u ? u.phones.map( ( p ) => ( { symbol: p.symbol, ipa: p.ipa, start_s: p.start_s, end_s: p.end_s } ) ) : [],
			hold: this.state.hold, voiced: this.panels?.voiced ?? null, dominance: this.dominance?.report() ?? null, warnings: u?.warnings ?? [],
		};

	}

	async load() {

		try {

			const anatomy = await getAnatomy( this.api );
			await loadAnatomy( this.head, anatomy.meshes, { api: this.api, onProgress: ( n, total ) => this.form.showStatus( `Loading the head: ${ n } of ${ total }` ) } );
			if ( ! this.viewer ) return;
			this.articulation = await loadArticulation( this.head, this.viewer, { api: this.api } );
			this.landmarks = await loadLandmarks( { api: this.api } ).catch( () => null );

		} catch ( error ) {

			this.fail( error.message );
			return;

		}

		if ( ! this.viewer ) return this.articulation.dispose();
		this.onUnmount( () => this.articulation.dispose() );
		this.epg = await ( await import( '../shared/HeadEpg.js' ) ).attachHeadEpg( this, { api: this.api } );
		if ( ! this.viewer ) return;
		this.panels = new SpeechPanels( { head: this.head, viewer: this.viewer, articulation: this.articulation, landmarks: this.landmarks, api: this.api } );
		this.onUnmount( () => this.panels.dispose() );
		this.dominance = this.panels.dominance;
		this.side.append( ...this.panels.sections );
		this.onUnmount( this.viewer.onFrame( () => this.tick() ) );
		this.apply();
		this.viewer.flyTo( zoomedPose( 'profile', 1, this.viewer.camera.fov, this.viewer.aspect ), 0 );
		this.state.loaded = true;
		this.form.setBusy( false );
		this.form.showStatus( '' );
		if ( this.sayOnLoad ) this.form.submit(); // the example in the box, ready to play
		this.resolveReady( true );

	}

	/** Ask the server for an utterance and make it the one played. */
	async say( body ) {

		if ( ! this.state.loaded ) return;
		const request = ++ this.requests;
		this.busy = true;
		this.form.setBusy( true );
		this.form.showStatus( 'Preparing the speech…' );
		let utterance;
		try {

			utterance = await this.api.post( 'utterances', body );

		} catch ( error ) {

			if ( request === this.requests ) {

				this.busy = false;
				this.form.setBusy( false );
				this.form.showStatus( '' );
				this.form.showError( error.message );

			}

			return;

		}

		if ( request !== this.requests || ! this.viewer ) return; // a newer request, or unmounted
		this.busy = false;
		this.form.setBusy( false );
		this.setUtterance( utterance );

	}

	setUtterance( utterance ) {

		const state = this.articulation.state;
		this.clock.pause();
		this.utterance = utterance;
		this.packed = packTracks( utterance.tracks, utterance.rate_hz, state.names, state );
		if ( utterance.audio_url ) this.audio.src = utterance.audio_url;
		else this.audio.removeAttribute( 'src' );
		this.clock.load( utterance.duration_s, utterance.rate_hz, Boolean( utterance.audio_url ) );
		this.state.hold = null;
		this.transport.setFrames( utterance.n_frames );
		this.transport.setEnabled( true );
		this.strip.set( utterance );
		this.dominance.set( utterance );
		const said = utterance.phones.filter( ( p ) => p.symbol !== 'sil' ).map( ( p ) => p.ipa ?? p.symbol ).join( ' ' );
		this.form.showStatus( `/${ said }/, ${ utterance.duration_s.toFixed( 2 ) } s${ utterance.voice ? `, voice: ${ utterance.voice }` : ', no sound' }` );
		this.form.showError( ( utterance.warnings ?? [] ).join( ' ' ) );
		this.show( 0 );

	}

	/**
	 * Every frame of the 3D view: the clock's time, shown when it moved (also the end, once).
	 * Returns whether there is something new to draw.
	 */
	tick() {

		if ( ! this.utterance ) return false;
		const t = this.clock.update();
		if ( t === this.shownTime ) return false;
		this.show( t );
		return true;

	}

	/** Everything at time t: the parameters (unless a target is held), the strip, the controls. */
	show( t ) {

		const u = this.utterance;
		if ( ! u ) return;
		this.shownTime = t;
		// The phone and the voicing first: the articulation's update draws the cues, whose air
		// is this phone's (a phone's first frame showed the phone before it).
		this.phone = phoneIndexAt( u.phones, t );
		this.panels.phoneSymbol = u.phones[ this.phone ]?.symbol ?? null;
		// The voice buzzes at the glottis only while the utterance is voiced (its voicing cue).
		const voicing = u.cues?.voicing;
		this.panels.voiced = voicing ? voicing[ Math.min( Math.max( Math.round( t * u.rate_hz ), 0 ), voicing.length - 1 ) ] > VOICED : true;
		const state = this.articulation.state;
		if ( this.state.hold === null ) {

			sampleTracks( this.packed, t, state.values );
			state.touch();
			this.articulation.update(); // now, so that what window.glasshead reads is this time's

		}

		this.strip.show( t, this.phone );
		this.dominance.show( t );
		this.transport.show( { playing: this.clock.playing, loop: this.clock.loop, hold: this.state.hold !== null, frame: this.clock.frame, time: t, speed: this.clock.speed } );
		this.viewer.requestRender();

	}

	togglePlay() {

		if ( this.clock.playing ) this.clock.pause();
		else {

			if ( this.state.hold !== null ) this.state.hold = null;
			this.clock.play();

		}

		this.show( this.clock.time );

	}

	seek( t ) {

		this.show( this.clock.seek( t ) );
		if ( this.state.hold !== null ) this.holdCurrent();

	}

	step( frames ) {

		this.show( this.clock.step( frames ) );
		if ( this.state.hold !== null ) this.holdCurrent();

	}

	setSpeed( speed ) {

		this.clock.setSpeed( speed );
		this.show( this.clock.time );

	}

	setLoop( on ) {

		this.clock.setLoop( on );
		this.show( this.clock.time );

	}

	/** Go to the middle of phone `index`; holding, hold its target. */
	goToPhone( index ) {

		const phone = this.utterance?.phones[ index ];
		if ( ! phone ) return;
		this.clock.pause();
		this.seek( ( phone.start_s + phone.end_s ) / 2 );

	}

	/** Static mode: freeze on the target of the current phoneme (on), or back to the tracks. */
	setHold( on ) {

		this.clock.pause();
		if ( on ) this.holdCurrent();
		else {

			this.state.hold = null;
			this.show( this.clock.time );

		}

	}

	/** Hold the current phone's target (GET /phonemes/{symbol}); a pause holds the rest pose. */
	async holdCurrent() {

		const phone = this.utterance?.phones[ this.phone ];
		if ( ! phone ) return;
		const symbol = phone.symbol;
		this.state.hold = symbol;
		const state = this.articulation.state;
		let params = {};
		if ( symbol !== 'sil' ) {

			try {

				params = ( await loadPhonemeTarget( symbol, { api: this.api } ) ).params ?? {};

			} catch ( error ) {

				this.form.showError( error.message );
				return;

			}

		}

		if ( this.state.hold !== symbol || ! this.viewer ) return; // moved on meanwhile
		const known = Object.fromEntries( Object.entries( params ).filter( ( [ name ] ) => state.index.has( name ) ).map( ( [ name, value ] ) => {

			const p = state.definition( name );
			return [ name, Math.min( Math.max( value, p.min ), p.max ) ];

		} ) );
		state.assign( known );
		this.articulation.update();
		this.form.showStatus( `Holding the target of /${ phone.ipa ?? symbol }/` );
		this.show( this.clock.time );

	}

	toggle( key ) {

		this.state[ key ] = ! this.state[ key ];
		this.apply();

	}

	apply() {

		this.head.setTransparency( this.state.skin ? this.state.transparency : 0 );
		this.head.setCutaway( this.state.cutaway );
		for ( const [ key, button ] of this.viewButtons ) button.setAttribute( 'aria-pressed', String( this.state[ key ] ) );
		this.viewer.requestRender();

	}

	fail( message ) {

		this.state.error = message;
		this.resolveReady( false );
		this.form.showStatus( '' );
		this.form.showError( message );
		console.error( `Glasshead: ${ message }` );

	}

	unmount() {

		this.resolveReady( false );
		this.clock.pause();
		this.audio.removeAttribute( 'src' );
		super.unmount();

	}

}

/** Route entry for the view registry. */
export function mountSpeechView( container ) {

	return new SpeechView().mount( container );

}
