// A picture for each sound (ui/shared/soundPictures.js): every phoneme of the inventory
// (server/glasshead/phonemes.py) has one, with words, drawn inside its 100 x 100 box.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

import { SOUND_PICTURE_CODES, soundPictureShapes, soundPictureWords } from '../../web/src/ui/shared/soundPictures.js';

const INVENTORY = [ ...readFileSync( new URL( '../../server/glasshead/phonemes.py', import.meta.url ), 'utf8' ).matchAll( /^\s+_[cv]\("([A-Z]+)", "([^"]+)"/gm ) ].map( ( [ , arpabet, ipa ] ) => ( { arpabet, ipa } ) );

test( 'every phoneme of the inventory has a picture and the words that name it, and nothing else has', () => {

	assert.equal( INVENTORY.length, 39 );
	assert.deepEqual( [ ...SOUND_PICTURE_CODES ].sort(), INVENTORY.map( ( p ) => p.arpabet ).sort() );
	const words = INVENTORY.map( ( p ) => soundPictureWords( p.arpabet ) );
	assert.equal( new Set( words ).size, words.length, 'no two sounds are named alike' );
	assert.equal( soundPictureWords( 'S' ), 'a snake: sss' );
	assert.equal( soundPictureWords( 'SH' ), 'a finger to the lips: shh' );
	assert.equal( soundPictureWords( 'XX' ), null );

} );

test( 'each picture is a few shapes inside its box, with no inline style', () => {

	for ( const { arpabet } of INVENTORY ) {

		const shapes = soundPictureShapes( arpabet );
		assert.ok( shapes.length >= 1 && shapes.length <= 20, `${ arpabet }: ${ shapes.length } shapes` );
		for ( const [ tag, attributes ] of shapes ) {

			assert.ok( [ 'circle', 'ellipse', 'rect', 'path', 'polygon' ].includes( tag ), `${ arpabet }: ${ tag }` );
			assert.equal( 'style' in attributes, false, arpabet );
			for ( const key of [ 'cx', 'x' ] ) if ( key in attributes ) assert.ok( attributes[ key ] >= 0 && attributes[ key ] <= 100, `${ arpabet } ${ key } ${ attributes[ key ] }` );
			for ( const key of [ 'cy', 'y' ] ) if ( key in attributes ) assert.ok( attributes[ key ] >= 0 && attributes[ key ] <= 100, `${ arpabet } ${ key } ${ attributes[ key ] }` );

		}

	}

} );

test( 'the voiced twins draw their voiceless pair and the voice', () => {

	for ( const [ voiced, voiceless ] of [ [ 'DH', 'TH' ], [ 'ZH', 'SH' ] ] ) {

		const twin = soundPictureShapes( voiced );
		assert.deepEqual( twin.slice( 0, soundPictureShapes( voiceless ).length ), soundPictureShapes( voiceless ) );
		assert.ok( twin.length > soundPictureShapes( voiceless ).length );

	}

} );
