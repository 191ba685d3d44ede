// The clinician's view of a child's history as plain data (clinicianChild.js shows it): the
// chooser's children grouped by class, the rows of the practice table with each item's target
// read from its lesson, ratings in words, and the paths of a recording's exports. No DOM; read by
// tests/js/clinicianChild.test.js.

/** The EPG export formats, as the server names them, with the words on their buttons. */
export const EXPORT_FORMATS = Object.freeze( [
	Object.freeze( { format: 'csv', label: 'CSV' } ),
	Object.freeze( { format: 'emur-json', label: 'emuR JSON' } ),
	Object.freeze( { format: 'ssff', label: 'SSFF' } ),
] );
const RATINGS = Object.freeze( { 1: 'not yet', 2: 'nearly', 3: 'got it' } );

/** The chooser's groups: [{ label: class name, children: [{ value, label }] }], classes in name order. */
export function childChoices( classes, children ) {

	const byClass = new Map( classes.map( ( c ) => [ c.id, { label: c.name, children: [] } ] ) );
	for ( const child of children ) byClass.get( child.class_id )?.children.push( { value: String( child.id ), label: `${ child.display_name } (${ child.avatar })` } );
	return [ ...byClass.values() ].filter( ( group ) => group.children.length ).sort( ( a, b ) => a.label.localeCompare( b.label ) );

}

/** A rating in words: '3, got it (adult)', or '' for none. */
export function ratingWords( rating, ratedBy ) {

	if ( rating === null || rating === undefined ) return '';
	return `${ rating }, ${ RATINGS[ rating ] ?? '?' }${ ratedBy ? ` (${ ratedBy })` : '' }`;

}

/**
 * The history table's rows from practice records and the lessons they name (Map id -> lesson,
 * with items): [{ id, when, lesson, item, target, replays, rating, heard, audio }], in the
 * records' order; `audio` is whether the go's sound was kept.
 */
export function practiceRows( records, lessons ) {

	return records.map( ( record ) => {

		const lesson = lessons.get( record.lesson_id );
		const target = lesson?.items?.[ record.item_index ]?.target;
		return {
			id: record.id,
			when: record.practised_at.replace( 'T', ' ' ).replace( /:\d\d(\.\d+)?(Z|[+-]\d\d:\d\d)$/, '' ),
			lesson: lesson?.title ?? `lesson ${ record.lesson_id }`,
			item: record.item_index + 1,
			target: target ? ( target.kind === 'phoneme' ? `/${ target.text }/` : target.text ) : '',
			replays: record.replays,
			rating: ratingWords( record.rating, record.rated_by ),
			heard: measureWords( record.measures ),
			audio: record.has_audio === true,
		};

	} );

}

/** The path of a recording's export in `format`. */
export function recordingExportPath( id, format ) {

	return `epg/recordings/${ id }/export?format=${ encodeURIComponent( format ) }`;

}

const VERDICTS = Object.freeze( { in: 'in the target', near: 'near', off: 'off' } );

/** What the voice measured on a go, in words: 'in the target: F1 410, F2 3050 Hz', '' for nothing. */
export function measureWords( measures ) {

	if ( ! measures ) return '';
	const parts = [];
	if ( measures.f1 && measures.f2 ) parts.push( `F1 ${ Math.round( measures.f1 ) }, F2 ${ Math.round( measures.f2 ) } Hz` );
	if ( measures.centroid ) parts.push( `centroid ${ Math.round( measures.centroid ) } Hz` );
	const verdict = VERDICTS[ measures.verdict ];
	return [ verdict, parts.join( '; ' ) ].filter( Boolean ).join( ': ' );

}

/**
 * The measured goes as series for the attempts plot, oldest first: vowels ({ when, f1, f2,
 * verdict }) and fricatives ({ when, centroid, verdict }); goes without measures are left out.
 */
export function measuredSeries( records ) {

	const measured = records.filter( ( r ) => r.measures ).sort( ( a, b ) => a.practised_at.localeCompare( b.practised_at ) || a.id - b.id );
	return {
		vowel: measured.filter( ( r ) => r.measures.f1 && r.measures.f2 ).map( ( r ) => ( { when: r.practised_at, f1: r.measures.f1, f2: r.measures.f2, verdict: r.measures.verdict ?? null } ) ),
		fricative: measured.filter( ( r ) => r.measures.centroid && ! r.measures.f1 ).map( ( r ) => ( { when: r.practised_at, centroid: r.measures.centroid, verdict: r.measures.verdict ?? null } ) ),
	};

}

/** The roles that may switch the keeping of a child's recordings (the server's rule too). */
export const RECORDING_SWITCH_ROLES = Object.freeze( [ 'clinician', 'admin' ] );

const MONTHS = Object.freeze( [ 'January', 'February', 'March', 'April', 'May', 'June', 'July', 'August', 'September', 'October', 'November', 'December' ] );

/** An ISO time as a person reads it, in UTC whatever the browser's zone: '2 March 2026, 09:30 UTC'. */
export function readableTime( iso ) {

	// A time without a zone is the server's UTC (JavaScript would read it as local time).
	const text = String( iso ?? '' );
	const date = new Date( /T[\d:.]+$/.test( text ) ? `${ text }Z` : text );
	if ( Number.isNaN( date.getTime() ) ) return text;
	const two = ( n ) => String( n ).padStart( 2, '0' );
	return `${ date.getUTCDate() } ${ MONTHS[ date.getUTCMonth() ] } ${ date.getUTCFullYear() }, ${ two( date.getUTCHours() ) }:${ two( date.getUTCMinutes() ) } UTC`;

}

/**
 * A child's recording switch (GET /children/{id}/audio-recording) in words: 'On since 2 March
 * 2026, 09:30 UTC, by Dr Ames', 'Off since …, by …' once someone turned it off, 'Off' when
 * nobody ever turned it on.
 */
export function recordingSwitchWords( state ) {

	const on = state?.enabled === true;
	if ( ! state?.set_at ) return on ? 'On' : 'Off';
	return `${ on ? 'On' : 'Off' } since ${ whenAndWho( state ) }`;

}

/** The switch's history, newest first, one line each: 'On: 2 March 2026, 09:30 UTC, by Dr Ames'. */
export function recordingHistoryLines( history ) {

	return ( history ?? [] ).map( ( entry ) => `${ entry.enabled ? 'On' : 'Off' }: ${ whenAndWho( entry ) }` );

}

/** A change of the switch's time and maker: '2 March 2026, 09:30 UTC, by Dr Ames'. */
function whenAndWho( change ) {

	return `${ readableTime( change.set_at ) }${ change.set_by_name ? `, by ${ change.set_by_name }` : '' }`;

}
