// The current articulation parameters: one Float32Array in the rigs' parameter order, a name ->
// index map, and the checks that keep every value a known name inside its range.
//
// The workbench's sliders, its copy and paste of JSON, saved poses and the per-frame articulation
// all read and write the same state. `version` grows by one on every change, so the per-frame
// pipeline recomputes only when something moved. Pure: no DOM, no three.js.

/** Group order of the workbench (the paper's Figure 4): jaw, lips, the velum, then the tongue. */
export const GROUP_ORDER = Object.freeze( [
	'jaw',
	'lips',
	'velum',
	'tongue sagittal',
	'tongue coronal front',
	'tongue coronal middle',
	'tongue coronal back',
] );

/** Decimals kept when parameters are copied as JSON: far below a slider step, above float32 noise. */
export const JSON_DECIMALS = 4;

const ROUND = 10 ** JSON_DECIMALS;

/** A value as it is shown and copied: rounded to JSON_DECIMALS, without a negative zero. */
export function roundValue( value ) {

	const rounded = Math.round( value * ROUND ) / ROUND;
	return rounded === 0 ? 0 : rounded;

}

export class ParamState {

	/**
	 * @param {Array<{name: string, unit: string, min: number, max: number, neutral: number,
	 *   group?: string, description?: string}>} definitions in the rigs' order (the tongue rig's
	 *   parameters first, so that its evaluator can read the same array)
	 */
	constructor( definitions ) {

		if ( ! Array.isArray( definitions ) || definitions.length === 0 ) throw new TypeError( 'ParamState needs a non-empty list of parameter definitions' );
		this.definitions = definitions.map( checkDefinition );
		this.names = this.definitions.map( ( p ) => p.name );
		this.index = new Map();
		this.names.forEach( ( name, k ) => {

			if ( this.index.has( name ) ) throw new RangeError( `parameter "${ name }" is defined twice` );
			this.index.set( name, k );

		} );
		this.count = this.names.length;
		this.minimum = Float32Array.from( this.definitions, ( p ) => p.min );
		this.maximum = Float32Array.from( this.definitions, ( p ) => p.max );
		this.neutral = Float32Array.from( this.definitions, ( p ) => p.neutral );
		this.values = Float32Array.from( this.neutral );
		this.version = 0;
		this.listeners = new Set();

	}

	/** The definition of parameter `name` (throws a RangeError naming it when unknown). */
	definition( name ) {

		return this.definitions[ this.indexOf( name ) ];

	}

	indexOf( name ) {

		const k = this.index.get( name );
		if ( k === undefined ) throw new RangeError( unknownMessage( name, this.names ) );
		return k;

	}

	get( name ) {

		return this.values[ this.indexOf( name ) ];

	}

	/** Set one parameter; a value outside its range is refused with a RangeError naming it. */
	set( name, value ) {

		const k = this.indexOf( name );
		const error = valueError( this.definitions[ k ], value );
		if ( error ) throw new RangeError( error );
		if ( this.values[ k ] === Math.fround( value ) ) return false;
		this.values[ k ] = value;
		this.changed( [ name ] );
		return true;

	}

	/**
	 * Replace every value: names given take their value, the others their neutral one. All or
	 * nothing: `params` is checked first (see checkParams) and a bad one changes no value.
	 */
	assign( params ) {

		const checked = checkParams( params, this );
		if ( ! checked.ok ) throw new RangeError( checked.error );
		const next = Float32Array.from( this.neutral );
		for ( const [ name, value ] of Object.entries( checked.params ) ) next[ this.index.get( name ) ] = value;
		const changedNames = this.names.filter( ( name, k ) => next[ k ] !== this.values[ k ] );
		if ( changedNames.length === 0 ) return false;
		this.values.set( next );
		this.changed( changedNames );
		return true;

	}

	/** Every parameter back to its neutral value. */
	reset() {

		const changedNames = this.names.filter( ( name, k ) => this.values[ k ] !== this.neutral[ k ] );
		if ( changedNames.length === 0 ) return false;
		this.values.set( this.neutral );
		this.changed( changedNames );
		return true;

	}

	/** { name: value } for every parameter, rounded as copied. */
	toObject() {

		const object = {};
		this.names.forEach( ( name, k ) => {

			object[ name ] = roundValue( this.values[ k ] );

		} );
		return object;

	}

	/** { name: value } of the parameters away from neutral only (a short, readable pose). */
	changedFromNeutral() {

		const object = {};
		this.names.forEach( ( name, k ) => {

			if ( roundValue( this.values[ k ] ) !== roundValue( this.neutral[ k ] ) ) object[ name ] = roundValue( this.values[ k ] );

		} );
		return object;

	}

	/** Every parameter as pretty JSON, one per line, in rig order: what "Copy" puts on the clipboard. */
	toJSON() {

		return JSON.stringify( this.toObject(), null, 2 );

	}

	/** Parse pasted text and assign it. Returns { ok: true } or { ok: false, error } (state unchanged). */
	paste( text ) {

		const parsed = parseParamsJson( text, this );
		if ( ! parsed.ok ) return parsed;
		this.assign( parsed.params );
		return { ok: true };

	}

	/** The parameters in workbench groups: [{ group, parameters: [definition] }], GROUP_ORDER first. */
	groups() {

		const byGroup = new Map();
		for ( const p of this.definitions ) {

			const group = p.group ?? 'other';
			if ( ! byGroup.has( group ) ) byGroup.set( group, [] );
			byGroup.get( group ).push( p );

		}

		const known = GROUP_ORDER.filter( ( group ) => byGroup.has( group ) );
		const others = [ ...byGroup.keys() ].filter( ( group ) => ! GROUP_ORDER.includes( group ) );
		return [ ...known, ...others ].map( ( group ) => ( { group, parameters: byGroup.get( group ) } ) );

	}

	/**
	 * Mark the values changed after writing `values` directly, as a track player does every frame.
	 * Allocates nothing; listeners get null for the names. The caller keeps the values in range.
	 */
	touch() {

		this.changed( null );

	}

	/**
	 * Call fn( changedNames, state ) after every change (changedNames null after touch()).
	 * Returns a function that removes it.
	 */
	onChange( fn ) {

		this.listeners.add( fn );
		return () => this.listeners.delete( fn );

	}

	changed( names ) {

		this.version ++;
		for ( const listener of this.listeners ) listener( names, this );

	}

}

function checkDefinition( p ) {

	if ( ! p || typeof p.name !== 'string' || p.name === '' ) throw new TypeError( `a parameter definition needs a name, got ${ JSON.stringify( p ) }` );
	for ( const key of [ 'min', 'max', 'neutral' ] ) {

		if ( typeof p[ key ] !== 'number' || ! Number.isFinite( p[ key ] ) ) throw new TypeError( `parameter "${ p.name }" needs a finite ${ key }` );

	}

	if ( ! ( p.min <= p.neutral && p.neutral <= p.max ) ) throw new RangeError( `parameter "${ p.name }": neutral ${ p.neutral } is not within [${ p.min }, ${ p.max }]` );
	return p;

}

/** The message for a value of parameter p that cannot be used, or null when it can. */
export function valueError( p, value ) {

	if ( typeof value !== 'number' ) return `${ p.name } must be a number, got ${ JSON.stringify( value ) }`;
	if ( ! Number.isFinite( value ) ) return `${ p.name } must be a finite number, got ${ value }`;
	if ( value < p.min || value > p.max ) return `${ p.name } = ${ value } is outside its range ${ p.min } to ${ p.max } ${ p.unit ?? '' }`.trimEnd();
	return null;

}

/**
 * Check a { name: value } object against the state's definitions. A saved pose's shape,
 * { name, params: { ... } }, is accepted too. Returns { ok: true, params } or { ok: false, error }
 * with the first problem, in words a teacher can act on.
 */
export function checkParams( object, state ) {

	if ( object === null || typeof object !== 'object' || Array.isArray( object ) ) {

		return { ok: false, error: 'Expected a JSON object of parameter names and values, like {"tip_height": 5}.' };

	}

	const params = object.params !== null && typeof object.params === 'object' && ! Array.isArray( object.params ) ? object.params : object;
	for ( const [ name, value ] of Object.entries( params ) ) {

		const k = state.index.get( name );
		if ( k === undefined ) return { ok: false, error: unknownMessage( name, state.names ) };
		const error = valueError( state.definitions[ k ], value );
		if ( error ) return { ok: false, error: `${ error }.` };

	}

	return { ok: true, params };

}

/** Parse pasted text: { ok: true, params } or { ok: false, error }. */
export function parseParamsJson( text, state ) {

	if ( typeof text !== 'string' || text.trim() === '' ) return { ok: false, error: 'Nothing to paste: the box is empty.' };
	let object;
	try {

		object = JSON.parse( text );

	} catch ( error ) {

		return { ok: false, error: `This is not valid JSON (${ error.message }).` };

	}

	return checkParams( object, state );

}

/** "unknown parameter" with the closest known name when one is near (a typo). */
function unknownMessage( name, names ) {

	const shown = JSON.stringify( String( name ) );
	const near = closestName( String( name ), names );
	return near ? `Unknown parameter ${ shown }: did you mean "${ near }"?` : `Unknown parameter ${ shown }. Known parameters: ${ names.join( ', ' ) }.`;

}

/** The known name within edit distance 2 of `name` (ties: the first), or null. */
export function closestName( name, names ) {

	let best = null;
	let bestDistance = 3;
	for ( const candidate of names ) {

		const d = editDistance( name, candidate );
		if ( d < bestDistance ) {

			best = candidate;
			bestDistance = d;

		}

	}

	return best;

}

/** Levenshtein distance (insertions, deletions, substitutions). */
export function editDistance( a, b ) {

	let previous = Array.from( { length: b.length + 1 }, ( _, j ) => j );
	for ( let i = 1; i <= a.length; i ++ ) {

		const row = [ i ];
		for ( let j = 1; j <= b.length; j ++ ) {

			row[ j ] = Math.min( previous[ j ] + 1, row[ j - 1 ] + 1, previous[ j - 1 ] + ( a[ i - 1 ] === b[ j - 1 ] ? 0 : 1 ) );

		}

		previous = row;

	}

	return previous[ b.length ];

}
