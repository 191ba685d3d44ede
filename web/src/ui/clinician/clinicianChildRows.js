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
 * with items): [{ when, lesson, item, target, replays, rating }], in the records' order.
 */
export function practiceRows( records, lessons ) {

	return records.map( ( record ) => {

		const lesson = lessons.get( record.lesson_id );
		const target = lesson?.items?.[ record.item_index ]?.target;
		return {
			when: record.practised_at.replace( 'T', ' ' ).replace( /:\d\d(\.\d+)?(Z|[+-]\d\d:\d\d)$/, '' ),
			lesson: lesson?.title ?? `lesson ${ record.lesson_id }`,
			item: record.item_index + 1,
			target: target ? ( target.kind === 'phoneme' ? `/${ target.text }/` : target.text ) : '',
			replays: record.replays,
			rating: ratingWords( record.rating, record.rated_by ),
		};

	} );

}

/** The path of a recording's export in `format`. */
export function recordingExportPath( id, format ) {

	return `epg/recordings/${ id }/export?format=${ encodeURIComponent( format ) }`;

}
