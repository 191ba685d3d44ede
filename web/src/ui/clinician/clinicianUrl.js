// The clinician view's selection in its URL, pure: #/clinician?target=pose:3&recording=12&frame=40
// is read when the view opens and written (without a new history entry) as the choices change, so
// that a link or a reload shows the same target, recording and frame. A value that cannot be right
// (a target without a kind, a recording id that is not a positive whole number, a frame that is not
// a whole number) is dropped with a message that says what was wrong, instead of failing later.

import { routePath } from '../shared/router.js';
import { parseTargetName } from '../shared/targets.js';

/** The route the view lives at. */
export const CLINICIAN_ROUTE = '#/clinician';

/**
 * The selection in `hash`: { target, recording, frame, problems } where each value is null when
 * absent or refused, and `problems` lists, in plain words, what was refused.
 */
export function parseSelection( hash ) {

	const query = new URLSearchParams( String( hash ?? '' ).split( '?' ).slice( 1 ).join( '?' ) );
	const selection = { target: null, recording: null, frame: null, problems: [] };
	const target = query.get( 'target' );
	if ( target ) {

		if ( parseTargetName( target ) ) selection.target = target;
		else selection.problems.push( `The link's target "${ shorten( target ) }" is not a target name (such as pose:3 or phoneme:T).` );

	}

	const recording = query.get( 'recording' );
	if ( recording ) {

		if ( /^[1-9]\d{0,11}$/.test( recording ) ) selection.recording = recording;
		else selection.problems.push( `The link's recording "${ shorten( recording ) }" is not a recording number.` );

	}

	const frame = query.get( 'frame' );
	if ( frame ) {

		if ( /^\d{1,9}$/.test( frame ) ) selection.frame = Number( frame );
		else selection.problems.push( `The link's frame "${ shorten( frame ) }" is not a frame number.` );

	}

	return selection;

}

/**
 * The message for a linked choice that is not on offer: `kind` 'target' or 'recording', `value`
 * as the link gave it.
 */
export function missingChoiceMessage( kind, value ) {

	return kind === 'target'
		? `The link's target "${ shorten( value ) }" does not exist (any more): choose a target from the list.`
		: `The link's recording ${ shorten( value ) } does not exist (any more): choose a recording from the list.`;

}

/** The hash of a selection { target, recording, frame } (absent values left out). */
export function selectionHash( { target = null, recording = null, frame = null } = {} ) {

	const query = new URLSearchParams();
	if ( target ) query.set( 'target', target );
	if ( recording ) query.set( 'recording', String( recording ) );
	if ( frame ) query.set( 'frame', String( frame ) );
	const text = query.toString().replaceAll( '%3A', ':' );
	return text ? `${ CLINICIAN_ROUTE }?${ text }` : CLINICIAN_ROUTE;

}

/**
 * The view's URL: reads the selection, writes it back (replacing the history entry, at most every
 * 250 ms, not while `writable()` is false) and hands `apply( hash )` a selection typed into the
 * URL while the view stays mounted. A URL changed by someone else since it was last read or
 * written is theirs, and is not overwritten.
 */
export class SelectionUrl {

	/**
	 * @param {Window} win
	 * @param {{ selection: () => object, writable: () => boolean, apply: ( hash: string ) => any }} view
	 */
	constructor( win, { selection, writable, apply } ) {

		this.window = win;
		this.selection = selection;
		this.writable = writable;
		this.lastHash = win.location.hash;
		this.timer = null;
		this.onHashChange = () => {

			const hash = this.window.location.hash;
			if ( hash !== this.lastHash && routePath( hash ) === '/clinician' ) apply( hash );

		};
		win.addEventListener( 'hashchange', this.onHashChange );

	}

	/** The selection in `hash`, which becomes the URL's last known state (see parseSelection). */
	read( hash ) {

		this.lastHash = hash;
		return parseSelection( hash );

	}

	write() {

		this.window.clearTimeout( this.timer );
		this.timer = this.window.setTimeout( () => {

			const hash = selectionHash( this.selection() );
			const current = this.window.location.hash;
			if ( ! this.writable() || current === hash || current !== this.lastHash ) return;
			this.window.history.replaceState( this.window.history.state, '', hash );
			this.lastHash = hash;

		}, 250 );

	}

	stop() {

		this.window.clearTimeout( this.timer );
		this.window.removeEventListener( 'hashchange', this.onHashChange );

	}

}

/** A value from the URL cut to a length a message can show. */
function shorten( value ) {

	const text = String( value );
	return text.length > 40 ? `${ text.slice( 0, 39 ) }…` : text;

}
