// Benchmark: the tongue from the voice, one 10 ms frame inverted live in JavaScript
// (core/listen/inversion.js invertFrame, the frame before's entry given), over the built codebook
// kept to the vowels, as the listening page runs it. Frames: the codebook's own formants of
// seeded random entries, each moved by up to 5 %. Measured in this run, over the same frames:
//   ours   typed arrays made once (log formants, parameters in their spread), no allocation;
//   plain  the same costs written plainly: entries as objects, logs taken per frame, the
//          continuity as map and reduce over each entry's parameters, as a first version would.
// Checked on the way: ours and plain choose the same entry for every frame. The goal:
// one frame in at most 2 ms.
//
//   node bench/inversion.bench.mjs [samples]   (GLASSHEAD_BENCH_QUICK=1: 3 samples x 20 frames)
import { codebookPose, invertFrame, keepTo, readCodebook } from '../web/src/core/listen/inversion.js';
import { INVERSION_CONTINUITY_WEIGHT, INVERSION_FORMANT_SD, INVERSION_PRIOR_WEIGHT, INVERSION_REJECT_COST } from '../web/src/core/constants.js';
import { builtFile } from './support/assets.mjs';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const SAMPLES = Number( process.argv[ 2 ] ?? count( 30, 3 ) );
const FRAMES = count( 200, 20 );
const SEED = 531;
const GOAL_MS = 2;
const VOWELS = [ 'i', 'ɪ', 'ɛ', 'æ', 'ʌ', 'ɑ', 'ɔ', 'ʊ', 'u', 'ɝ' ];

const document = JSON.parse( builtFile( 'inversion-codebook.json' ).toString( 'utf8' ) );
const codebook = keepTo( readCodebook( document ), VOWELS );
const next = random( SEED );
const frames = Array.from( { length: SAMPLES * FRAMES }, () => {

	const entry = Math.floor( next() * codebook.count );
	return [ 0, 1, 2 ].map( ( k ) => Math.exp( codebook.logFormants[ entry * 3 + k ] ) * ( 0.95 + 0.1 * next() ) );

} );
const now = () => Number( process.hrtime.bigint() ) / 1e6;

// The plain version: the same costs (docs/acoustics.md) over entries as objects.
const plainEntries = Array.from( { length: codebook.count }, ( _, i ) => {

	const pose = codebookPose( codebook, i );
	return {
		formants: [ 0, 1, 2 ].map( ( k ) => Math.exp( codebook.logFormants[ i * 3 + k ] ) ),
		scaled: codebook.parameters.map( ( name, p ) => pose[ name ] / document.spread[ p ] ),
		prior: codebook.prior[ i ],
	};

} );

function plainInvert( formants, previous ) {

	const acoustic = plainEntries.map( ( e ) => e.formants.map( ( f, k ) => ( ( Math.log( formants[ k ] ) - Math.log( f ) ) / INVERSION_FORMANT_SD[ k ] ) ** 2 ).reduce( ( a, b ) => a + b ) / 3 );
	if ( Math.min( ...acoustic ) > INVERSION_REJECT_COST ) return null;
	const totals = plainEntries.map( ( e, i ) => acoustic[ i ] + INVERSION_PRIOR_WEIGHT * e.prior + ( previous == null ? 0
		: INVERSION_CONTINUITY_WEIGHT * e.scaled.map( ( v, p ) => ( v - plainEntries[ previous ].scaled[ p ] ) ** 2 ).reduce( ( a, b ) => a + b ) / e.scaled.length ) );
	return totals.indexOf( Math.min( ...totals ) );

}

/** Median over samples of the mean ms per frame, each frame given the one before's entry. */
function time( invert ) {

	const perSample = [];
	const chosen = [];
	for ( let sample = 0; sample < SAMPLES; sample ++ ) {

		let previous = null;
		const start = now();
		for ( let f = 0; f < FRAMES; f ++ ) {

			const entry = invert( frames[ sample * FRAMES + f ], previous );
			chosen.push( entry );
			previous = entry ?? previous;

		}

		perSample.push( ( now() - start ) / FRAMES );

	}

	return { ms: median( perSample ), chosen };

}

const scratch = new Float64Array( codebook.count );
const ourInvert = ( formants, previous ) => invertFrame( formants, codebook, 1, previous, scratch );
for ( let warm = 0; warm < 2; warm ++ ) {

	time( ourInvert );
	time( plainInvert );

}

const ours = time( ourInvert );
const plain = time( plainInvert );
const same = ours.chosen.every( ( entry, k ) => entry === plain.chosen[ k ] );
const estimated = ours.chosen.filter( ( entry ) => entry !== null ).length;
console.log( `inversion: ${ codebook.count } vowel entries of ${ codebook.size } parameters; ${ SAMPLES } samples x ${ FRAMES } frames, seed ${ SEED }` );
console.log( `  one frame  ours  ${ ours.ms.toFixed( 4 ) } ms median   plain ${ plain.ms.toFixed( 4 ) } ms   ratio ${ ( plain.ms / ours.ms ).toFixed( 1 ) }x   goal <= ${ GOAL_MS } ms: ${ ours.ms <= GOAL_MS ? 'met' : 'NOT met' }` );
console.log( JSON.stringify( { benchmark: 'inversion', ours_median_ms: Number( ours.ms.toPrecision( 3 ) ), plain_median_ms: Number( plain.ms.toPrecision( 3 ) ), ratio: Number( ( plain.ms / ours.ms ).toFixed( 1 ) ), goal_ms: GOAL_MS, goal_met: ours.ms <= GOAL_MS } ) );
check( 'ours and plain choose the same entry for every frame', same && estimated === ours.chosen.length, `${ estimated } of ${ ours.chosen.length } estimated` );
