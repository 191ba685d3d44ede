// The read-only `window.glasshead` debug object.
//
// End-to-end tests and curious developers read the page's live state here instead of comparing
// pixels. Modules add fields with `registerDebug( name, getter )`; each read of a field calls its
// getter, so the value is always current. The object itself is frozen and its values are frozen
// snapshots: writing to it throws in strict code and does nothing otherwise, and nothing read from
// it can reach back into the application's state.

const getters = new Map();
let current = Object.freeze( {} );

const FIELD_NAME = /^[A-Za-z_$][A-Za-z0-9_$]*$/;

/**
 * A frozen, detached copy of a value: primitives pass through, typed arrays become plain arrays,
 * arrays and plain objects are copied recursively. Functions are refused (the object is data).
 */
export function snapshot( value ) {

	if ( value === null || typeof value !== 'object' ) {

		if ( typeof value === 'function' ) throw new TypeError( 'debug values must be data, not functions' );
		return value;

	}

	if ( ArrayBuffer.isView( value ) ) return Object.freeze( Array.from( value ) );
	if ( Array.isArray( value ) ) return Object.freeze( value.map( snapshot ) );

	const copy = {};
	for ( const key of Object.keys( value ) ) copy[ key ] = snapshot( value[ key ] );
	return Object.freeze( copy );

}

/**
 * Build a frozen object whose enumerable accessor properties call `fieldGetters`.
 * fieldGetters: Map<string, () => any>. A getter that throws reads as null, so one broken field
 * cannot hide the others.
 */
export function createDebugObject( fieldGetters ) {

	const object = {};
	for ( const [ name, getter ] of fieldGetters ) {

		Object.defineProperty( object, name, {
			enumerable: true,
			configurable: false,
			get() {

				try {

					return snapshot( getter() );

				} catch {

					return null;

				}

			},
		} );

	}

	return Object.freeze( object );

}

/**
 * Add (or replace) the field `name` of the debug object; `getter()` returns its current value.
 * Returns a function that removes the field again.
 */
export function registerDebug( name, getter ) {

	if ( typeof name !== 'string' || ! FIELD_NAME.test( name ) ) {

		throw new TypeError( `debug field name must be an identifier, got ${ JSON.stringify( name ) }` );

	}

	if ( typeof getter !== 'function' ) throw new TypeError( `debug field "${ name }" needs a getter function` );

	getters.set( name, getter );
	current = createDebugObject( getters );

	return function unregister() {

		if ( getters.get( name ) === getter ) {

			getters.delete( name );
			current = createDebugObject( getters );

		}

	};

}

/** The current debug object (what `window.glasshead` returns). */
export function debugObject() {

	return current;

}

/**
 * Define `target.glasshead` as a getter-only, non-configurable property that returns the current
 * debug object, so the page cannot replace or delete it.
 */
export function installDebug( target = globalThis ) {

	const existing = Object.getOwnPropertyDescriptor( target, 'glasshead' );
	if ( existing && existing.get === debugObject ) return;

	Object.defineProperty( target, 'glasshead', {
		enumerable: true,
		configurable: false,
		get: debugObject,
	} );

}
