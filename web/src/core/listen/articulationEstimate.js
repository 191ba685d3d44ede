// The learner's articulation guessed from the sound: the vowel targets' parameters blended by how
// near the measured F1 and F2 lie to each vowel's norm. It is an estimate from the sound, not a
// measurement of the tongue: two different tongues can make the same formants, and the blend can
// only give tongues between the targets.
//
// The space is the learner group's normalised formant space: F1 and F2 as z-scores against the
// mean and standard deviation of all the group's vowel tokens (Lobanov 1971), computed from the
// norms' per-vowel means, standard deviations and counts, so that F1's smaller range weighs as
// much as F2's larger one. The weights are Shepard's (1968) inverse distance weights over the
// nearest few vowels, in Franke and Nielson's (1980) form: a vowel's weight falls to zero at the
// distance of the first vowel left out, so the estimate does not jump when that vowel takes a
// place among the nearest.
//
// Pure functions over plain objects: no DOM, no three.js.

/** Vowels blended: the nearest three (two would leave a measure between three vowels to two of them). */
export const NEAREST_VOWELS = 3;
/** Inverse distance weights fall as 1 / d^WEIGHT_POWER (Shepard's usual 2). */
export const WEIGHT_POWER = 2;
/** A measure closer than this to a vowel's mean (z units) is that vowel exactly. */
const AT_VOWEL_Z = 1e-12;

/**
 * The mean and standard deviation of F1 and F2 over every token of a group (Hz), from its norms
 * ({ code: { n, f1: { mean, sd }, f2: { mean, sd } } } of vowel-norms.json): the pooled
 * within-vowel variance plus the spread of the vowels' means. `codes` limits it to some vowels.
 * @returns {{ f1: { mean: number, sd: number }, f2: { mean: number, sd: number } }}
 */
export function groupFormantScale( vowels, codes = Object.keys( vowels ) ) {

	const scale = {};
	for ( const formant of [ 'f1', 'f2' ] ) {

		let count = 0;
		let sum = 0;
		for ( const code of codes ) {

			const n = vowels[ code ].n ?? 1;
			count += n;
			sum += n * vowels[ code ][ formant ].mean;

		}

		const mean = sum / count;
		let squares = 0;
		for ( const code of codes ) {

			const { n = 1 } = vowels[ code ];
			const { mean: m, sd } = vowels[ code ][ formant ];
			squares += Math.max( 0, n - 1 ) * sd * sd + n * ( m - mean ) * ( m - mean );

		}

		const sd = Math.sqrt( squares / Math.max( 1, count - 1 ) );
		if ( ! ( sd > 0 ) ) throw new RangeError( `the norms give ${ formant.toUpperCase() } no spread` );
		scale[ formant ] = { mean, sd };

	}

	return scale;

}

/** (F1, F2) in Hz as [ z1, z2 ] against a groupFormantScale. */
export function normalisedFormants( f1, f2, scale ) {

	return [ ( f1 - scale.f1.mean ) / scale.f1.sd, ( f2 - scale.f2.mean ) / scale.f2.sd ];

}

/**
 * The weights of the `nearest` vowels to (F1, F2), Hz, in the group's normalised space: { code:
 * weight }, summing to 1, the nearest first. A measure at a vowel's mean gives it weight 1.
 * `vowels`: the norms of the vowels that may take part.
 */
export function vowelWeights( f1, f2, vowels, { nearest = NEAREST_VOWELS, power = WEIGHT_POWER, scale = groupFormantScale( vowels ) } = {} ) {

	const [ z1, z2 ] = normalisedFormants( f1, f2, scale );
	const ranked = Object.entries( vowels ).map( ( [ code, entry ] ) => {

		const [ v1, v2 ] = normalisedFormants( entry.f1.mean, entry.f2.mean, scale );
		return { code, distance: Math.hypot( z1 - v1, z2 - v2 ) };

	} ).sort( ( a, b ) => a.distance - b.distance );
	const chosen = ranked.slice( 0, Math.max( 1, nearest ) );
	const at = chosen.filter( ( { distance } ) => distance < AT_VOWEL_Z );
	if ( at.length ) return Object.fromEntries( chosen.map( ( { code } ) => [ code, at.some( ( v ) => v.code === code ) ? 1 / at.length : 0 ] ) );

	// Franke and Nielson: ( ( R - d ) / ( R d ) )^p, R the distance of the first vowel left out.
	const radius = ranked[ chosen.length ]?.distance ?? Infinity;
	const raw = chosen.map( ( { distance } ) => ( Number.isFinite( radius ) ? Math.max( 0, radius - distance ) / ( radius * distance ) : 1 / distance ) ** power );
	const total = raw.reduce( ( a, b ) => a + b, 0 );
	// Every chosen vowel as far as the next one (a tie): an even share.
	return Object.fromEntries( chosen.map( ( { code }, k ) => [ code, total > 0 ? raw[ k ] / total : 1 / chosen.length ] ) );

}

/**
 * Parameters blended by `weights` ({ code: weight }) from `targets` ({ code: { name: value } }):
 * each parameter is the weighted mean over the weighted vowels whose target gives it (weights
 * renormalised over them); a parameter that none gives keeps its value in `base`.
 */
export function blendParams( weights, targets, base = {} ) {

	const sums = new Map();
	for ( const [ code, weight ] of Object.entries( weights ) ) {

		if ( ! ( weight > 0 ) ) continue;
		for ( const [ name, value ] of Object.entries( targets[ code ] ?? {} ) ) {

			if ( ! Number.isFinite( value ) ) continue;
			const sum = sums.get( name ) ?? { value: 0, weight: 0 };
			sum.value += weight * value;
			sum.weight += weight;
			sums.set( name, sum );

		}

	}

	const params = { ...base };
	for ( const [ name, sum ] of sums ) params[ name ] = sum.value / sum.weight;
	return params;

}

/**
 * The learner's articulation estimated from a measured vowel { f1, f2 } (Hz): { weights, params,
 * z } or null without a measure or without vowels that have both a norm and a target.
 * @param {{ f1: number, f2: number }|null} measure
 * @param {Object<string, object>} vowels the group's norms, { code: entry } of vowel-norms.json
 * @param {Object<string, Object<string, number>>} targets { code: params } of the vowels' phoneme targets
 * @param {{ nearest?: number, base?: Object<string, number> }} options `base`: the values of
 *   parameters no target gives
 */
export function estimateArticulation( measure, vowels, targets, { nearest = NEAREST_VOWELS, base = {} } = {} ) {

	if ( ! ( measure?.f1 > 0 && measure?.f2 > 0 ) ) return null;
	const known = Object.fromEntries( Object.entries( vowels ?? {} ).filter( ( [ code ] ) => targets?.[ code ] ) );
	if ( ! Object.keys( known ).length ) return null;
	// The space is the whole group's, whichever vowels have targets.
	const scale = groupFormantScale( vowels );
	const weights = vowelWeights( measure.f1, measure.f2, known, { nearest, scale } );
	return { weights, params: blendParams( weights, targets, base ), z: normalisedFormants( measure.f1, measure.f2, scale ) };

}
