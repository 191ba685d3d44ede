// The label layer's pure parts (web/src/ui/shared/labelPlacement.js): the entries it shows, labels kept
// apart on the screen, and the part a pointer over a mesh names. Also the landmarks loader.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { createApi } from '../../web/src/api.js';
import { LANDMARKS_FORMAT_VERSION } from '../../web/src/core/constants.js';
import { labelEntries, partAt, placeLabels, preferredAngles } from '../../web/src/ui/shared/labelPlacement.js';
import { loadLandmarks } from '../../web/src/ui/shared/loaders.js';

const TONGUE = [ 'tongue_rest' ];
const DOCUMENT = Object.freeze( {
	format_version: LANDMARKS_FORMAT_VERSION,
	landmarks: [
		{ name: 'teeth', label: 'teeth', kind: 'part', position: [ 28, - 3, 0 ], meshes: [ 'maxilla', 'mandible' ] },
		{ name: 'alveolar_ridge', label: 'alveolar ridge', kind: 'part', position: [ 5, 18, 0 ], meshes: [ 'maxilla' ] },
		{ name: 'hard_palate', label: 'hard palate', kind: 'part', position: [ - 10, 22, 0 ], meshes: [ 'maxilla' ] },
		{ name: 'tongue_tip', label: 'tongue tip', kind: 'part', position: [ 22, 0, 0 ], meshes: TONGUE },
		{ name: 'tongue_back', label: 'tongue back', kind: 'part', position: [ - 32, 9, 0 ], meshes: TONGUE },
		{ name: 'tongue_root', label: 'tongue root', kind: 'part', position: [ - 47, - 12, 0 ], meshes: TONGUE },
		{ name: 'alveolar', label: 'alveolar', kind: 'place', order: 0, position: [ 5, 18, 0 ], meshes: [] },
		{ name: 'glottis', label: 'glottis', kind: 'reference', position: [ - 33, - 65, 0 ], meshes: [] },
	],
} );

test( 'the layer shows parts and places, not the reference points', () => {

	const entries = labelEntries( DOCUMENT );
	assert.deepEqual( entries.map( ( e ) => e.name ), [ 'teeth', 'alveolar_ridge', 'hard_palate', 'tongue_tip', 'tongue_back', 'tongue_root', 'alveolar' ] );
	assert.throws( () => labelEntries( { ...DOCUMENT, format_version: 99 } ), /format_version 99/ );

} );

test( 'on the tongue the nearest tongue landmark names the part', () => {

	const entries = labelEntries( DOCUMENT );
	assert.equal( partAt( 'tongue_rest', [ 20, 2, 5 ], entries ).label, 'tongue tip' );
	assert.equal( partAt( 'tongue_rest', [ - 30, 5, - 8 ], entries ).label, 'tongue back' );
	assert.equal( partAt( 'tongue_rest', [ - 45, - 20, 0 ], entries ).label, 'tongue root' );

} );

test( 'on the maxilla a tooth says teeth and the bone the nearest palate landmark', () => {

	const entries = labelEntries( DOCUMENT );
	assert.equal( partAt( 'maxilla', [ - 20, 5, 25 ], entries, { isTooth: true } ).label, 'teeth' );
	assert.equal( partAt( 'maxilla', [ 25, 0, 0 ], entries, { isTooth: false } ).label, 'alveolar ridge' );
	assert.equal( partAt( 'maxilla', [ - 15, 23, 0 ], entries, { isTooth: false } ).label, 'hard palate' );
	assert.equal( partAt( 'mandible', [ 0, - 40, 0 ], entries, { isTooth: false } ).label, 'jaw' );
	assert.equal( partAt( 'face_skin', [ 0, 0, 0 ], entries ), null );

} );

test( 'labels crowded on one point are placed apart, inside the screen', () => {

	const anchors = Array.from( { length: 8 }, () => ( { x: 300, y: 200, w: 120, h: 28, angle: - Math.PI / 2 } ) );
	const boxes = placeLabels( anchors, { width: 800, height: 600 } );
	for ( let i = 0; i < boxes.length; i ++ ) {

		const a = boxes[ i ];
		assert.ok( a.x >= 0 && a.y >= 0 && a.x + a.w <= 800 && a.y + a.h <= 600, `label ${ i } leaves the screen` );
		assert.equal( a.overlapping, false, `label ${ i } overlaps` );
		for ( let k = 0; k < i; k ++ ) {

			const b = boxes[ k ];
			const apart = a.x + a.w <= b.x || b.x + b.w <= a.x || a.y + a.h <= b.y || b.y + b.h <= a.y;
			assert.ok( apart, `labels ${ k } and ${ i } overlap` );

		}

	}

	// The first label takes the nearest spot in its preferred direction: straight above.
	assert.ok( boxes[ 0 ].y + boxes[ 0 ].h < 200 && Math.abs( boxes[ 0 ].x + boxes[ 0 ].w / 2 - 300 ) < 1e-9 );

} );

test( 'labels keep off the panels over the view and each other, even when their best spot is under one', () => {

	// A card at the bottom left (the EPG card) and a panel down the right side.
	const card = { x: 16, y: 420, w: 190, h: 230 }, side = { x: 700, y: 0, w: 300, h: 768 };
	const bounds = { width: 1000, height: 768 };
	// Anchors just above and beside the card, preferring to hang down into it, and crowded at the side panel.
	const anchors = [
		{ x: 120, y: 400, w: 110, h: 26, angle: Math.PI / 2 },
		{ x: 150, y: 410, w: 110, h: 26, angle: Math.PI * 0.6 },
		{ x: 90, y: 395, w: 110, h: 26, angle: Math.PI * 0.4 },
		{ x: 660, y: 300, w: 140, h: 26, angle: 0 },
		{ x: 665, y: 320, w: 140, h: 26, angle: 0 },
	];
	const apart = ( a, b ) => a.x + a.w <= b.x || b.x + b.w <= a.x || a.y + a.h <= b.y || b.y + b.h <= a.y;
	const free = placeLabels( anchors, bounds );
	assert.ok( free.some( ( box ) => ! apart( box, card ) || ! apart( box, side ) ), 'without the panels some labels would lie under them' );
	const boxes = placeLabels( anchors, bounds, [ card, side ] );
	boxes.forEach( ( box, i ) => {

		assert.ok( apart( box, card ), `label ${ i } covers the card` );
		assert.ok( apart( box, side ), `label ${ i } covers the side panel` );
		assert.equal( box.overlapping, false );
		for ( let k = 0; k < i; k ++ ) assert.ok( apart( box, boxes[ k ] ), `labels ${ k } and ${ i } overlap` );

	} );

} );

test( 'a label with no spot free of a panel says that it overlaps', () => {

	const panel = { x: 0, y: 0, w: 400, h: 300 };
	const [ box ] = placeLabels( [ { x: 200, y: 150, w: 100, h: 20, angle: 0 } ], { width: 400, height: 300 }, [ panel ] );
	assert.equal( box.overlapping, true );

} );

test( 'places point up, parts away from the middle of the parts', () => {

	const entries = [ { kind: 'part' }, { kind: 'part' }, { kind: 'place' } ];
	const angles = preferredAngles( entries, [ { x: 0, y: 0 }, { x: 10, y: 0 }, { x: 5, y: 5 } ] );
	assert.ok( Math.abs( angles[ 0 ] - Math.PI ) < 1e-12 );
	assert.ok( Math.abs( angles[ 1 ] ) < 1e-12 );
	assert.ok( Math.abs( angles[ 2 ] + Math.PI / 2 ) < 1e-12 );

} );

test( 'the landmarks load through the one client from GET /anatomy/landmarks', async () => {

	const asked = [];
	const api = createApi( { fetchImpl: async ( url ) => {

		asked.push( url );
		return { ok: true, status: 200, statusText: '', json: async () => DOCUMENT };

	} } );
	const document = await loadLandmarks( { api } );
	assert.deepEqual( asked, [ '/api/v1/anatomy/landmarks' ] );
	assert.equal( document.landmarks.length, DOCUMENT.landmarks.length );

} );
