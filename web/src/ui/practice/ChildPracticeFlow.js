// The child's practice as plain data: a class code as the server takes it, and a round through a
// lesson's items, one target at a time, counting how often the child heard the target again and
// making the practice record (POST /practice) of each try. No DOM: ChildPractice.js shows it and
// tests/js/childPractice.test.js reads it.

/** The characters of a join code (docs/lessons.md; store/lessons.py JOIN_CODE_ALPHABET): no
 * 0/O, 1/I/L, 2/Z, 5/S, 8/B. */
export const JOIN_CODE_ALPHABET = '34679ACDEFGHJKMNPQRTUVWXY';
/** How many characters a join code has. */
export const JOIN_CODE_LENGTH = 6;
const JOIN_CODE_PATTERN = new RegExp( `^[${ JOIN_CODE_ALPHABET }]{${ JOIN_CODE_LENGTH }}$` );

/** What was typed as a class code, as the server compares it: capitals, no spaces or dashes. */
export function normaliseJoinCode( typed ) {

	return String( typed ?? '' ).toUpperCase().replace( /[\s-]+/g, '' );

}

/** Whether `code` (normalised) can be a class code, so the page asks the server only then. */
export function looksLikeJoinCode( code ) {

	return JOIN_CODE_PATTERN.test( code );

}

/** The class code a join link carries ('#/practice?code=ACD347'), normalised, or null. */
export function joinCodeFromHash( hash ) {

	const query = new URLSearchParams( String( hash ?? '' ).split( '?' ).slice( 1 ).join( '?' ) );
	const code = normaliseJoinCode( query.get( 'code' ) ?? '' );
	return looksLikeJoinCode( code ) ? code : null;

}

/** One pass through a lesson's items for one child. */
export class PracticeRound {

	/**
	 * @param {{ id: number, items: Array<object> }} lesson the lesson with its items
	 * @param {{ id: number }} child the signed-in child
	 */
	constructor( lesson, child ) {

		if ( ! Array.isArray( lesson?.items ) || lesson.items.length === 0 ) throw new TypeError( 'a practice round needs a lesson with items' );
		this.lesson = lesson;
		this.child = child;
		this.index = 0;
		this.replays = 0;
		this.records = [];

	}

	/** The item being practised, or null when the round is done. */
	get item() {

		return this.lesson.items[ this.index ] ?? null;

	}

	get done() {

		return this.index >= this.lesson.items.length;

	}

	/** The target was played again (the replay button). */
	replayed() {

		this.replays += 1;

	}

	/**
	 * The POST /practice body of the try at the current item: its replays, the child's rating
	 * (RATINGS: 1 not yet, 2 nearly, 3 got it) when the child chose a face, and what the child's
	 * voice measured (listenScales.attemptMeasures) when the page listened.
	 */
	record( rating = null, measures = null ) {

		const body = { child_id: this.child.id, lesson_id: this.lesson.id, item_index: this.index, replays: this.replays };
		if ( rating !== null ) Object.assign( body, { rating, rated_by: 'child' } );
		if ( measures && Object.keys( measures ).length ) body.measures = measures;
		return body;

	}

	/** The try was recorded as `saved` (the server's answer): on to the next target. */
	next( saved ) {

		this.records.push( saved );
		this.index += 1;
		this.replays = 0;
		return this.item;

	}

}
