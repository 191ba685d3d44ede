// The area function in JS (web/src/core/areaFunction.js) against the shared vectors that Python
// writes (tests/vectors/area-function.json): the same sections, widths, areas and regions for
// every hand-drawn tract; and what each law gives by hand.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { near, nearRelative, readVectors, tolerance } from './support/vectors.js';

import { areaFunction, chainPart, createAreaFunction, lipWidthMm, nasalBranch, widthToArea } from '../../web/src/core/areaFunction.js';
import { TRACT_AREA_LAWS } from '../../web/src/core/constants.js';

const VECTORS = readVectors( 'area-function.json' );
const MM = tolerance( VECTORS, 'mm' );
const AREA = tolerance( VECTORS, 'area' );

const parts = ( list ) => list.map( ( { points, closed } ) => chainPart( points, closed ) );

test( 'every tract of the shared vectors: the same tube as Python', () => {

	assert.ok( VECTORS.cases.length >= 6 );
	for ( const { description, input, expected } of VECTORS.cases ) {

		const stations = Float64Array.from( input.stations );
		const out = areaFunction( stations, parts( input.floor ), parts( input.roof ), {
			incisorX: input.incisor_x, uvulaY: input.uvula_y, lipFrontX: input.lip_front_x, lipRounding: input.lip_rounding,
		}, createAreaFunction( stations.length / 2 ) );
		assert.equal( out.count, expected.length_mm.length, `${ description }: sections` );
		assert.equal( out.closed, expected.closed, `${ description }: closed` );
		for ( let k = 0; k < out.count; k ++ ) {

			near( out.lengths[ k ], expected.length_mm[ k ], MM, `${ description }: length ${ k }` );
			near( out.positions[ k ], expected.position_mm[ k ], MM, `${ description }: position ${ k }` );
			nearRelative( out.areas[ k ], expected.area_mm2[ k ], AREA, `${ description }: area ${ k }` );
			assert.equal( out.regions[ k ], expected.region[ k ], `${ description }: region ${ k }` );
			if ( expected.width_mm[ k ] === null ) assert.ok( Number.isNaN( out.widths[ k ] ) );
			else near( out.widths[ k ], expected.width_mm[ k ], MM, `${ description }: width ${ k }` );

		}

		const nasal = nasalBranch( out, VECTORS.fixtures.nose, VECTORS.fixtures.port_mm2 );
		assert.deepEqual( nasal && { at: nasal.at, length_mm: nasal.lengths, area_mm2: nasal.areas }, expected.nasal, `${ description }: nasal branch` );

	}

} );

test( 'a shut port or a tube without a mouth makes no nasal branch', () => {

	const tube = { count: 3, regions: Int8Array.of( - 1, 0, 1 ) };
	const nose = VECTORS.fixtures.nose;
	assert.equal( nasalBranch( tube, nose, 0 ), null );
	assert.equal( nasalBranch( { count: 2, regions: Int8Array.of( - 1, 0 ) }, nose, 40 ), null );
	assert.equal( nasalBranch( tube, nose, 40 ).at, 2 );

} );

test( 'the laws by hand: 1 cm of mouth, 1 cm of pharynx, and lips that narrow as they round', () => {

	near( widthToArea( 10, 1, 40 ), 100 * TRACT_AREA_LAWS.oral.alpha, 1e-9, 'mouth' );
	near( widthToArea( 10, 0, 40 ), 100 * TRACT_AREA_LAWS.pharynx.alpha, 1e-9, 'pharynx' );
	near( widthToArea( 4, 2, 40 ), Math.PI * 40, 1e-9, 'lips: an ellipse 4 by 40 mm' );
	assert.ok( lipWidthMm( 8 ) < lipWidthMm( 0 ) && lipWidthMm( 100 ) === TRACT_AREA_LAWS.lips.min_mm );

} );

test( 'too few stations, or lips reaching past the output, are refused', () => {

	const floor = [ chainPart( [ - 10, - 5, 10, - 5 ], false ) ], roof = [ chainPart( [ - 10, 5, 10, 5 ], false ) ];
	const where = { incisorX: 0, uvulaY: - 100, lipFrontX: 0, lipRounding: 0 };
	assert.throws( () => areaFunction( Float64Array.of( 0, 0 ), floor, roof, where, createAreaFunction( 1 ) ), /at least two stations/ );
	assert.throws( () => areaFunction( Float64Array.of( 0, 0, 2, 0 ), floor, roof, { ...where, lipFrontX: 500 }, createAreaFunction( 2, 4 ) ), /the lips reach/ );

} );
