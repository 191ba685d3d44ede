// The author's lesson editor as plain data: the draft of a lesson being written, its items added,
// moved, changed and removed, the body a save sends, the server's 422 turned into messages beside
// the fields they name, a lesson file read for an import, and the editor's address
// (#/author, #/author?lesson=ID, #/author?lesson=new). No DOM and no requests: LessonEditor.js
// shows it and tests/js/lessonEditor.test.js reads it. The format is the server's
// (server/glasshead/lessons/schema.py, docs/lessons.md).

import { CAMERA_VIEWS, LABEL_NAMES, LESSON_VIEW_DEFAULTS, LESSON_ZOOM_RANGE, VOWEL_NORMS_VOWELS } from '../../core/constants.js';

/** The editor's route. */
export const AUTHOR_PATH = '/author';
/** The lesson format's version, as exports carry it. */
export const FORMAT_VERSION = 1;
/** Most items in a lesson (the schema's MAX_ITEMS). */
export const MAX_ITEMS = 200;

export const TARGET_KINDS = Object.freeze( [
	Object.freeze( { value: 'phoneme', label: 'Sound (phoneme)' } ),
	Object.freeze( { value: 'syllable', label: 'Open syllable' } ),
	Object.freeze( { value: 'word', label: 'Word' } ),
	Object.freeze( { value: 'phrase', label: 'Phrase' } ),
] );
/** Each vowel of the norms in IPA and the /hVd/ word it is said in. */
const VOWEL_WORDS = Object.freeze( {
	iy: [ 'i', 'heed' ], ih: [ 'ɪ', 'hid' ], eh: [ 'ɛ', 'head' ], ae: [ 'æ', 'had' ], ah: [ 'ʌ', 'hud' ],
	aa: [ 'ɑ', 'hod' ], ao: [ 'ɔ', 'hawed' ], uh: [ 'ʊ', 'hood' ], uw: [ 'u', 'who’d' ], er: [ 'ɝ', 'heard' ],
} );

/** What a try at an item can be measured on (the lesson format's `listen`), as the editor offers it. */
export const LISTEN_CHOICES = Object.freeze( [
	Object.freeze( { value: '', label: 'Not measured (or by its phoneme)' } ),
	...VOWEL_NORMS_VOWELS.map( ( code ) => Object.freeze( { value: `vowel:${ code }`, label: `The vowel /${ VOWEL_WORDS[ code ][ 0 ] }/ (as in ${ VOWEL_WORDS[ code ][ 1 ] })` } ) ),
	Object.freeze( { value: 'sibilant:s', label: 'The hiss of /s/' } ),
	Object.freeze( { value: 'sibilant:sh', label: 'The hiss of /ʃ/' } ),
	Object.freeze( { value: 'rhotic', label: 'The F3 of /r/' } ),
] );

/** The choice (LISTEN_CHOICES' value) of an item's `listen`. */
export function listenChoice( listen ) {

	if ( ! listen ) return '';
	if ( listen.measure === 'vowel' ) return `vowel:${ listen.vowel }`;
	if ( listen.measure === 'sibilant' ) return `sibilant:${ listen.sound }`;
	return listen.measure ?? '';

}

/** The `listen` of a choice, keeping the zone `previous` set when the measure stays the same. */
export function listenFromChoice( choice, previous = null ) {

	const [ measure, what ] = String( choice ?? '' ).split( ':' );
	const keep = previous?.measure === measure ? previous : {};
	if ( measure === 'vowel' ) return { ...( keep.within_sd ? { within_sd: keep.within_sd } : {} ), measure, vowel: what };
	if ( measure === 'sibilant' ) return { ...( keep.from_share ? { from_share: keep.from_share } : {} ), measure, sound: what };
	if ( measure === 'rhotic' ) return { ...( keep.f3_below_hz ? { f3_below_hz: keep.f3_below_hz } : {} ), measure };
	return null;

}

export const PRESENTATIONS = Object.freeze( [
	Object.freeze( { value: 'dynamic', label: 'Dynamic: spoken' } ),
	Object.freeze( { value: 'static', label: 'Static: the target held' } ),
] );
export const AUDIO_KINDS = Object.freeze( [
	Object.freeze( { value: 'natural', label: 'Natural' } ),
	Object.freeze( { value: 'lowpass', label: 'Low-pass (muffled)' } ),
	Object.freeze( { value: 'vocoded', label: 'Vocoded' } ),
	Object.freeze( { value: 'articulatory', label: 'Articulatory synthesis' } ),
	Object.freeze( { value: 'tract', label: 'The head\'s own tract' } ),
	Object.freeze( { value: 'none', label: 'No sound' } ),
] );
/** The on/off views of an item, in the form's order. */
export const VIEW_SWITCHES = Object.freeze( [
	Object.freeze( { key: 'cutaway', label: 'Cutaway' } ),
	Object.freeze( { key: 'diagram', label: '2D diagram' } ),
	Object.freeze( { key: 'cues', label: 'Cues' } ),
	Object.freeze( { key: 'epg', label: 'EPG panel' } ),
] );
/** Where the camera looks from, in an author's words (the format's CAMERA_VIEWS). */
const CAMERA_WORDS = Object.freeze( { profile: 'Profile (the cut side)', 'three-quarter': 'Three-quarter', front: 'Front' } );
export const CAMERA_CHOICES = Object.freeze( CAMERA_VIEWS.map( ( value ) => Object.freeze( { value, label: CAMERA_WORDS[ value ] ?? value } ) ) );
/** How a phoneme target is said (the format's `said_as`). */
export const SAID_AS_CHOICES = Object.freeze( [
	Object.freeze( { value: '', label: 'By its sound (held, or "ta")' } ),
	Object.freeze( { value: 'alone', label: 'Alone (held when it can be)' } ),
	Object.freeze( { value: 'syllable', label: 'In a syllable (ta)' } ),
	Object.freeze( { value: 'repeated', label: 'Three times (t-t-t)' } ),
] );
/** Which labels the head shows: none, all, or those chosen. */
export const LABEL_MODES = Object.freeze( [
	Object.freeze( { value: 'none', label: 'None' } ),
	Object.freeze( { value: 'all', label: 'All of them' } ),
	Object.freeze( { value: 'chosen', label: 'Only these:' } ),
] );
/** The names a label list may hold, each with the words the label shows. */
export const LABEL_CHOICES = Object.freeze( LABEL_NAMES.map( ( value ) => Object.freeze( { value, label: value === 'velum' ? 'velum (soft palate)' : value.replace( /_/g, ' ' ) } ) ) );
/** The labels an author starts from on choosing "Only these". */
export const FIRST_CHOSEN_LABELS = Object.freeze( [ 'tongue_tip' ] );

/** The mode (LABEL_MODES) of an item's `views.labels`. */
export function labelMode( labels ) {

	return Array.isArray( labels ) ? 'chosen' : labels ? 'all' : 'none';

}

/** `views.labels` for a mode, keeping the names `previous` chose. */
export function labelsOfMode( mode, previous ) {

	if ( mode === 'chosen' ) return Array.isArray( previous ) && previous.length ? [ ...previous ] : [ ...FIRST_CHOSEN_LABELS ];
	return mode === 'all';

}

/** `labels` with `name` chosen or not, in the label layer's order. */
export function toggleLabel( labels, name, chosen ) {

	const names = new Set( Array.isArray( labels ) ? labels : [] );
	if ( chosen ) names.add( name );
	else names.delete( name );
	return LABEL_NAMES.filter( ( n ) => names.has( n ) );

}

/** Ranges the server accepts (schema.py): [low, high]. */
export const RANGES = Object.freeze( {
	speed: Object.freeze( [ 0.1, 1 ] ),
	cutoff_hz: Object.freeze( [ 100, 8000 ] ),
	channels: Object.freeze( [ 1, 16 ] ),
	skin_transparency: Object.freeze( [ 0, 1 ] ),
	zoom: LESSON_ZOOM_RANGE,
} );

/** What a stale save says, in plain words. */
export const CONFLICT_MESSAGE = 'Someone else changed this lesson since you opened it. Your changes are still here: reload to see their version (your changes are dropped), or overwrite it with yours.';

/** A new item: `text` said as a `kind` target, with the schema's defaults. */
export function newItem( kind = 'phoneme', text = 's' ) {

	return normaliseItem( { target: { kind, text } } );

}

/** A new lesson's draft. */
export function blankLesson() {

	return { title: '', language: 'en-US', description: '', items: [ newItem() ] };

}

/** `item` with every field present (the schema's defaults filled in), as a new object. */
export function normaliseItem( item = {} ) {

	const audio = item.audio ?? {};
	return {
		target: { kind: item.target?.kind ?? 'phoneme', text: item.target?.text ?? '' },
		presentation: item.presentation ?? 'dynamic',
		audio: { kind: audio.kind ?? 'natural', cutoff_hz: audio.cutoff_hz ?? null, channels: audio.channels ?? null },
		views: { ...LESSON_VIEW_DEFAULTS, ...( item.views ?? {} ) },
		speed: item.speed ?? 1,
		said_as: item.said_as ?? null,
		listen: item.listen ? { ...item.listen } : null,
	};

}

/** The editable draft of a lesson read from the server (or an import): a deep copy. */
export function draftOf( lesson ) {

	return {
		title: lesson?.title ?? '',
		language: lesson?.language ?? 'en-US',
		description: lesson?.description ?? '',
		items: ( lesson?.items ?? [] ).map( normaliseItem ),
	};

}

/**
 * What a save or an export sends: the lesson format, with only the audio options that apply
 * (the low-pass cut-off for lowpass, the channels for vocoded) and no empty ones.
 */
export function lessonBody( draft ) {

	return {
		format_version: FORMAT_VERSION,
		title: draft.title,
		language: draft.language,
		description: draft.description,
		items: draft.items.map( ( item ) => {

			const audio = { kind: item.audio.kind };
			if ( item.audio.kind === 'lowpass' && item.audio.cutoff_hz !== null ) audio.cutoff_hz = item.audio.cutoff_hz;
			if ( item.audio.kind === 'vocoded' && item.audio.channels !== null ) audio.channels = item.audio.channels;
			const views = { ...item.views, labels: Array.isArray( item.views.labels ) ? [ ...item.views.labels ] : item.views.labels };
			const body = { target: { ...item.target }, presentation: item.presentation, audio, views, speed: item.speed };
			// How a phoneme is said, when the author chose; a word or phrase has none.
			if ( item.said_as && item.target.kind === 'phoneme' ) body.said_as = item.said_as;
			// What a try is measured on is kept as the lesson had it (the starter lessons set it).
			if ( item.listen ) body.listen = { ...item.listen };
			return body;

		} ),
	};

}

/** Whether `draft` differs from `saved` in what a save would send. */
export function isDirty( draft, saved ) {

	return JSON.stringify( lessonBody( draft ) ) !== JSON.stringify( lessonBody( saved ) );

}

/** `items` with the item at `from` moved to `to` (both kept inside the list), as a new list. */
export function moveItem( items, from, to ) {

	const result = items.slice();
	if ( from < 0 || from >= items.length ) return result;
	const target = Math.min( Math.max( to, 0 ), items.length - 1 );
	const [ moved ] = result.splice( from, 1 );
	result.splice( target, 0, moved );
	return result;

}

/** `items` without the item at `index`, as a new list. */
export function removeItem( items, index ) {

	return items.filter( ( _, k ) => k !== index );

}

/** `items` with `item` inserted at `index` (the end when past it), as a new list. */
export function insertItem( items, index, item ) {

	const result = items.slice();
	result.splice( Math.min( Math.max( index, 0 ), items.length ), 0, item );
	return result;

}

/** `item` with the field at `path` ('speed', 'target.text', 'views.cutaway') set, as a new item. */
export function setField( item, path, value ) {

	const [ head, ...rest ] = path.split( '.' );
	if ( rest.length === 0 ) return { ...item, [ head ]: value };
	return { ...item, [ head ]: setField( item[ head ] ?? {}, rest.join( '.' ), value ) };

}

/** A number typed into a field: a finite number, or null for an empty or unreadable one. */
export function readNumber( text ) {

	const trimmed = String( text ?? '' ).trim();
	if ( trimmed === '' ) return null;
	const value = Number( trimmed );
	return Number.isFinite( value ) ? value : null;

}

/**
 * The server's 422 detail as messages by field: 'body.items.1.speed: Input should be …; body.title:
 * …' -> Map { 'items.1.speed' => 'Input should be …', 'title' => '…' }. A message that names no
 * field is kept under '' (shown at the top). FastAPI's list form is read too.
 */
export function fieldErrors( detail ) {

	const errors = new Map();
	const add = ( where, message ) => {

		const key = where.replace( /^body\.?/, '' );
		const text = String( message ).replace( /^Value error, /, '' ).trim();
		errors.set( key, errors.has( key ) ? `${ errors.get( key ) } ${ text }` : text );

	};

	if ( Array.isArray( detail ) ) {

		for ( const entry of detail ) add( ( entry?.loc ?? [] ).join( '.' ), entry?.msg ?? JSON.stringify( entry ) );
		return errors;

	}

	if ( typeof detail !== 'string' || detail === '' ) return errors;
	// Messages are joined with '; ' and each starts with where it is ('body.…: '); split only
	// there, since a message may hold '; ' itself.
	for ( const part of detail.split( /;\s+(?=body[.:])/ ) ) {

		const match = /^(body(?:\.[^\s:]+)?):\s*(.*)$/s.exec( part.trim() );
		if ( match ) add( match[ 1 ], match[ 2 ] );
		else add( '', part.trim() );

	}

	return errors;

}

/**
 * The messages of item `index` by its field ('target', 'target.text', 'speed', 'views.cutaway', …),
 * from fieldErrors(); a message about the whole item is under ''.
 */
export function itemErrors( errors, index ) {

	const prefix = `items.${ index }`;
	const result = new Map();
	for ( const [ key, message ] of errors ) {

		if ( key === prefix ) result.set( '', message );
		else if ( key.startsWith( `${ prefix }.` ) ) result.set( key.slice( prefix.length + 1 ), message );

	}

	return result;

}

/** The items that have a message (their indices, in order). */
export function itemsWithErrors( errors ) {

	const found = new Set();
	for ( const key of errors.keys() ) {

		const match = /^items\.(\d+)(\.|$)/.exec( key );
		if ( match ) found.add( Number( match[ 1 ] ) );

	}

	return [ ...found ].sort( ( a, b ) => a - b );

}

/**
 * Read a lesson file chosen for an import: its JSON, which must be an object with items. Throws
 * an Error whose message says in plain words what is wrong; the server checks the rest.
 */
export function parseLessonFile( text ) {

	let value;
	try {

		value = JSON.parse( text );

	} catch ( error ) {

		throw new Error( `This file is not JSON (${ error.message }). Choose a lesson exported from Glasshead.`, { cause: error } );

	}

	if ( ! value || typeof value !== 'object' || Array.isArray( value ) || ! Array.isArray( value.items ) ) {

		throw new Error( 'This file is JSON but not a lesson: a lesson has a title and a list of items.' );

	}

	return value;

}

/** The editor's address for lesson `id` ('new' for a new one; null for the list). */
export function authorHref( id = null ) {

	return id === null ? `#${ AUTHOR_PATH }` : `#${ AUTHOR_PATH }?lesson=${ id }`;

}

/** The lesson an editor address names: a whole number from 1, 'new', or null for the list. */
export function parseAuthorHash( hash ) {

	const query = new URLSearchParams( ( hash ?? '' ).split( '?' ).slice( 1 ).join( '?' ) );
	const lesson = query.get( 'lesson' );
	if ( lesson === 'new' ) return { lesson: 'new' };
	return { lesson: /^\d+$/.test( lesson ?? '' ) && Number( lesson ) >= 1 ? Number( lesson ) : null };

}

/** An item's one-line summary in the list: 'Word "ship", static, 0.5x'. */
export function itemSummary( item ) {

	const kind = TARGET_KINDS.find( ( k ) => k.value === item.target.kind )?.label.split( ' ' )[ 0 ] ?? item.target.kind;
	const text = item.target.kind === 'phoneme' ? `/${ item.target.text }/` : `"${ item.target.text }"`;
	const parts = [ `${ kind } ${ text }` ];
	if ( item.presentation === 'static' ) parts.push( 'held' );
	if ( item.speed !== 1 ) parts.push( `${ item.speed }x` );
	if ( item.audio.kind !== 'natural' ) parts.push( item.audio.kind === 'none' ? 'no sound' : item.audio.kind );
	return parts.join( ', ' );

}
