// The time base of the clinician view, pure: EPG frames as one Uint8Array, playback at a
// recording's own frame times, and the target frame shown at each recording frame.

import { EPG_CELLS } from '../core/constants.js';
import { epgIndicesAll, INDEX_SLOTS, INDEX_STRIDE, rowsToFrame } from '../core/epgIndices.js';

/** Frames given as emuR rows (8 strings per frame) -> Uint8Array of 64 cells per frame. */
export function framesFromRows( rowsList ) {

	const frames = new Uint8Array( rowsList.length * EPG_CELLS );
	rowsList.forEach( ( rows, i ) => rowsToFrame( rows, frames, i ) );
	return frames;

}

/** The emuR indices of every frame: { name: Float64Array(n) } for each of INDEX_SLOTS. */
export function indexTracks( frames, count ) {

	const table = epgIndicesAll( frames, count, new Float64Array( count * INDEX_STRIDE ) );
	const tracks = {};
	INDEX_SLOTS.forEach( ( name, k ) => {

		tracks[ name ] = Float64Array.from( { length: count }, ( _, i ) => table[ i * INDEX_STRIDE + k ] );

	} );
	return tracks;

}

/**
 * The frame showing at `elapsed` seconds after the first frame: the last frame whose time from the
 * first is at most `elapsed` (frames are held until the next; binary search).
 */
export function frameAtElapsed( t_s, elapsed ) {

	if ( ! t_s.length ) return - 1;
	const target = t_s[ 0 ] + elapsed + 1e-9;
	let lo = 0, hi = t_s.length - 1;
	if ( target < t_s[ 0 ] ) return 0;
	while ( lo < hi ) {

		const mid = ( lo + hi + 1 ) >> 1;
		if ( t_s[ mid ] <= target ) lo = mid;
		else hi = mid - 1;

	}

	return lo;

}

/**
 * Which target frame stands for each recording frame, as the compare API aligns them: one target
 * frame stands for all; as many frames as the recording go one to one when they have no times;
 * otherwise sample and hold on times measured from each side's first frame.
 */
export function alignTarget( recordingTimes, targetCount, targetTimes = null ) {

	const n = recordingTimes.length;
	const out = new Int32Array( n );
	if ( targetCount <= 1 ) return out;
	if ( ! targetTimes ) {

		for ( let i = 0; i < n; i ++ ) out[ i ] = Math.min( i, targetCount - 1 );
		return out;

	}

	for ( let i = 0; i < n; i ++ ) out[ i ] = frameAtElapsed( targetTimes, recordingTimes[ i ] - recordingTimes[ 0 ] );
	return out;

}

/** Codes of a comparison frame (8 strings of digits, as the compare API gives them) -> 64 cells. */
export function codesFromRows( codeRowsList ) {

	const codes = new Uint8Array( codeRowsList.length * EPG_CELLS );
	codeRowsList.forEach( ( rows, i ) => {

		rows.forEach( ( row, r ) => {

			for ( let c = 0; c < 8; c ++ ) codes[ i * EPG_CELLS + r * 8 + c ] = row.charCodeAt( c ) - 48;

		} );

	} );
	return codes;

}
