// The tongue from the voice: acoustic-to-articulatory inversion by codebook (twin of
// server/glasshead/acoustics/inversion.py, whose docstring gives the method;
// tests/vectors/inversion.json holds both to the same choices).
//
// A codebook (assets/build/inversion-codebook.json) holds poses of the head's vowel space with
// their own tract's F1 to F3 and a prior (the distance to the nearest anchor target). A frame's
// acoustic cost for a pose is the mean over F1 to F3 of ( ln( F * scale / F_pose ) / sd )^2; its
// local cost adds the weighted prior; a step from one pose to the next costs the weighted mean
// squared distance of their parameters, each in its spread over the anchors. A frame without
// F1 to F3, or whose best acoustic cost passes INVERSION_REJECT_COST, gets no pose (null).
//
// Pure functions over plain arrays: no DOM, no three.js.

import {
	INVERSION_CANDIDATES, INVERSION_CONTINUITY_WEIGHT, INVERSION_FORMANT_SD,
	INVERSION_PRIOR_WEIGHT, INVERSION_REJECT_COST,
} from '../shared.generated.js';

/**
 * The codebook of an inversion-codebook.json document, in typed arrays (allocates; once).
 * @returns {{ parameters: string[], fixed: object, spread: Float64Array, count: number, size: number,
 *   logFormants: Float64Array, prior: Float64Array, scaled: Float64Array, values: Float64Array,
 *   groupScale: object, anchors: object }}
 */
export function readCodebook( document ) {

	const { parameters, fixed, spread, entries } = document;
	const count = entries.values.length;
	const size = parameters.length;
	if ( ! ( count > 0 ) || spread.length !== size || entries.formants.length !== count || entries.prior.length !== count || entries.anchors.length !== count ) {

		throw new RangeError( 'the inversion codebook\'s entries, formants, priors and parameters do not agree' );

	}

	const values = new Float64Array( count * size );
	const scaled = new Float64Array( count * size );
	const logFormants = new Float64Array( count * 3 );
	for ( let i = 0; i < count; i ++ ) {

		for ( let p = 0; p < size; p ++ ) {

			values[ i * size + p ] = entries.values[ i ][ p ];
			scaled[ i * size + p ] = entries.values[ i ][ p ] / spread[ p ];

		}

		for ( let k = 0; k < 3; k ++ ) logFormants[ i * 3 + k ] = Math.log( entries.formants[ i ][ k ] );

	}

	return {
		parameters: [ ...parameters ], fixed: { ...fixed }, spread: Float64Array.from( spread ), count, size, values, scaled, logFormants,
		prior: Float64Array.from( entries.prior ), groupScale: { ...document.group_scale },
		anchors: [ ...document.anchors ], blends: entries.anchors.map( ( used ) => [ ...used ] ),
	};

}

/** The codebook of the entries that blend only `anchors` (IPA), for example the vowels. */
export function keepTo( codebook, anchors ) {

	const unknown = anchors.filter( ( a ) => ! codebook.anchors.includes( a ) );
	if ( unknown.length ) throw new RangeError( `the codebook has no anchor ${ unknown.join( ', ' ) }` );
	const allowed = new Set( anchors.map( ( a ) => codebook.anchors.indexOf( a ) ) );
	const rows = [];
	codebook.blends.forEach( ( used, i ) => used.every( ( k ) => allowed.has( k ) ) && rows.push( i ) );
	const { size } = codebook;
	const pick = ( array, width ) => {

		const out = new Float64Array( rows.length * width );
		rows.forEach( ( row, i ) => out.set( array.subarray( row * width, ( row + 1 ) * width ), i * width ) );
		return out;

	};

	return {
		...codebook, count: rows.length, values: pick( codebook.values, size ), scaled: pick( codebook.scaled, size ),
		logFormants: pick( codebook.logFormants, 3 ), prior: pick( codebook.prior, 1 ), blends: rows.map( ( i ) => codebook.blends[ i ] ),
	};

}

/** The entry that is the anchor `ipa` alone, or -1. */
export function anchorEntry( codebook, ipa ) {

	const k = codebook.anchors.indexOf( ipa );
	return codebook.blends.findIndex( ( used ) => used.length === 1 && used[ 0 ] === k );

}

/**
 * A listening hop's F1 to F3 when it is voiced and has all three, else null: silence, noise and
 * voiceless sounds get no tongue.
 */
export function estimableFormants( hop ) {

	const formants = hop?.formants;
	if ( ! hop?.voiced || ! formants || formants.length < 3 ) return null;
	for ( let k = 0; k < 3; k ++ ) if ( formants[ k ] == null || ! Number.isFinite( formants[ k ] ) ) return null;
	return [ formants[ 0 ], formants[ 1 ], formants[ 2 ] ];

}

/** The factors mapping a speaker group's F1 to F3 onto the head's ([ 1, 1, 1 ] for none or 'head'). */
export function groupScale( codebook, group ) {

	if ( group == null || group === 'head' ) return [ 1, 1, 1 ];
	const scale = codebook.groupScale[ group ];
	if ( ! Array.isArray( scale ) || scale.length !== 3 ) throw new RangeError( `no formant scale for the group ${ group }: the codebook has ${ Object.keys( codebook.groupScale ).sort().join( ', ' ) }` );
	return scale;

}

/** Entry `index` as the rigs' parameters by name. */
export function codebookPose( codebook, index ) {

	const params = { ...codebook.fixed };
	for ( let p = 0; p < codebook.size; p ++ ) params[ codebook.parameters[ p ] ] = codebook.values[ index * codebook.size + p ];
	return params;

}

/**
 * Each pose's acoustic cost for measured F1 to F3 (Hz), each times its `scale` (one factor for
 * all, or one per formant), into `out` (Float64Array of count), or
 * null when the frame has no F1 to F3 or the best pose costs more than INVERSION_REJECT_COST.
 */
export function acousticCosts( formants, codebook, scale = 1, out = new Float64Array( codebook.count ) ) {

	if ( ! formants || formants.length < 3 ) return null;
	const logs = [ 0, 0, 0 ];
	for ( let k = 0; k < 3; k ++ ) {

		const f = formants[ k ];
		if ( f == null || ! Number.isFinite( f ) || f <= 0 ) return null;
		logs[ k ] = Math.log( f * ( typeof scale === 'number' ? scale : scale[ k ] ) );

	}

	const { logFormants, count } = codebook;
	let best = Infinity;
	for ( let i = 0; i < count; i ++ ) {

		let sum = 0;
		for ( let k = 0; k < 3; k ++ ) {

			const z = ( logs[ k ] - logFormants[ i * 3 + k ] ) / INVERSION_FORMANT_SD[ k ];
			sum += z * z;

		}

		out[ i ] = sum / 3;
		if ( out[ i ] < best ) best = out[ i ];

	}

	return best <= INVERSION_REJECT_COST ? out : null;

}

/** Mean squared distance between entries a and b, each parameter in its spread. */
function move( codebook, a, b ) {

	const { scaled, size } = codebook;
	let sum = 0;
	for ( let p = 0; p < size; p ++ ) {

		const d = scaled[ a * size + p ] - scaled[ b * size + p ];
		sum += d * d;

	}

	return sum / size;

}

/**
 * The entry for one live frame given the frame before's (null: none), or null. `scratch`, a
 * Float64Array of the codebook's count, spares the allocation.
 */
export function invertFrame( formants, codebook, scale = 1, previous = null, scratch = undefined ) {

	const costs = acousticCosts( formants, codebook, scale, scratch );
	if ( ! costs ) return null;
	let best = - 1;
	let bestCost = Infinity;
	for ( let i = 0; i < codebook.count; i ++ ) {

		let total = costs[ i ] + INVERSION_PRIOR_WEIGHT * codebook.prior[ i ];
		if ( previous != null ) total += INVERSION_CONTINUITY_WEIGHT * move( codebook, i, previous );
		if ( total < bestCost ) {

			bestCost = total;
			best = i;

		}

	}

	return best;

}

/** The INVERSION_CANDIDATES best entries by local cost, ties to the lower index. */
function candidates( local ) {

	const order = Array.from( local.keys() );
	order.sort( ( a, b ) => local[ a ] - local[ b ] || a - b );
	return order.slice( 0, INVERSION_CANDIDATES );

}

/** The cheapest path through a run of frames' local costs (Viterbi over each frame's candidates). */
function path( locals, codebook ) {

	const rows = locals.map( candidates );
	let score = rows[ 0 ].map( ( i ) => locals[ 0 ][ i ] );
	const back = [];
	for ( let k = 1; k < rows.length; k ++ ) {

		const from = rows[ k - 1 ];
		const choice = [];
		const next = rows[ k ].map( ( to ) => {

			let best = 0;
			let bestCost = Infinity;
			for ( let j = 0; j < from.length; j ++ ) {

				const cost = score[ j ] + INVERSION_CONTINUITY_WEIGHT * move( codebook, from[ j ], to );
				if ( cost < bestCost ) {

					bestCost = cost;
					best = j;

				}

			}

			choice.push( best );
			return bestCost + locals[ k ][ to ];

		} );
		back.push( choice );
		score = next;

	}

	let at = 0;
	for ( let j = 1; j < score.length; j ++ ) if ( score[ j ] < score[ at ] ) at = j;
	const out = [ rows[ rows.length - 1 ][ at ] ];
	for ( let k = rows.length - 1; k > 0; k -- ) {

		at = back[ k - 1 ][ at ];
		out.push( rows[ k - 1 ][ at ] );

	}

	return out.reverse();

}

/**
 * The entry of every frame of a track (F1 to F3 per frame, or null), null where no tongue can be
 * estimated; the cheapest path through each run of estimable frames.
 * @returns {(number|null)[]}
 */
export function invertTrack( frames, codebook, scale = 1 ) {

	const out = new Array( frames.length ).fill( null );
	let run = [];
	const closeRun = () => {

		if ( ! run.length ) return;
		path( run.map( ( r ) => r.local ), codebook ).forEach( ( entry, k ) => ( out[ run[ k ].index ] = entry ) );
		run = [];

	};

	frames.forEach( ( formants, index ) => {

		const costs = acousticCosts( formants, codebook, scale );
		if ( ! costs ) return closeRun();
		const local = new Float64Array( codebook.count );
		for ( let i = 0; i < codebook.count; i ++ ) local[ i ] = costs[ i ] + INVERSION_PRIOR_WEIGHT * codebook.prior[ i ];
		run.push( { index, local } );

	} );
	closeRun();
	return out;

}
