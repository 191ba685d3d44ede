// What a lesson item asks of the head, as plain data (the lesson format of
// server/glasshead/lessons/schema.py and docs/lessons.md): the POST /utterances body that says its
// target with its audio, the views to show, the words in big letters, the speed; and the lesson
// runner's address (#/teach?lesson=ID&item=N) and keys. No DOM: the lesson runner and the child's
// practice turn it into the head's settings, and tests/js/lessonRunner.test.js reads it.

import { LESSON_VIEW_DEFAULTS, LESSON_ZOOM_RANGE } from '../../core/constants.js';
import { utteranceRequest } from '../speak/SpeechControls.js';
import { SPEED_RANGE } from '../speak/speechClock.js';

/** The runner's route. */
export const RUNNER_PATH = '/teach';
/** Slow motion: S plays at this speed, or back at the item's own. */
export const SLOW_SPEED = 0.25;

/** The item's views when the lesson leaves them out (the schema's defaults). */
export const DEFAULT_VIEWS = LESSON_VIEW_DEFAULTS;

/** How long a sound that can be held is held when it is said alone, s (600 to 800 ms to copy). */
export const HELD_S = 0.7;
/** The silence before and after a held sound, s. */
const HELD_QUIET_S = 0.2;
/** Manners of sounds that cannot be held: a burst, said in a syllable or repeated instead. */
const UNHELD_MANNERS = new Set( [ 'stop', 'affricate' ] );
/** The vowel a syllable is made with: open, central to the mouth, where every place shows. */
const SYLLABLE_VOWEL = 'ɑ';

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
	// An open dialog (the class code shown to the class) keeps its keys: Esc closes it.
	if ( event.target?.closest?.( 'dialog' ) ) return null;
	const tag = event.target?.tagName;
	if ( tag === 'INPUT' || tag === 'TEXTAREA' || tag === 'SELECT' ) return event.key === 'Escape' ? 'leave' : null;
	// Space on a focused button presses the button; the runner's own play is the same action.
	if ( event.key === ' ' && tag === 'BUTTON' ) return null;
	return RUNNER_KEYS[ event.key ] ?? null;

}

/**
 * How a phoneme target is said (the item's `said_as`, or by its sound when it leaves it out):
 * 'alone' for a sound that can be held, 'syllable' for a stop or an affricate. `phoneme` is its
 * GET /phonemes entry (its `manner`), or undefined when the inventory is not known.
 */
export function saidAs( item, phoneme ) {

	if ( item.said_as ) return item.said_as;
	return UNHELD_MANNERS.has( phoneme?.manner ) ? 'syllable' : 'alone';

}

/**
 * The POST /utterances body that says `item`'s target with its audio: a syllable, word or
 * phrase as text (between slashes: phonemes, as the speech player takes them); a phoneme held
 * HELD_S between silences (as timed phones, which the server stretches keeping its pitch), in a
 * syllable before /ɑ/, three times (t-t-t), or alone as the voice says it (a stop alone: its
 * burst). `inventory` maps a symbol (IPA or ARPAbet) to its GET /phonemes entry.
 */
export function itemRequest( item, inventory = new Map() ) {

	const { kind, text } = item.target;
	const audio = { kind: item.audio?.kind ?? 'natural', cutoff_hz: item.audio?.cutoff_hz ?? 1000, channels: item.audio?.channels ?? 4 };
	if ( kind !== 'phoneme' ) return utteranceRequest( text, audio );
	const phoneme = inventory.get( text );
	const how = saidAs( item, phoneme );
	if ( how === 'syllable' ) return utteranceRequest( `/${ text } ˈ${ SYLLABLE_VOWEL }/`, audio );
	if ( how === 'repeated' ) return utteranceRequest( `/${ [ 1, 2, 3 ].map( () => `${ text } ə` ).join( ' sil ' ) }/`, audio );
	const request = utteranceRequest( `/${ text }/`, audio );
	if ( ! phoneme || UNHELD_MANNERS.has( phoneme.manner ) ) return request;
	const { phonemes, ...rest } = request;
	const ms = ( seconds ) => Math.round( seconds * 1000 ) / 1000; // 0.9, not 0.8999999999999999
	const end = ms( HELD_QUIET_S + HELD_S );
	return { phones: [
		{ symbol: 'sil', start_s: 0, end_s: HELD_QUIET_S },
		{ symbol: phonemes, start_s: HELD_QUIET_S, end_s: end },
		{ symbol: 'sil', start_s: end, end_s: ms( end + HELD_QUIET_S ) },
	], ...rest };

}

/** The inventory as itemRequest reads it: each GET /phonemes entry under its IPA and ARPAbet. */
export function phonemeIndex( phonemes ) {

	const index = new Map();
	for ( const entry of phonemes ?? [] ) {

		index.set( entry.ipa, entry );
		index.set( entry.arpabet, entry );
		index.set( entry.arpabet.toLowerCase(), entry );

	}

	return index;

}

/**
 * The head's settings for `item`: skin transparency in percent (0 opaque), cutaway, the 2D
 * diagram, cues, the labels (true, false or the names to show), the EPG card, the camera's view
 * and zoom, the speed (SPEED_RANGE) and whether the target is held (static presentation) or
 * spoken.
 */
export function itemSettings( item ) {

	const views = { ...DEFAULT_VIEWS, ...( item.views ?? {} ) };
	const [ low, high ] = SPEED_RANGE;
	const [ closest, farthest ] = [ LESSON_ZOOM_RANGE[ 0 ], LESSON_ZOOM_RANGE[ 1 ] ];
	return {
		transparency: Math.round( Math.min( Math.max( views.skin_transparency, 0 ), 1 ) * 100 ),
		cutaway: Boolean( views.cutaway ),
		diagram: Boolean( views.diagram ),
		cues: Boolean( views.cues ),
		labels: Array.isArray( views.labels ) ? [ ...views.labels ] : Boolean( views.labels ),
		epg: Boolean( views.epg ),
		camera: views.camera,
		zoom: Math.min( Math.max( Number( views.zoom ) || 1, closest ), farthest ),
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

/**
 * The runner's address for item `index` (from 0) of lesson `lessonId`; the list without a
 * lesson. `present`: the lesson opens straight in presentation mode (the list's Present).
 */
export function runnerHref( lessonId = null, index = 0, { present = false } = {} ) {

	if ( lessonId === null ) return `#${ RUNNER_PATH }`;
	return `#${ RUNNER_PATH }?lesson=${ lessonId }&item=${ index }${ present ? '&present=1' : '' }`;

}

/**
 * The lesson and item of a runner address ('#/teach?lesson=3&item=2' -> { lesson: 3, item: 2,
 * present: false }); lesson null for the list, item 0 when missing or not a whole number from 0;
 * present when the address asks for presentation mode.
 */
export function parseRunnerHash( hash ) {

	const query = new URLSearchParams( ( hash ?? '' ).split( '?' ).slice( 1 ).join( '?' ) );
	const whole = ( value ) => ( /^\d+$/.test( value ?? '' ) ? Number( value ) : null );
	const lesson = whole( query.get( 'lesson' ) );
	return { lesson: lesson !== null && lesson >= 1 ? lesson : null, item: whole( query.get( 'item' ) ) ?? 0, present: query.get( 'present' ) === '1' };

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
