// The clinician's EMA tracks (web/src/ui/clinician/emaTracks.js): each sensor's two strips on
// one scale, the phones along the top, the frame's line, and the scores in words.

import assert from 'node:assert/strict';
import { test } from 'node:test';
import { drawEmaTracks, heightRange, scoreRows, TRACK_COLORS, TRACK_LAYOUT, tracksHeight } from '../../web/src/ui/clinician/emaTracks.js';
import { recordingContext } from './support/recordingContext.js';

/** A made-up playback document: 11 frames, 0.1 s apart, with a sensor dropout at frame 5. */
function playbackDoc() {

	const t_s = Array.from( { length: 11 }, ( _, i ) => i / 10 );
	const track = ( lift ) => t_s.map( ( t, i ) => [ 10, lift + Math.sin( 6 * t ) * 3 + i * 0.1, 0 ] );
	const head = { tongue_tip: track( 5 ), lower_lip: track( - 20 ) };
	const measured = { tongue_tip: track( 6 ), lower_lip: track( - 19 ) };
	measured.tongue_tip[ 5 ] = [ null, null, null ];
	return { t_s, phones: [ { symbol: 'sil', ipa: null, start_s: 0, end_s: 0.2 }, { symbol: 'T', ipa: 't', start_s: 0.2, end_s: 0.5 }, { symbol: 'AA1', ipa: 'ɑ', start_s: 0.5, end_s: 1 } ], head, measured };

}

test( 'each sensor the document has is drawn twice, the head above the speaker, with the frame’s line', () => {

	const ctx = recordingContext();
	const doc = playbackDoc();
	const drawn = drawEmaTracks( ctx, doc, 5, { width: 618 } );
	assert.deepEqual( drawn.sensors, [ 'tongue_tip', 'lower_lip' ] );
	const plotWidth = 618 - TRACK_LAYOUT.left - TRACK_LAYOUT.right;
	assert.equal( drawn.cursorX, TRACK_LAYOUT.left + plotWidth * 0.5 );
	const texts = ctx.calls.filter( ( c ) => c.name === 'fillText' ).map( ( c ) => c.args[ 0 ] );
	assert.deepEqual( texts, [ 't', 'ɑ', 'tongue tip', 'speaker', 'lower lip', 'speaker' ], 'no label for a pause' );
	// The head's tip strip draws 11 points in one line; the speaker's breaks at the dropout.
	const strokes = ctx.calls.filter( ( c ) => c.name === 'lineTo' || c.name === 'moveTo' );
	const byColor = ( color ) => strokes.filter( ( c ) => c.strokeStyle === color );
	assert.equal( byColor( TRACK_COLORS.head ).length, 22 );
	assert.equal( byColor( TRACK_COLORS.speaker ).filter( ( c ) => c.name === 'moveTo' ).length, 3, 'two moves for the tip (before and after the gap), one for the lip' );
	assert.equal( tracksHeight(), TRACK_LAYOUT.phones + 6 * ( 2 * TRACK_LAYOUT.strip + TRACK_LAYOUT.gap ) );

} );

test( 'one scale for both tracks of a sensor, at least a millimetre tall, missing samples left out', () => {

	assert.deepEqual( heightRange( [ [ 0, 1, 0 ], [ 0, 4, 0 ] ], [ [ 0, 2, 0 ], [ 0, null, 0 ], [ 0, 6, 0 ] ] ), [ 1, 6 ] );
	assert.deepEqual( heightRange( [ [ 0, 2, 0 ] ], [ [ 0, 2.2, 0 ] ] ), [ 1.6, 2.6 ] );
	assert.deepEqual( heightRange( [], [ [ 0, null, 0 ] ] ), [ 0, 1 ] );

} );

test( 'the scores become table rows per sensor and a line per signal with the ranges', () => {

	const { sensors, signals } = scoreRows( {
		sensors: { tongue_tip: { vertical: { r: 0.1049, rmse_mm: 5.13 }, anterior: { r: - 0.34, rmse_mm: 3.4 } } },
		signals: { tip_height: { r: 0.25, baseline_r: 0.38 }, jaw_opening: { r: 0.612, head_range_mm: 5.38, speaker_range_mm: 11.15, range_ratio: 0.4827 }, lip_aperture: { r: null } },
	} );
	assert.deepEqual( sensors, [ [ 'tongue tip', '0.10', '5.1', '-0.34', '3.4' ] ] );
	assert.deepEqual( signals, [ 'tongue-tip height: r 0.25', 'jaw opening: r 0.61, range 5.4 of 11.2 mm (0.48)', 'lip aperture: r –' ] );

} );
