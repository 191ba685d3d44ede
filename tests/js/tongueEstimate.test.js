// The listening page's estimate of the learner's tongue (web/src/ui/listen/tongueEstimate.js) on
// the built codebook: live hop by hop, lapsing after a gap; over a finished attempt; none for
// hops without a voice; the vowels only when a vowel is the target.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

import { LIVE_HOLD_S, TongueEstimator, VOWEL_ANCHORS } from '../../web/src/ui/listen/tongueEstimate.js';
import { anchorEntry, codebookPose } from '../../web/src/core/listen/inversion.js';

const BUILD = new URL( '../../assets/build/', import.meta.url );
const DOCUMENT = JSON.parse( readFileSync( new URL( 'inversion-codebook.json', BUILD ) ).toString( 'utf8' ) );

/** Hops of the head's own formants of an anchor (Hz), 10 ms apart from `t0`. */
function hops( estimator, ipa, count, t0 = 0, voiced = true ) {

	const book = estimator.full;
	const entry = anchorEntry( book, ipa );
	const formants = [ 0, 1, 2 ].map( ( k ) => Math.exp( book.logFormants[ entry * 3 + k ] ) );
	return Array.from( { length: count }, ( _, i ) => ( { t: t0 + 0.01 * i, voiced, formants: [ ...formants, 3500 ] } ) );

}

test( 'live: each new hop is estimated once, and the estimate lapses after a gap without a voice', () => {

	const estimator = new TongueEstimator( DOCUMENT );
	const options = { group: 'head', target: 'iy' };
	const said = hops( estimator, 'i', 20 );
	const first = estimator.live( said, options );
	assert.ok( first && first.t === said.at( - 1 ).t );
	assert.deepEqual( estimator.nearestAnchors( first.params ), [ 'i', 'ɪ' ] );
	// More of the same vowel: the same estimate, so the page has nothing new to draw.
	said.push( ...hops( estimator, 'i', 3, 0.2 ) );
	assert.equal( estimator.live( said, options ), first );
	assert.ok( Math.abs( first.t - 0.22 ) < 1e-9, 'its time is the newest voiced hop\'s' );
	// The page's array grows and is trimmed at its start: only the new hops are inverted.
	said.push( ...hops( estimator, 'i', 2, 0.23, false ) );
	said.splice( 0, 10 );
	assert.equal( estimator.live( said, options ), first, 'a short gap keeps the estimate' );
	said.push( ...hops( estimator, 'i', Math.ceil( LIVE_HOLD_S * 100 ) + 1, 0.25, false ) );
	assert.equal( estimator.live( said, options ), null, 'a longer gap ends it' );

} );

test( 'an attempt: the mean pose along its path; none from voiceless hops', () => {

	const estimator = new TongueEstimator( DOCUMENT );
	const ah = estimator.attempt( hops( estimator, 'ɑ', 30 ), { group: 'head', target: 'aa' } );
	assert.equal( ah.frames, 30 );
	assert.equal( estimator.nearestAnchors( ah.params, 1 )[ 0 ], 'ɑ' );
	const target = codebookPose( estimator.full, anchorEntry( estimator.full, 'ɑ' ) );
	assert.ok( Math.abs( ah.params.dorsum_height - target.dorsum_height ) < 0.5, `${ ah.params.dorsum_height } vs ${ target.dorsum_height }` );
	assert.equal( estimator.attempt( hops( estimator, 'ɑ', 30, 0, false ), { group: 'child', target: 'aa' } ), null );

} );

test( 'a vowel target keeps to the vowels; without one /l/ can be found', () => {

	const estimator = new TongueEstimator( DOCUMENT );
	const said = hops( estimator, 'l', 10 );
	assert.equal( estimator.nearestAnchors( estimator.attempt( said, { group: 'head', target: '' } ).params, 1 )[ 0 ], 'l' );
	const asVowel = estimator.attempt( said, { group: 'head', target: 'iy' } );
	assert.ok( ! asVowel || VOWEL_ANCHORS.includes( estimator.nearestAnchors( asVowel.params, 1 )[ 0 ] ) );
	assert.ok( estimator.vowels.count < estimator.full.count && estimator.vowels.blends.every( ( used ) => used.every( ( k ) => k < 10 ) ) );

} );
