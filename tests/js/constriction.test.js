// The narrowest constriction (web/src/core/constriction.js): on a small tract made of prisms cut
// by z = 0, and on the real head (the built meshes, the tongue rig, the face and velum rigs).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';

import { createSectionPart, cutSection } from '../../web/src/core/midSection.js';
import {
	CONSTRICTION_AT, CONSTRICTION_FOUND, CONSTRICTION_LENGTH, CONSTRICTION_PLACE, CONSTRICTION_WIDTH,
	alongMidline, findConstriction, tractMidline,
} from '../../web/src/core/constriction.js';
import { fewestGarbageCollections } from './support/garbage.js';

/** A prism z in [ -1, 1 ] over a polyline (x y pairs), cut by z = 0 into a section part. */
function prism( points, closed ) {

	const n = points.length / 2;
	const positions = [];
	for ( let k = 0; k < n; k ++ ) positions.push( points[ 2 * k ], points[ 2 * k + 1 ], - 1, points[ 2 * k ], points[ 2 * k + 1 ], 1 );
	const index = [];
	for ( let k = 0; k < ( closed ? n : n - 1 ); k ++ ) {

		const a = 2 * k, b = 2 * ( ( k + 1 ) % n );
		index.push( a, b, a + 1, a + 1, b, b + 1 );

	}

	const part = createSectionPart( Uint32Array.from( index ), 2 * n );
	cutSection( part, Float32Array.from( positions ) );
	return part;

}

// The roof from the larynx (-50, -30) up the pharynx, along the palate to the upper lip (40, 5);
// the floor's top (the tongue and the lower lip) 8 mm under it at rest.
const ROOF = [ - 50, - 30, - 50, 10, - 30, 20, 5, 22, 25, 12, 40, 5 ];
const restTongue = ( tip ) => [ - 42, - 30, - 42, 2, - 28, 12, 5, 14 + tip, 20, 4 + tip, 22, - 5, 0, - 15, - 30, - 25 ];
const LOWER_LIP = [ 30, - 3, 40, - 3, 40, - 10, 30, - 10 ];
// Places of articulation: bilabial, alveolar, velar.
const PLACES = Float64Array.of( 40, 5, 5, 22, - 35, 18 );
const PLACE_NAMES = [ 'bilabial', 'alveolar', 'velar' ];
const MIDLINE = tractMidline( Float64Array.from( ROOF ), Float64Array.of( - 42, - 30, - 42, 2, - 28, 12, 5, 14, 20, 4, 30, - 3 ) );

function constriction( tip ) {

	const target = new Float64Array( CONSTRICTION_LENGTH );
	findConstriction( [ prism( restTongue( tip ), true ), prism( LOWER_LIP, true ) ], [ prism( ROOF, false ) ], MIDLINE, PLACES, target );
	return target;

}

test( 'a tongue raised into the alveolar ridge gives a smaller width than the rest tongue, at the front, named alveolar', () => {

	const rest = constriction( 0 );
	const raised = constriction( 7 );
	assert.equal( rest[ CONSTRICTION_FOUND ], 1 );
	assert.ok( rest[ CONSTRICTION_WIDTH ] > 6, `rest width ${ rest[ CONSTRICTION_WIDTH ] }` );
	assert.ok( Math.abs( raised[ CONSTRICTION_WIDTH ] - 2 / Math.sqrt( 5 ) ) < 1e-6, `raised width ${ raised[ CONSTRICTION_WIDTH ] } (the tongue top at (5, 21) against the ridge slope)` );
	assert.equal( PLACE_NAMES[ raised[ CONSTRICTION_PLACE ] ], 'alveolar' );
	const total = MIDLINE.lengths[ MIDLINE.lengths.length - 1 ];
	assert.ok( raised[ CONSTRICTION_AT ] < total / 3, `at ${ raised[ CONSTRICTION_AT ] } mm of ${ total } mm from the lips` );

} );

test( 'the midline runs from the lips to the larynx; distances along it grow backwards', () => {

	const { points, lengths } = MIDLINE;
	assert.ok( points[ 0 ] > 30, 'it starts at the lips' );
	assert.ok( points[ points.length - 2 ] < - 40, 'it ends in the pharynx' );
	assert.ok( alongMidline( MIDLINE, 5, 18 ) < alongMidline( MIDLINE, - 40, 0 ) );
	assert.equal( lengths[ 0 ], 0 );

} );

test( 'without a floor there is no gap; the search allocates nothing', async () => {

	const target = new Float64Array( CONSTRICTION_LENGTH );
	findConstriction( [], [ prism( ROOF, false ) ], MIDLINE, PLACES, target );
	assert.equal( target[ CONSTRICTION_FOUND ], 0 );
	const floor = [ prism( restTongue( 3 ), true ), prism( LOWER_LIP, true ) ];
	const roof = [ prism( ROOF, false ) ];
	assert.equal( await fewestGarbageCollections( () => {

		for ( let k = 0; k < 20000; k ++ ) findConstriction( floor, roof, MIDLINE, PLACES, target );

	} ), 0 );

} );

const BUILD = new URL( '../../assets/build/', import.meta.url );
const built = [ 'manifest.json', 'tongue-rig.json', 'collision-tables.bin', 'face-rig.json', 'velum-rig.json', 'landmarks.json' ].every( ( name ) => existsSync( new URL( name, BUILD ) ) );

test( 'on the real head: the tip raised to the alveolar ridge narrows the gap; the dorsum raised makes it palatal or velar', { skip: built ? false : 'run glasshead build first' }, async () => {

	const { loadBuiltHead } = await import( './support/builtHead.js' );
	const { DiagramSection } = await import( '../../web/src/scene/DiagramSection.js' );
	const { head, articulation, landmarks } = await loadBuiltHead();
	const diagram = new DiagramSection( head, { landmarks } );
	const pose = ( params ) => {

		articulation.state.values.set( articulation.state.neutral );
		for ( const [ name, value ] of Object.entries( params ) ) articulation.state.values[ articulation.state.indexOf( name ) ] = value;
		articulation.state.touch();
		articulation.update();
		return diagram.update().constriction();

	};
	const rest = pose( {} );
	const tip = pose( { tip_height: 8 } );
	const dorsum = pose( { dorsum_height: 10, back_dorsum_height: 6 } );
	for ( const key of [ 'tongue', 'palate', 'mandible', 'velum', 'upperLip', 'lowerLip', 'pharynx', 'larynx', 'airway' ] ) {

		assert.ok( diagram.parts( key ).some( ( part ) => part.pointCount > 10 ), `${ key } has a section` );

	}

	assert.ok( tip.widthMm < rest.widthMm, `tip raised ${ tip.widthMm } mm, rest ${ rest.widthMm } mm` );
	assert.ok( tip.widthMm < 1, `tip raised ${ tip.widthMm } mm` );
	assert.ok( tip.atMm < 30, `tip raised at ${ tip.atMm } mm from the lips` );
	assert.ok( [ 'dental', 'alveolar', 'postalveolar' ].includes( tip.place ), tip.place );
	assert.ok( [ 'palatal', 'velar' ].includes( dorsum.place ), dorsum.place );
	assert.ok( dorsum.atMm > tip.atMm );

} );
