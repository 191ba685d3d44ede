// The lossy tube in JS (web/src/core/tubeAcoustics.js) against the shared vectors that Python
// writes (tests/vectors/tube-acoustics.json): the transfer function at each frequency and the
// formants and bandwidths of every tube; and the textbook uniform tube.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { near, nearRelative, readVectors, tolerance } from './support/vectors.js';

import { tubeFormants, tubeTransfer } from '../../web/src/core/tubeAcoustics.js';

const VECTORS = readVectors( 'tube-acoustics.json' );
const TRANSFER = tolerance( VECTORS, 'transfer' );
const FREQUENCY = tolerance( VECTORS, 'frequency' );

test( 'every tube of the shared vectors: the same transfer function, formants and bandwidths as Python', () => {

	assert.ok( VECTORS.cases.length >= 12 );
	assert.ok( VECTORS.cases.filter( ( c ) => c.input.nasal ).length >= 4, 'tubes with a nose' );
	for ( const { description, input, expected } of VECTORS.cases ) {

		const nasal = input.nasal && { at: input.nasal.at, lengths: input.nasal.length_mm, areas: input.nasal.area_mm2 };
		input.frequencies_hz.forEach( ( f, k ) => {

			const h = tubeTransfer( input.lengths_mm, input.areas_mm2, f, input.lossy, undefined, nasal );
			nearRelative( h[ 0 ], expected.transfer[ k ][ 0 ], TRANSFER, `${ description }: Re H(${ f })` );
			nearRelative( h[ 1 ], expected.transfer[ k ][ 1 ], TRANSFER, `${ description }: Im H(${ f })` );

		} );
		const { frequencies, bandwidths } = tubeFormants( input.lengths_mm, input.areas_mm2, { lossy: input.lossy, nasal } );
		expected.formants_hz.forEach( ( f, k ) => ( f === null ? assert.ok( Number.isNaN( frequencies[ k ] ) ) : near( frequencies[ k ], f, FREQUENCY, `${ description }: F${ k + 1 }` ) ) );
		expected.bandwidths_hz.forEach( ( b, k ) => {

			if ( b !== null ) near( bandwidths[ k ], b, FREQUENCY, `${ description }: B${ k + 1 }` );

		} );

	}

} );

test( 'the lossless uniform 17.5 cm tube resonates at 500, 1500, 2500 and 3500 Hz', () => {

	const lengths = new Array( 35 ).fill( 5 ), areas = new Array( 35 ).fill( 300 );
	const { frequencies } = tubeFormants( lengths, areas, { lossy: false } );
	[ 500, 1500, 2500, 3500 ].forEach( ( f, k ) => near( frequencies[ k ], f, 0.005 * f, `F${ k + 1 }` ) );

} );
