// What a person reads when saving a pose fails: the server's answer (a status and a detail such as
// "body.name: String should have at most 120 characters") said in plain words, with what to do
// about it, and never a status code or a field path. Pure: unit-tested without a browser.

import { describeDetail } from '../../api.js';

/** A parameter's name in words: 'tip_height' -> 'Tip height'. */
function parameterWords( name ) {

	const words = name.replace( /[_.]+/g, ' ' ).trim();
	return words.charAt( 0 ).toUpperCase() + words.slice( 1 );

}

/** A refused value or name (422), from the server's detail line; null when it is not recognised. */
function refusal( detail ) {

	let match = /name: String should have at most (\d+) characters?/.exec( detail );
	if ( match ) return `Names can be at most ${ match[ 1 ] } characters. Shorten the name and save again.`;
	if ( /name: String should have at least/.test( detail ) ) return 'Give the pose a name first.';
	match = /description: String should have at most (\d+) characters?/.exec( detail );
	if ( match ) return `Descriptions can be at most ${ match[ 1 ] } characters.`;
	match = /params\.([A-Za-z][A-Za-z0-9_.]*): (\S+) is outside \[(\S+), (\S+)\] ?(.*)$/.exec( detail );
	if ( match ) {

		const unit = match[ 5 ] ? ` ${ match[ 5 ] }` : '';
		return `${ parameterWords( match[ 1 ] ) } must be between ${ match[ 3 ] } and ${ match[ 4 ] }${ unit }; it is ${ match[ 2 ] }. The pose was not saved.`;

	}

	match = /params\.([A-Za-z][A-Za-z0-9_.]*): unknown parameter/.exec( detail );
	if ( match ) return `The server does not know the parameter "${ match[ 1 ] }". The pose was not saved.`;
	match = /params\.([A-Za-z][A-Za-z0-9_.]*): (.+)$/.exec( detail );
	if ( match ) return `${ parameterWords( match[ 1 ] ) }: ${ lowerFirst( match[ 2 ] ) }. The pose was not saved.`;
	return null;

}

function lowerFirst( text ) {

	return text.charAt( 0 ).toLowerCase() + text.slice( 1 ).replace( /\.$/, '' );

}

/**
 * The sentence to show when saving the pose `name` failed with `error` (an ApiError from the
 * client, or an Error): what went wrong and what to do.
 */
export function poseSaveMessage( error, name = '' ) {

	const status = error?.status;
	if ( status === undefined ) return error?.message ?? String( error );
	if ( status === null ) return 'Could not reach the server, so the pose was not saved. Check the connection and save again.';
	if ( status === 409 ) return `A pose named "${ name }" already exists. Choose another name.`;
	if ( status === 413 ) return 'This pose is too large to save.';
	if ( status === 422 ) {

		const detail = describeDetail( error.detail );
		return refusal( detail ) ?? `The server refused this pose: ${ lowerFirst( detail.replace( /^body\./, '' ) ) }.`;

	}

	if ( status >= 500 ) return 'The server failed while saving the pose. Save again in a moment.';
	return `The pose was not saved: the server answered ${ status }.`;

}
