// What the fit page sends, pure: the kind its chosen files make, and the form POST /fits takes
// (docs/fits.md). One file is a fit of its own kind; two or more of a contour, EPG frames and
// sensors are one combined fit, each with its weight. A surface is fitted alone.

/** The measurements the page offers, in its order: the field's name, its kind and words. */
export const FIT_PARTS = Object.freeze( [
	Object.freeze( { kind: 'contour', label: 'Tongue contour', accept: '.csv,.txt', hint: 'CSV, x_mm,y_mm per line, root to tip' } ),
	Object.freeze( { kind: 'epg', label: 'EPG frames', accept: '.json,.csv,.ssff,.epg', hint: 'emuR JSON, EPG CSV or SSFF' } ),
	Object.freeze( { kind: 'ema', label: 'Sensors (EMA)', accept: '.csv,.json,.txt', hint: 'one frame: point,x_mm,y_mm[,z_mm] per sensor' } ),
	Object.freeze( { kind: 'surface', label: 'Tongue surface', accept: '.obj,.ply', hint: 'OBJ or PLY, fitted alone' } ),
] );

/** The parts a combined fit takes together. */
const COMBINED = Object.freeze( [ 'contour', 'epg', 'ema' ] );

/**
 * The fit the chosen files make: { kind, problem } where `files` is { kind: File-like | null }.
 * `problem` (words for the page) is set, and `kind` null, when the files cannot be fitted.
 */
export function fitKindFor( files ) {

	const chosen = FIT_PARTS.map( ( part ) => part.kind ).filter( ( kind ) => files[ kind ] );
	if ( chosen.length === 0 ) return { kind: null, problem: 'Choose a file to fit.' };
	if ( chosen.length === 1 ) return { kind: chosen[ 0 ], problem: null };
	if ( chosen.includes( 'surface' ) ) return { kind: null, problem: 'A surface is fitted alone: clear the other files, or the surface.' };
	return { kind: 'combined', problem: null };

}

/**
 * The multipart form of POST /fits for `files` ({ kind: File | null }), `weights` ({ kind:
 * number }, used only by a combined fit, a weight of 1 left out as the default) and `name`.
 * Throws when the files make no fit (fitKindFor's problem).
 */
export function fitForm( files, { weights = {}, name = '', FormDataImpl = globalThis.FormData } = {} ) {

	const { kind, problem } = fitKindFor( files );
	if ( ! kind ) throw new Error( problem );
	const form = new FormDataImpl();
	form.append( 'kind', kind );
	if ( name.trim() ) form.append( 'name', name.trim() );
	if ( kind !== 'combined' ) {

		form.append( 'file', files[ kind ], files[ kind ].name );
		return form;

	}

	for ( const part of COMBINED ) {

		if ( ! files[ part ] ) continue;
		form.append( `${ part }_file`, files[ part ], files[ part ].name );
		const weight = Number( weights[ part ] );
		if ( Number.isFinite( weight ) && weight !== 1 ) form.append( `${ part }_weight`, String( weight ) );

	}

	return form;

}

/** A running fit's progress in words: "312 evaluations, best 1.07". */
export function progressWords( progress ) {

	const evaluations = progress?.evaluations ?? 0;
	const best = Number.isFinite( progress?.best_error ) ? `, best ${ progress.best_error.toFixed( 3 ) }` : '';
	return `${ evaluations } evaluations${ best }`;

}
