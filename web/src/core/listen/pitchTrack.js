// Pitch tracking: per frame, the choice among YIN's candidates (pitch.js) and "unvoiced" that
// makes the cheapest path through the frames, by dynamic programming (Viterbi), after Boersma's
// path finder (Boersma 1993, "Accurate short-term analysis of the fundamental frequency and the
// harmonics-to-noise ratio of a sampled sound", IFA Proceedings 17, 97-110, section 5; Praat's
// Sound_to_Pitch). A lone frame cannot tell a fundamental from its undertone (a periodic signal
// repeats at 2T as well as at T) nor, in a high vowel whose F1 sits on the second harmonic, from
// its octave; the frames around it can: a path pays for every octave it jumps.
//
// Costs, in units of aperiodicity (d', about 1 - Praat's correlation strength):
//   a voiced candidate     d' - OCTAVE_COST log2( f / floor )      (higher pitches a little cheaper)
//   unvoiced               1 - VOICING_STRENGTH, or 0 below the voicing floor (then no voiced candidate)
//   voiced to voiced       OCTAVE_JUMP_COST |log2( f / f_before )|
//   voiced <-> unvoiced    VOICED_UNVOICED_COST
// Live, a frame is decided once `lookahead` frames after it are in: the cheapest path to the
// newest frame is followed back to it. Decisions depend on the frames alone, never on when they
// arrived, so streaming and whole-file analyses agree.

import { OCTAVE_COST, OCTAVE_JUMP_COST, VOICED_UNVOICED_COST, VOICING_STRENGTH } from './params.js';

/**
 * A tracker over frames of at most `candidates` voiced candidates each.
 * @param {{ candidates: number, lookahead: number, floor: number }} options floor: the pitch floor, Hz
 */
export function createPitchTracker( { candidates, lookahead, floor } ) {

	const slots = candidates + 1; // slot 0: unvoiced
	const depth = lookahead + 2; // frames kept: the one to decide, those after it, and one spare
	return {
		candidates, lookahead, floor, slots, depth,
		f0: new Float64Array( depth * slots ),
		octaves: new Float64Array( depth * slots ), // log2( f0 / floor ) of each candidate
		cost: new Float64Array( depth * slots ),
		back: new Int16Array( depth * slots ),
		count: new Int32Array( depth ),
		frames: 0,
	};

}

/**
 * Add the next frame: its candidates f0s[ 0 .. n ) (Hz) and their aperiodicities, and whether it
 * is loud enough to be voiced at all. Allocates nothing. Returns the frame's index.
 */
export function addPitchFrame( tracker, f0s, aperiodicities, n, loud ) {

	const { slots, depth, floor, f0, octaves, cost, back } = tracker;
	// Constants as locals, and each case in its own loop: a value that is sometimes a module
	// constant and sometimes computed would be boxed on every pass.
	const unvoicedCost = 1 - VOICING_STRENGTH, switchCost = VOICED_UNVOICED_COST;
	const jumpCost = OCTAVE_JUMP_COST, octaveCost = OCTAVE_COST;
	const k = tracker.frames;
	const row = ( k % depth ) * slots;
	const count = loud ? Math.min( n, slots - 1 ) : 0;
	tracker.count[ k % depth ] = count;
	cost[ row ] = loud ? unvoicedCost : 0;
	f0[ row ] = 0;
	for ( let i = 1; i <= count; i ++ ) {

		f0[ row + i ] = f0s[ i - 1 ];
		octaves[ row + i ] = Math.log2( f0s[ i - 1 ] / floor );
		cost[ row + i ] = aperiodicities[ i - 1 ] - octaveCost * octaves[ row + i ];

	}

	if ( k > 0 ) {

		const before = ( ( k - 1 ) % depth ) * slots;
		const beforeCount = tracker.count[ ( k - 1 ) % depth ];
		// Unvoiced now: from unvoiced for nothing, from any voiced candidate for a switch.
		let best = cost[ before ], from = 0;
		for ( let j = 1; j <= beforeCount; j ++ ) {

			if ( cost[ before + j ] + switchCost < best ) {

				best = cost[ before + j ] + switchCost;
				from = j;

			}

		}

		cost[ row ] += best;
		back[ row ] = from;
		let lowest = cost[ row ];
		// Voiced now: from unvoiced for a switch, from a voiced candidate for the octaves jumped.
		for ( let i = 1; i <= count; i ++ ) {

			best = cost[ before ] + switchCost;
			from = 0;
			for ( let j = 1; j <= beforeCount; j ++ ) {

				const total = cost[ before + j ] + jumpCost * Math.abs( octaves[ row + i ] - octaves[ before + j ] );
				if ( total < best ) {

					best = total;
					from = j;

				}

			}

			cost[ row + i ] += best;
			back[ row + i ] = from;
			if ( cost[ row + i ] < lowest ) lowest = cost[ row + i ];

		}

		// Only differences matter: keep the numbers small over long recordings.
		for ( let i = 0; i <= count; i ++ ) cost[ row + i ] -= lowest;

	}

	tracker.frames = k + 1;
	return k;

}

/**
 * The pitch of frame k (Hz, 0 when unvoiced) on the cheapest path to the newest frame, looking
 * no further than k + lookahead. Frame k must be among the kept ones (decide each frame before
 * lookahead + 2 more are added). Allocates nothing.
 */
export function decidePitch( tracker, k ) {

	const { slots, depth, cost, back } = tracker;
	const end = Math.min( tracker.frames - 1, k + tracker.lookahead );
	if ( k < 0 || k > end || tracker.frames - 1 - k >= depth ) throw new RangeError( `pitch frame ${ k } is not held (frames: ${ tracker.frames })` );
	let row = ( end % depth ) * slots;
	let state = 0;
	for ( let i = 1; i <= tracker.count[ end % depth ]; i ++ ) if ( cost[ row + i ] < cost[ row + state ] ) state = i;
	for ( let j = end; j > k; j -- ) {

		state = back[ ( j % depth ) * slots + state ];

	}

	row = ( k % depth ) * slots;
	return tracker.f0[ row + state ];

}
