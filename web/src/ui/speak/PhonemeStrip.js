// The phoneme strip under the head: the utterance's words above its phones, each phone as wide as
// it lasts, the current one lit, and a playhead at the clock's time. Touching a phone goes to it
// (its middle); the player decides what that means (in static mode, hold its target).
//
//   const strip = new PhonemeStrip( { onChoose: ( index ) => player.goToPhone( index ) } );
//   strip.set( utterance );        // a POST /utterances answer: phones, words, duration_s
//   strip.show( t, index );        // every frame: the time and the current phone

import { h } from '../shared/dom.js';

/** What a pause is called in the answer, and how the strip shows it. */
const PAUSE = 'sil';
const PAUSE_LABEL = '·';

export class PhonemeStrip {

	/** @param {{ onChoose?: ( index: number ) => void }} handlers */
	constructor( { onChoose = () => {} } = {} ) {

		this.onChoose = onChoose;
		this.phones = [];
		this.duration = 0;
		this.current = - 1;
		this.words = h( 'div', { className: 'sp-words', 'aria-hidden': 'true' } );
		this.row = h( 'div', { className: 'sp-phones', role: 'group', 'aria-label': 'Phonemes' } );
		this.playhead = h( 'div', { className: 'sp-playhead', 'aria-hidden': 'true' } );
		this.element = h( 'div', { className: 'sp-strip' }, this.words, this.row, this.playhead );
		this.buttons = [];

	}

	/** Lay out the phones and words of `utterance`. */
	set( utterance ) {

		const phones = utterance?.phones ?? [];
		this.phones = phones;
		this.duration = utterance?.duration_s ?? 0;
		this.current = - 1;
		const span = ( start ) => `${ 100 * start / this.duration }%`;
		const width = ( start, end ) => `${ 100 * ( end - start ) / this.duration }%`;
		this.buttons = phones.map( ( phone, index ) => {

			const pause = phone.symbol === PAUSE;
			const label = pause ? PAUSE_LABEL : phone.ipa ?? phone.symbol;
			const button = h( 'button', {
				type: 'button', className: pause ? 'sp-phone sp-pause' : 'sp-phone',
				'aria-label': pause ? `pause, ${ formatTime( phone.start_s ) }` : `/${ label }/ in ${ phone.word ?? 'the phrase' }, ${ formatTime( phone.start_s ) }`,
				title: pause ? 'pause' : `/${ label }/ (${ phone.symbol })${ phone.word ? ` in "${ phone.word }"` : '' }`,
				onClick: () => this.onChoose( index ),
			}, label );
			button.style.left = span( phone.start_s );
			button.style.width = width( phone.start_s, phone.end_s );
			return button;

		} );
		this.row.replaceChildren( ...this.buttons );
		this.words.replaceChildren( ...( utterance?.words ?? [] ).map( ( word ) => {

			const element = h( 'span', { className: 'sp-word' }, word.text );
			element.style.left = span( word.start_s );
			element.style.width = width( word.start_s, word.end_s );
			return element;

		} ) );
		this.show( 0, phones.length ? 0 : - 1 );

	}

	/** Light phone `index` and put the playhead at `t` seconds. */
	show( t, index ) {

		if ( index !== this.current ) {

			this.buttons[ this.current ]?.removeAttribute( 'aria-current' );
			this.buttons[ index ]?.setAttribute( 'aria-current', 'true' );
			this.current = index;

		}

		const fraction = this.duration > 0 ? Math.min( Math.max( t / this.duration, 0 ), 1 ) : 0;
		this.playhead.style.left = `${ 100 * fraction }%`;

	}

}

/** Seconds as "1.23 s". */
export function formatTime( seconds ) {

	return `${ seconds.toFixed( 2 ) } s`;

}
