// The inversion in JS (web/src/core/listen/inversion.js) against the shared vectors that Python
// writes (tests/vectors/inversion.json): the same entry for every frame, live and over the whole
// track, on a hand-made codebook; and what a hop without a voice gives.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readVectors } from './support/vectors.js';

import { anchorEntry, codebookPose, estimableFormants, groupScale, invertFrame, invertTrack, keepTo, readCodebook } from '../../web/src/core/listen/inversion.js';

const VECTORS = readVectors( 'inversion.json' );
const FULL = readCodebook( VECTORS.fixtures.codebook );

test( 'every track of the shared vectors: the same entries as Python, live and over the track', () => {

	assert.ok( VECTORS.cases.length >= 4 );
	for ( const { description, input, expected } of VECTORS.cases ) {

		const codebook = input.keep_to ? keepTo( FULL, input.keep_to ) : FULL;
		const scale = groupScale( codebook, input.group );
		assert.equal( codebook.count, expected.kept_entries, `${ description }: entries kept` );
		let previous = null;
		const live = input.frames.map( ( frame ) => {

			const entry = invertFrame( frame, codebook, scale, previous );
			previous = entry ?? previous;
			return entry;

		} );
		assert.deepEqual( live, expected.live, `${ description }: live` );
		assert.deepEqual( invertTrack( input.frames, codebook, scale ), expected.track, `${ description }: track` );

	}

} );

test( 'an anchor is its own pose, and a bad group or anchor is named', () => {

	const entry = anchorEntry( FULL, 'a' );
	assert.deepEqual( codebookPose( FULL, entry ), { jaw_opening: 2, height: 6, front: 3 } );
	assert.throws( () => groupScale( FULL, 'teenager' ), /teenager/ );
	assert.throws( () => keepTo( FULL, [ 'i', 'ø' ] ), /ø/ );
	assert.deepEqual( groupScale( FULL, null ), [ 1, 1, 1 ] );

} );

test( 'a hop without a voice or without F1 to F3 gives no formants to invert', () => {

	assert.equal( estimableFormants( { voiced: false, formants: [ 500, 1500, 2500, 3500 ] } ), null );
	assert.equal( estimableFormants( { voiced: true, formants: [ 500, null, 2500, 3500 ] } ), null );
	assert.equal( estimableFormants( { voiced: true, formants: null } ), null );
	assert.deepEqual( estimableFormants( { voiced: true, formants: [ 500, 1500, 2500, 3500 ] } ), [ 500, 1500, 2500 ] );

} );
