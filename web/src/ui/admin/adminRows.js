// The admin's privacy page as plain data (AdminView.js shows it): what a deletion removed, in
// words, and what the confirmation says will go. No DOM; read by tests/js/adminRows.test.js.

/** The kinds of rows a child's deletion counts (DELETE /children/{id}/data), in the words shown. */
export const DELETED_KINDS = Object.freeze( [
	Object.freeze( [ 'practice_records', 'practice record', 'practice records' ] ),
	Object.freeze( [ 'recordings', 'EPG recording', 'EPG recordings' ] ),
	Object.freeze( [ 'assignments', 'assignment', 'assignments' ] ),
	Object.freeze( [ 'child_tokens', 'sign-in', 'sign-ins' ] ),
] );

/** '2 practice records, 1 EPG recording, no assignments and 1 sign-in' from the deletion's counts. */
export function deletedWords( counts ) {

	const parts = DELETED_KINDS.map( ( [ key, one, many ] ) => {

		const n = counts?.[ key ] ?? 0;
		return n === 0 ? `no ${ many }` : `${ n } ${ n === 1 ? one : many }`;

	} );
	return `${ parts.slice( 0, - 1 ).join( ', ' ) } and ${ parts[ parts.length - 1 ] }`;

}

/** What the confirmation says before a child's data is deleted. */
export function confirmWords( child ) {

	return `Delete everything stored about ${ child.display_name }: their practice, EPG recordings, own assignments and sign-ins, and ${ child.display_name } from their class. This cannot be undone; export first to keep a copy.`;

}

/** The file name an export of `child` is saved under when the server gives none. */
export function exportName( child ) {

	return `child-${ child.id }.json`;

}
