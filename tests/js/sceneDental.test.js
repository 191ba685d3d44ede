// Which vertices of a jaw are teeth, gums or palate (web/src/core/dentalShading.js), on small
// synthetic jaws whose answer is known by construction.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { DENTAL_DEFAULTS, dentalWeights, palatalWeights } from '../../web/src/core/dentalShading.js';

/**
 * An upper jaw made of points: a row of teeth along x at |z| = 20 (vertical columns of points from
 * y = 0 up to y = 16, every mm) and a palate plate at y = 18 between them (|z| <= 12).
 * Returns { positions, normals, kind } with kind 'tooth-column' or 'palate' per point.
 */
function upperJaw() {

	const points = [], normals = [], kind = [];
	for ( let x = 0; x <= 30; x += 2 ) {

		for ( const z of [ - 20, 20 ] ) {

			for ( let y = 0; y <= 16; y ++ ) {

				points.push( x, y, z );
				normals.push( 0, 0, Math.sign( z ) );
				kind.push( 'tooth-column' );

			}

		}

		for ( let z = - 12; z <= 12; z += 3 ) {

			points.push( x, 18, z );
			normals.push( 0, - 1, 0 );
			kind.push( 'palate' );

		}

	}

	return { positions: Float32Array.from( points ), normals: Float32Array.from( normals ), kind };

}

test( 'points up to the crown height above the tips are teeth; the gum band lies just above', () => {

	const { positions, kind } = upperJaw();
	const n = kind.length;
	const teeth = new Float32Array( n ), gum = new Float32Array( n );
	dentalWeights( positions, {}, teeth, gum );
	const { crownHeight, blend, gumHeight } = DENTAL_DEFAULTS;
	for ( let i = 0; i < n; i ++ ) {

		const y = positions[ 3 * i + 1 ];
		if ( kind[ i ] === 'palate' ) {

			assert.equal( teeth[ i ], 0, `palate point ${ i } is tooth` );
			continue;

		}

		if ( y <= crownHeight - blend / 2 ) assert.equal( teeth[ i ], 1, `y = ${ y }` );
		if ( y >= crownHeight + blend / 2 ) assert.equal( teeth[ i ], 0, `y = ${ y }` );
		if ( y >= crownHeight + blend / 2 && y <= crownHeight + gumHeight - blend / 2 ) assert.equal( gum[ i ], 1, `gum at y = ${ y }` );
		if ( y >= crownHeight + gumHeight + blend / 2 ) assert.equal( gum[ i ], 0, `gum at y = ${ y }` );
		assert.ok( teeth[ i ] + gum[ i ] <= 1 + 1e-6 );

	}

} );

test( 'a column whose tip is far above the occlusal level carries no tooth', () => {

	const { positions, kind } = upperJaw();
	// Raise one column (x = 30, z = 20) by 10 mm: a bony ridge, not a tooth.
	for ( let i = 0; i < kind.length; i ++ ) {

		if ( positions[ 3 * i ] === 30 && positions[ 3 * i + 2 ] === 20 ) positions[ 3 * i + 1 ] += 10;

	}

	const teeth = new Float32Array( kind.length ), gum = new Float32Array( kind.length );
	dentalWeights( positions, {}, teeth, gum );
	for ( let i = 0; i < kind.length; i ++ ) {

		if ( positions[ 3 * i ] === 30 && positions[ 3 * i + 2 ] === 20 ) assert.equal( teeth[ i ], 0 );
		if ( positions[ 3 * i ] === 0 && positions[ 3 * i + 1 ] === 0 ) assert.equal( teeth[ i ], 1 );

	}

} );

test( 'a lower jaw mirrors the rule: its teeth point up to the given occlusal level', () => {

	const { positions, kind } = upperJaw();
	// Mirror y and add a tall condyle well above the occlusal level.
	const points = Array.from( positions );
	for ( let i = 1; i < points.length; i += 3 ) points[ i ] = - points[ i ];
	for ( let y = 10; y <= 40; y ++ ) points.push( - 30, y, 30 );
	const mirrored = Float32Array.from( points );
	const n = mirrored.length / 3;
	const teeth = new Float32Array( n ), gum = new Float32Array( n );
	dentalWeights( mirrored, { upward: true, occlusalY: 0 }, teeth, gum );
	for ( let i = 0; i < n; i ++ ) {

		const y = mirrored[ 3 * i + 1 ];
		if ( i >= kind.length ) assert.equal( teeth[ i ], 0, 'the condyle is not a tooth' );
		else if ( kind[ i ] === 'tooth-column' && y >= - 7 ) assert.equal( teeth[ i ], 1, `y = ${ y }` );
		else if ( kind[ i ] === 'palate' ) assert.equal( teeth[ i ], 0 );

	}

} );

test( 'the palate is the downward surface inside the arch of the teeth', () => {

	const { positions, normals, kind } = upperJaw();
	const n = kind.length;
	const teeth = new Float32Array( n ), gum = new Float32Array( n ), palate = new Float32Array( n );
	dentalWeights( positions, {}, teeth, gum );
	palatalWeights( positions, normals, teeth, {}, palate );
	for ( let i = 0; i < n; i ++ ) assert.equal( palate[ i ], kind[ i ] === 'palate' ? 1 : 0, `point ${ i } (${ kind[ i ] })` );

} );

test( 'dental weights refuse short targets and bad options', () => {

	const { positions, kind } = upperJaw();
	assert.throws( () => dentalWeights( positions, {}, new Float32Array( 3 ), new Float32Array( kind.length ) ), RangeError );
	assert.throws( () => dentalWeights( positions, { radius: 0 }, new Float32Array( kind.length ), new Float32Array( kind.length ) ), RangeError );
	assert.throws( () => dentalWeights( positions.subarray( 1 ), {}, new Float32Array( kind.length ), new Float32Array( kind.length ) ), /multiple of 3/ );

} );
