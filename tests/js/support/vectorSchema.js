// The one schema of every shared vector file (tests/vectors/*.json). Twin of
// server/glasshead/vectors/schema.py, which states the rules; both report a problem with the
// file and, inside a case, its index and description.

const TOP_LEVEL = [ 'description', 'generator', 'format_version', 'constants', 'tolerance', 'cases' ];
const OPTIONAL = [ 'fixtures' ];
const CASE_KEYS = [ 'description', 'input', 'expected' ];
const TOLERANCE_KEYS = [ 'value', 'unit', 'reason' ];
/** Units a tolerance may have: mm, mm^3, relative, "1" (absolute, dimensionless), rad, deg. */
export const UNITS = [ 'mm', 'mm2', 'mm3', 'relative', '1', 'rad', 'deg', 'Hz' ];
const GENERATOR_PREFIX = 'glasshead vectors';

/** The error a document that breaks the schema is refused with; the message lists every problem. */
export class VectorSchemaError extends Error {

	constructor( message ) {

		super( message );
		this.name = 'VectorSchemaError';

	}

}

const isText = ( value ) => typeof value === 'string' && value.trim() !== '';
const isObject = ( value ) => value !== null && typeof value === 'object' && ! Array.isArray( value );
const pyRepr = ( text ) => ( text.includes( '\'' ) && ! text.includes( '"' ) ? `"${ text }"` : `'${ text.replaceAll( '\'', '\\\'' ) }'` );

function where( index, entry ) {

	return isObject( entry ) && isText( entry.description ) ? `case ${ index } (${ pyRepr( entry.description ) })` : `case ${ index }`;

}

function caseProblems( index, entry, seen ) {

	const at = where( index, entry );
	if ( ! isObject( entry ) ) return [ `${ at }: a case must be an object` ];
	const found = [];
	const keys = Object.keys( entry );
	const missing = CASE_KEYS.filter( ( k ) => ! keys.includes( k ) );
	const unknown = keys.filter( ( k ) => ! CASE_KEYS.includes( k ) ).sort();
	if ( missing.length ) found.push( `${ at }: missing ${ missing.join( ', ' ) }` );
	if ( unknown.length ) found.push( `${ at }: unknown keys ${ unknown.join( ', ' ) }` );
	const description = entry.description;
	if ( ! isText( description ) ) found.push( `${ at }: description must be non-empty text` );
	else if ( seen.has( description ) ) found.push( `${ at }: description repeats case ${ seen.get( description ) }` );
	else seen.set( description, index );
	if ( 'input' in entry && ! isObject( entry.input ) ) found.push( `${ at }: input must be an object` );
	const expected = entry.expected;
	if ( 'expected' in entry && ! isObject( expected ) ) found.push( `${ at }: expected must be an object` );
	else if ( isObject( expected ) && 'error' in expected && ( ! isText( expected.error ) || Object.keys( expected ).length !== 1 ) ) {

		found.push( `${ at }: a refusal's expected must be exactly {"error": text}` );

	}

	return found;

}

function toleranceProblems( tolerance ) {

	const found = [];
	for ( const [ name, entry ] of Object.entries( tolerance ) ) {

		const at = `tolerance '${ name }'`;
		if ( ! isObject( entry ) || Object.keys( entry ).sort().join() !== [ ...TOLERANCE_KEYS ].sort().join() ) {

			found.push( `${ at }: must be exactly {value, unit, reason}` );
			continue;

		}

		if ( typeof entry.value !== 'number' || ! Number.isFinite( entry.value ) || entry.value <= 0 ) found.push( `${ at }: value must be a finite number > 0` );
		if ( ! UNITS.includes( entry.unit ) ) found.push( `${ at }: unit '${ entry.unit }' is not one of ${ UNITS.join( ', ' ) }` );
		if ( ! isText( entry.reason ) ) found.push( `${ at }: reason must be non-empty text` );

	}

	return found;

}

/** Every way ``document`` breaks the schema, as messages (empty when it follows it). */
export function schemaProblems( document ) {

	if ( ! isObject( document ) ) return [ 'top level: a vector file must hold a JSON object' ];
	const found = [];
	const keys = Object.keys( document );
	const missing = TOP_LEVEL.filter( ( k ) => ! keys.includes( k ) );
	const unknown = keys.filter( ( k ) => ! TOP_LEVEL.includes( k ) && ! OPTIONAL.includes( k ) ).sort();
	if ( missing.length ) found.push( `top level: missing ${ missing.join( ', ' ) }` );
	if ( unknown.length ) found.push( `top level: unknown keys ${ unknown.join( ', ' ) } (shared inputs go in fixtures, fixed numbers in constants)` );
	if ( 'description' in document && ! isText( document.description ) ) found.push( 'top level: description must be non-empty text' );
	if ( 'generator' in document && ! ( isText( document.generator ) && document.generator.startsWith( GENERATOR_PREFIX ) ) ) {

		found.push( `top level: generator must be the command, ${ GENERATOR_PREFIX } ...` );

	}

	if ( 'format_version' in document && ! ( Number.isInteger( document.format_version ) && document.format_version >= 1 ) ) {

		found.push( 'top level: format_version must be an integer >= 1' );

	}

	for ( const key of [ 'constants', 'fixtures' ] ) if ( key in document && ! isObject( document[ key ] ) ) found.push( `top level: ${ key } must be an object` );
	if ( 'tolerance' in document ) {

		if ( isObject( document.tolerance ) ) found.push( ...toleranceProblems( document.tolerance ) );
		else found.push( 'top level: tolerance must be an object ({} when every result is exact)' );

	}

	if ( 'cases' in document && ! Array.isArray( document.cases ) ) found.push( 'top level: cases must be an array' );
	else if ( Array.isArray( document.cases ) ) {

		const seen = new Map();
		document.cases.forEach( ( entry, index ) => found.push( ...caseProblems( index, entry, seen ) ) );

	}

	return found;

}

/** Throw ``VectorSchemaError`` naming the file ``name`` and each problem, if there is any. */
export function checkVectorDocument( document, name ) {

	const found = schemaProblems( document );
	if ( found.length ) {

		const shown = found.slice( 0, 20 ).concat( found.length > 20 ? [ `... and ${ found.length - 20 } more` ] : [] );
		throw new VectorSchemaError( `${ name } breaks the vector schema:\n${ shown.map( ( p ) => `  ${ name }: ${ p }` ).join( '\n' ) }` );

	}

	return document;

}
