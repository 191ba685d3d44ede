// What a lesson item asks of the head, as plain data (the lesson format of
// server/glasshead/lessons/schema.py and docs/lessons.md): the POST /utterances body that says its
// target with its audio, the views to show, the words in big letters, the speed; and the lesson
// runner's address (#/teach?lesson=ID&item=N) and keys. No DOM: the lesson runner and the child's
// practice turn it into the head's settings, and tests/js/lessonRunner.test.js reads it.

import { utteranceRequest } from '../speak/SpeechControls.js';
import { SPEED_RANGE } from '../speak/speechClock.js';

/** The runner's route. */
export const RUNNER_PATH = '/teach';
/** Slow motion: S plays at this speed, or back at the item's own. */
export const SLOW_SPEED = 0.25;

/** The item's views when the lesson leaves them out (the schema's defaults). */
export const DEFAULT_VIEWS = Object.freeze( {
	skin_transparency: 0.6, cutaway: false, diagram: false, cues: true, labels: false, epg: false,
} );

/** The keys of presentation mode: KeyboardEvent.key -> what it does. */
export const RUNNER_KEYS = Object.freeze( {
	' ': 'play',
	ArrowLeft: 'previous',
	ArrowRight: 'next',
	s: 'slow',
	S: 'slow',
	f: 'fullscreen',
	F: 'fullscreen',
	Escape: 'leave',
} );

/** What a key does in the runner ('play', 'previous', ...), or null: keys typed into a field are its own. */
export function runnerAction( event ) {

	if ( event.ctrlKey || event.metaKey || event.altKey ) return null;
	const tag = event.target?.tagName;
	if ( tag === 'INPUT' || tag === 'TEXTAREA' || tag === 'SELECT' ) return event.key === 'Escape' ? 'leave' : null;
	// Space on a focused button presses the button; the runner's own play is the same action.
	if ( event.key === ' ' && tag === 'BUTTON' ) return null;
	return RUNNER_KEYS[ event.key ] ?? null;

}

/**
 * The POST /utterances body that says `item`'s target with its audio: a phoneme as phonemes,
 * a syllable, word or phrase as text (between slashes: phonemes, as the speech player takes them).
 */
export function itemRequest( item ) {

	const { kind, text } = item.target;
	const audio = { kind: item.audio?.kind ?? 'natural', cutoff_hz: item.audio?.cutoff_hz ?? 1000, channels: item.audio?.channels ?? 4 };
	const typed = kind === 'phoneme' ? `/${ text }/` : text;
	return utteranceRequest( typed, audio );

}

/**
 * The head's settings for `item`: skin transparency in percent (0 opaque), cutaway, the 2D
 * diagram, cues, labels and the EPG card, the speed (SPEED_RANGE) and whether the target is held
 * (static presentation) or spoken.
 */
export function itemSettings( item ) {

	const views = { ...DEFAULT_VIEWS, ...( item.views ?? {} ) };
	const [ low, high ] = SPEED_RANGE;
	return {
		transparency: Math.round( Math.min( Math.max( views.skin_transparency, 0 ), 1 ) * 100 ),
		cutaway: Boolean( views.cutaway ),
		diagram: Boolean( views.diagram ),
		cues: Boolean( views.cues ),
		labels: Boolean( views.labels ),
		epg: Boolean( views.epg ),
		speed: Math.min( Math.max( item.speed ?? 1, low ), high ),
		hold: ( item.presentation ?? 'dynamic' ) === 'static',
	};

}

/** The target as shown in big letters: a phoneme between slashes, anything else as written. */
export function targetLabel( item ) {

	const { kind, text } = item.target;
	return kind === 'phoneme' ? `/${ text }/` : text;

}

/** What kind of target, in a teacher's words. */
export function targetKindLabel( item ) {

	return { phoneme: 'Sound', syllable: 'Syllable', word: 'Word', phrase: 'Phrase' }[ item.target.kind ] ?? item.target.kind;

}

/** The runner's address for item `index` (from 0) of lesson `lessonId`; the list without a lesson. */
export function runnerHref( lessonId = null, index = 0 ) {

	return lessonId === null ? `#${ RUNNER_PATH }` : `#${ RUNNER_PATH }?lesson=${ lessonId }&item=${ index }`;

}

/**
 * The lesson and item of a runner address ('#/teach?lesson=3&item=2' -> { lesson: 3, item: 2 });
 * lesson null for the list, item 0 when missing or not a whole number from 0.
 */
export function parseRunnerHash( hash ) {

	const query = new URLSearchParams( ( hash ?? '' ).split( '?' ).slice( 1 ).join( '?' ) );
	const whole = ( value ) => ( /^\d+$/.test( value ?? '' ) ? Number( value ) : null );
	const lesson = whole( query.get( 'lesson' ) );
	return { lesson: lesson !== null && lesson >= 1 ? lesson : null, item: whole( query.get( 'item' ) ) ?? 0 };

}

/** Item `index` moved by `step`, kept inside a lesson of `count` items. */
export function stepItem( index, step, count ) {

	return Math.min( Math.max( index + step, 0 ), Math.max( count - 1, 0 ) );

}

/** The speed to play at: the item's own, or slow motion (never faster than the item's own). */
export function runnerSpeed( settings, slow ) {

	return slow ? Math.min( SLOW_SPEED, settings.speed ) : settings.speed;

}

/**
 * The listening page for the class to say `item`'s target into the room's microphone, on the
 * projector: children's norms, and the target's vowel or /s/–/ʃ/ when the item is a phoneme.
 */
export function listenHref( item ) {

	const vowel = item?.listen?.measure === 'vowel' ? `&vowel=${ item.listen.vowel }` : '';
	const phoneme = item?.target?.kind === 'phoneme' ? `&phoneme=${ encodeURIComponent( item.target.text ) }` : '';
	return `#/listen?group=child${ vowel || phoneme }`;

}
