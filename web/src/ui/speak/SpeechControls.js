// The speech player's controls: what to say (free text or an example of each size: phoneme, open
// syllable, word, phrase) with the audio to hear, and the transport (play, pause, loop, frame
// steps, the time slider, slow motion and holding a phoneme's target). Big targets (44 px and
// more) for tablets and projectors; every control has an accessible name. Plain DOM: the player
// is told through the handlers, and tells back through the set* methods.

import { h } from '../shared/dom.js';
import { SPEED_RANGE } from './speechClock.js';

/** Examples by size. Between slashes: phonemes (ARPAbet or IPA, spaces between), else text. */
export const EXAMPLES = Object.freeze( [
	[ 'Phoneme', [ '/T/', '/K/', '/M/', '/S/', '/UW/', '/IY/' ] ],
	[ 'Open syllable', [ '/M AA/', '/T IY/', '/K IY/', '/K UW/', '/N OW/', '/S UW/' ] ],
	[ 'Word', [ 'stew', 'key', 'map', 'king', 'sunny' ] ],
	[ 'Phrase', [ 'Tom and Kate bring a map.', 'Put the cat on the mat.', 'Good morning, how are you?' ] ],
] );

export const DEFAULT_TEXT = 'Tom and Kate bring a map.';

/** The audio kinds of POST /utterances, as a teacher would name them. */
export const AUDIO_KINDS = Object.freeze( [
	[ 'natural', 'Natural voice' ],
	[ 'lowpass', 'Low-pass (hearing loss)' ],
	[ 'vocoded', 'Vocoded (cochlear implant)' ],
	[ 'none', 'No sound' ],
	[ 'articulatory', 'Articulatory (VocalTractLab)' ],
	[ 'tract', 'The head\'s own tract' ],
] );

/**
 * The request body for what was typed: `/…/` is phonemes, anything else text; null when empty.
 * @param {string} typed
 * @param {{ kind: string, cutoff_hz?: number, channels?: number }} audio
 */
export function utteranceRequest( typed, audio ) {

	const text = ( typed ?? '' ).trim();
	if ( text === '' ) return null;
	const phonemes = /^\/(.+)\/$/.exec( text );
	const options = { kind: audio.kind };
	if ( audio.kind === 'lowpass' ) options.cutoff_hz = audio.cutoff_hz;
	if ( audio.kind === 'vocoded' ) options.channels = audio.channels;
	const body = phonemes ? { phonemes: phonemes[ 1 ].trim() } : { text };
	return { ...body, audio: options, dominance: true };

}

export class SpeechForm {

	/** @param {{ onSay: ( body: object ) => void }} handlers */
	constructor( { onSay } ) {

		this.onSay = onSay;
		this.text = h( 'textarea', { id: 'sp-text', className: 'sp-text', rows: '2', maxlength: '500', 'aria-label': 'Text to say', spellcheck: 'false' } );
		this.text.value = DEFAULT_TEXT;
		this.examples = h( 'select', { id: 'sp-examples', className: 'sp-select', 'aria-label': 'Examples', onChange: () => this.choose() },
			h( 'option', { value: '' }, 'Choose an example…' ),
			...EXAMPLES.map( ( [ size, items ] ) => h( 'optgroup', { label: size }, ...items.map( ( item ) => h( 'option', { value: item }, item ) ) ) ),
		);
		this.kind = h( 'select', { id: 'sp-audio', className: 'sp-select', 'aria-label': 'Audio', onChange: () => this.showAudioOptions() },
			...AUDIO_KINDS.map( ( [ value, label ] ) => h( 'option', { value }, label ) ) );
		this.cutoff = h( 'input', { type: 'number', id: 'sp-cutoff', className: 'sp-number', min: '100', max: '8000', step: '50', value: '1000', 'aria-label': 'Cut-off (Hz)' } );
		this.channels = h( 'input', { type: 'number', id: 'sp-channels', className: 'sp-number', min: '1', max: '16', step: '1', value: '4', 'aria-label': 'Channels' } );
		this.cutoffRow = h( 'label', { className: 'sp-inline', for: 'sp-cutoff' }, 'Cut-off, Hz', this.cutoff );
		this.channelsRow = h( 'label', { className: 'sp-inline', for: 'sp-channels' }, 'Channels', this.channels );
		this.say = h( 'button', { type: 'submit', className: 'sp-say' }, 'Say it' );
		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' } );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
		this.element = h( 'form', { className: 'sp-form', 'aria-label': 'What to say', onSubmit: ( event ) => {

			event.preventDefault();
			this.submit();

		} },
		h( 'label', { className: 'field-label', for: 'sp-text' }, 'Type, or choose an example' ),
		this.text, this.examples,
		h( 'label', { className: 'field-label', for: 'sp-audio' }, 'Sound' ),
		this.kind, this.cutoffRow, this.channelsRow,
		this.say, this.status, this.error );
		this.text.addEventListener( 'keydown', ( event ) => {

			if ( event.key === 'Enter' && ! event.shiftKey ) {

				event.preventDefault();
				this.submit();

			}

		} );
		this.showAudioOptions();

	}

	/** What the audio choice asks of the server. */
	audio() {

		return { kind: this.kind.value, cutoff_hz: Number( this.cutoff.value ), channels: Number( this.channels.value ) };

	}

	choose() {

		if ( ! this.examples.value ) return;
		this.text.value = this.examples.value;
		this.examples.value = '';
		this.submit();

	}

	showAudioOptions() {

		this.cutoffRow.hidden = this.kind.value !== 'lowpass';
		this.channelsRow.hidden = this.kind.value !== 'vocoded';

	}

	submit() {

		const body = utteranceRequest( this.text.value, this.audio() );
		if ( ! body ) return this.showError( 'Type something to say first.' );
		this.showError( '' );
		this.onSay( body );

	}

	setBusy( busy ) {

		this.say.disabled = busy;
		this.say.textContent = busy ? 'Preparing…' : 'Say it';

	}

	showStatus( text ) {

		this.status.textContent = text;

	}

	showError( message ) {

		this.error.textContent = message;
		this.error.hidden = ! message;

	}

}

export class Transport {

	/**
	 * @param {{ onPlay: Function, onLoop: Function, onStep: ( frames: number ) => void,
	 *   onScrub: ( frame: number ) => void, onSpeed: ( speed: number ) => void, onHold: Function }} handlers
	 */
	constructor( handlers ) {

		const [ low, high ] = SPEED_RANGE;
		this.play = h( 'button', { type: 'button', className: 'sp-play', onClick: () => handlers.onPlay() }, 'Play' );
		this.loop = h( 'button', { type: 'button', className: 'toggle', 'aria-pressed': 'false', onClick: () => handlers.onLoop() }, 'Loop' );
		this.back = h( 'button', { type: 'button', 'aria-label': 'Previous frame', title: 'Previous frame', onClick: () => handlers.onStep( - 1 ) }, '◀︎ Frame' );
		this.forward = h( 'button', { type: 'button', 'aria-label': 'Next frame', title: 'Next frame', onClick: () => handlers.onStep( 1 ) }, 'Frame ▶︎' );
		this.hold = h( 'button', { type: 'button', className: 'toggle', 'aria-pressed': 'false', title: 'Freeze on the target of the current phoneme', onClick: () => handlers.onHold() }, 'Hold target' );
		this.scrub = h( 'input', { type: 'range', className: 'slider sp-scrub', min: '0', max: '0', step: '1', value: '0', 'aria-label': 'Time', onInput: () => handlers.onScrub( Number( this.scrub.value ) ) } );
		this.time = h( 'output', { className: 'sp-time', 'aria-live': 'off' }, '0.00 s' );
		this.speed = h( 'input', { type: 'range', className: 'slider sp-speed', min: String( low ), max: String( high ), step: '0.05', value: String( high ), 'aria-label': 'Speed', onInput: () => handlers.onSpeed( Number( this.speed.value ) ) } );
		this.speedValue = h( 'output', { className: 'slider-value' }, '1×' );
		this.element = h( 'div', { className: 'sp-transport', role: 'group', 'aria-label': 'Player' },
			this.play, this.back, this.forward,
			h( 'div', { className: 'sp-scrub-row' }, this.scrub, this.time ),
			h( 'label', { className: 'sp-inline sp-speed-row' }, 'Speed', this.speed, this.speedValue ),
			this.loop, this.hold );
		this.setEnabled( false );

	}

	setEnabled( on ) {

		for ( const control of [ this.play, this.loop, this.back, this.forward, this.hold, this.scrub, this.speed ] ) control.disabled = ! on;

	}

	/** The frames of a new utterance. */
	setFrames( count ) {

		this.scrub.max = String( Math.max( 0, count - 1 ) );

	}

	show( { playing, loop, hold, frame, time, speed } ) {

		this.play.textContent = playing ? 'Pause' : 'Play';
		this.loop.setAttribute( 'aria-pressed', String( loop ) );
		this.hold.setAttribute( 'aria-pressed', String( hold ) );
		this.scrub.value = String( frame );
		this.time.textContent = `${ time.toFixed( 2 ) } s`;
		this.speed.value = String( speed );
		this.speedValue.textContent = `${ speed.toFixed( 2 ).replace( /\.?0+$/, '' ) }×`;

	}

}
