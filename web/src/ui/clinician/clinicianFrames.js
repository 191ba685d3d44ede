// The time base of the clinician view, pure: EPG frames as one Uint8Array, playback at a
// recording's own frame times, and the target frame shown at each recording frame.

import { EPG_CELLS, EPG_COLUMNS, EPG_ELECTRODES, EPG_ROWS } from '../../core/constants.js';
import { contactRows } from '../../core/epgContacts.js';
import { epgIndicesAll, INDEX_SLOTS, INDEX_STRIDE, rowsToFrame } from '../../core/epgIndices.js';

const GRID = Object.freeze( { rows: EPG_ROWS, columns: EPG_COLUMNS } );

/** Frames given as emuR rows (8 strings per frame) -> Uint8Array of EPG_CELLS (64) cells per frame. */
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

			for ( let c = 0; c < EPG_COLUMNS; c ++ ) codes[ i * EPG_CELLS + r * EPG_COLUMNS + c ] = row.charCodeAt( c ) - 48;

		} );

	} );
	return codes;

}

/**
 * The contacts of frame `index` of `frames` (EPG_CELLS per frame): { rows (8 strings, R1 first),
 * contacted, percent of the 62 electrodes }; null when there is no such frame.
 */
export function frameContacts( frames, index ) {

	if ( ! frames || index < 0 ) return null;
	const cells = frames.subarray( index * EPG_CELLS, ( index + 1 ) * EPG_CELLS );
	const contacted = cells.reduce( ( sum, v ) => sum + v, 0 );
	return { rows: contactRows( GRID, cells ), contacted, percent: Math.round( 100000 * contacted / EPG_ELECTRODES ) / 1000 };

}

/** Index tracks ({ name: Float64Array }) sampled at `aligned` frames: one value per aligned frame. */
export function alignedTracks( tracks, aligned ) {

	const out = {};
	for ( const [ name, values ] of Object.entries( tracks ) ) out[ name ] = Float64Array.from( aligned, ( k ) => values[ k ] );
	return out;

}

/**
 * What the index plot draws for the chosen { target, recording, comparison } at `frame`: the
 * recording's tracks and the target's aligned to the recording's frames (or, alone, to its own),
 * as IndexPlot.set takes them. `times` are the target's when there is no recording (null for one
 * static frame); colors { recording, target }.
 */
export function plotTracks( { target, recording, comparison, frame }, times, colors ) {

	const tracks = [];
	const baseTimes = recording ? recording.t_s : ( target.count > 1 ? times : Float64Array.of( 0, 0.1 ) );
	if ( recording ) tracks.push( { label: `recording ${ recording.name }`, indices: recording.indices, color: colors.recording } );
	if ( target ) {

		const aligned = recording
			? ( comparison ? Int32Array.from( comparison.reference_frame ) : alignTarget( recording.t_s, target.count, target.t_s ) )
			: Int32Array.from( baseTimes, ( _, i ) => Math.min( i, target.count - 1 ) );
		tracks.push( { label: `target ${ target.label }`, indices: alignedTracks( target.indices, aligned ), color: colors.target, dash: [ 6, 4 ] } );

	}

	return { t_s: baseTimes, tracks, current: recording || target.count > 1 ? frame : null };

}

/**
 * The table of indices at `frame` (the target's at `targetFrame`): per name { name, target,
 * recording, difference } (null where there is none; the difference is the compare API's when
 * there is a comparison, else recording minus target).
 */
export function indexRows( { target, recording, comparison, frame }, targetFrame, names ) {

	return names.map( ( name ) => {

		const a = target ? target.indices[ name ][ targetFrame ] : null;
		const b = recording ? recording.indices[ name ][ frame ] : null;
		const d = comparison?.index_difference[ name ]?.[ frame ] ?? ( a !== null && b !== null ? b - a : null );
		return { name, target: a, recording: b, difference: d };

	} );

}

// The chosen { target, recording, comparison, frame } of the view: the recording's frames are the
// time base when there is one, else the target's.

/** Frames of the time base (at least 1). */
export function frameCount( { target, recording } ) {

	return Math.max( 1, recording?.count ?? target?.count ?? 1 );

}

/** Times of the time base's frames, s (null for a target of one static frame, or nothing). */
export function frameTimes( { target, recording } ) {

	return recording?.t_s ?? ( target?.t_s ? Float64Array.from( target.t_s ) : null );

}

/** The target frame shown at the current frame (-1 without a target). */
export function targetFrameAt( { target, recording, comparison, frame } ) {

	if ( ! target ) return - 1;
	if ( comparison ) return comparison.reference_frame[ frame ];
	if ( recording ) return alignTarget( recording.t_s, target.count, target.t_s )[ frame ];
	return Math.min( frame, target.count - 1 );

}
