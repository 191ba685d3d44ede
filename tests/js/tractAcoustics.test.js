// The head's tract as a tube in the browser (scene/TractAcoustics.js) on the real built head:
// the phoneme targets' vowels land where the vowel chart puts them, a stop shuts the tube, and
// the browser's section gives the server's formants (POST /tract/acoustics computes them from
// the rigs; tests/test_area_function.py).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

import { DiagramSection } from '../../web/src/scene/DiagramSection.js';
import { TractAcoustics } from '../../web/src/scene/TractAcoustics.js';
import { loadBuiltHead } from './support/builtHead.js';

const BUILD = new URL( '../../assets/build/', import.meta.url );
const json = ( name ) => JSON.parse( readFileSync( new URL( name, BUILD ) ).toString( 'utf8' ) );

const { head, articulation, landmarks } = await loadBuiltHead();
const diagram = new DiagramSection( head, { landmarks } );
const tract = new TractAcoustics( diagram, json( 'tract-section.json' ), articulation.state, { velumRig: articulation.velum.rig } );
const targets = Object.fromEntries( json( 'phoneme-targets.json' ).targets.map( ( t ) => [ t.ipa, t ] ) );

function pose( params ) {

	const state = articulation.state;
	state.values.set( state.neutral );
	for ( const [ name, value ] of Object.entries( params ) ) {

		const k = state.indexOf( name );
		if ( k >= 0 ) state.values[ k ] = value;

	}

	state.touch();
	articulation.update();
	diagram.update();
	return tract.update().summary();

}

test( 'the vowels sit where the chart puts them: front above back in F2, F1 rising as the tongue lowers', () => {

	const f = Object.fromEntries( [ 'i', 'ɪ', 'ɛ', 'æ', 'u', 'ʊ', 'ɔ', 'ɑ' ].map( ( v ) => [ v, pose( targets[ v ].params ).formants ] ) );
	for ( const front of [ 'i', 'ɪ', 'ɛ', 'æ' ] ) for ( const back of [ 'u', 'ʊ', 'ɔ', 'ɑ' ] ) assert.ok( f[ front ][ 1 ] > f[ back ][ 1 ], `F2 of /${ front }/ ${ f[ front ][ 1 ] } over /${ back }/ ${ f[ back ][ 1 ] }` );
	for ( const side of [ [ 'i', 'ɪ', 'ɛ', 'æ' ], [ 'u', 'ʊ', 'ɔ', 'ɑ' ] ] ) {

		const f1 = side.map( ( v ) => f[ v ][ 0 ] );
		assert.deepEqual( f1, [ ...f1 ].sort( ( a, b ) => a - b ), `F1 down ${ side.join( ' ' ) }: ${ f1 }` );

	}

	assert.ok( f.i[ 0 ] < 350 && f.i[ 1 ] > 1700, `/i/ ${ f.i }` );
	assert.ok( f[ 'ɑ' ][ 0 ] > 550, `/ɑ/ ${ f[ 'ɑ' ] }` );

} );

test( 'a stop shuts the tube and a vowel does not; the tube runs from the glottis to the lips', () => {

	assert.equal( pose( targets.t.params ).closed, true );
	assert.equal( pose( targets.k.params ).closed, true );
	const vowel = pose( targets[ 'ɑ' ].params );
	assert.equal( vowel.closed, false );
	assert.ok( vowel.lengthMm > 150 && vowel.lengthMm < 200, `${ vowel.lengthMm } mm` );
	assert.ok( tract.lastMs < 50 );

} );

test( 'the nasals open the nose: a branch behind the velum\'s port, and the murmur\'s low first peak', () => {

	const oral = pose( targets[ 'ɑ' ].params );
	assert.equal( oral.nasalAt, null, 'a raised velum: no branch' );
	for ( const nasal of [ 'm', 'n', 'ŋ' ] ) {

		const summary = pose( targets[ nasal ].params );
		assert.ok( summary.nasalPortMm2 > 50 && summary.nasalAt > 10, `/${ nasal }/: ${ JSON.stringify( summary ) }` );
		assert.ok( summary.formants[ 0 ] < 450, `/${ nasal }/ murmur: ${ summary.formants }` );

	}

	// The same /m/ with the velum raised: a shut tube and no nose.
	const shut = pose( { ...targets.m.params, velum_opening: 0 } );
	assert.equal( shut.nasalAt, null );
	assert.notDeepEqual( shut.formants, pose( targets.m.params ).formants );

} );
