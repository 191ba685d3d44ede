// End-to-end tests of the workbench (#/workbench) in Debian's Chromium (SwiftShader WebGL2). One
// server, one browser and one page for the whole file; the tests run in order and share it.
// Assertions read `window.glasshead`; the screenshots in e2e/screenshots/ are for a person.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { compareImages, decodePng } from './png.js';
import { authHeaders, openSignedIn } from './accounts.js';
import { readDebug, saveScreenshot, serverAndBrowser, settle } from './harness.js';

/** Poses of the screenshots (rig parameter names, mm and degrees). */
const POSES = Object.freeze( {
	tipRaised: { tip_height: 8, tip_advancement: 2, blade_height: 5 },
	grooved: { front_groove_depth: 5, middle_groove_depth: 5, front_groove_width: 2, blade_height: 3 },
	retracted: { tip_advancement: - 4, blade_advancement: - 4, dorsum_advancement: - 4, root_advancement: - 8 },
	// Narrowed, so that the tongue meets the palate vault rather than wrapping the teeth.
	intoPalate: { tip_height: 6, blade_height: 8, dorsum_height: 10, back_dorsum_height: 4, front_width: - 6, middle_width: - 6, back_width: - 6 },
} );

describe( 'the workbench', { timeout: 300_000 }, () => {

	let server, browser, page, rig, author;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		const response = await fetch( `${ server.baseUrl }/api/v1/tongue/rig` );
		assert.equal( response.status, 200, `GET /api/v1/tongue/rig answered ${ response.status }` );
		rig = await response.json();
		// Saving poses needs an author (or a clinician or admin) signed in.
		page = await openSignedIn( browser, server, 'author', `${ server.baseUrl }/#/workbench` );
		author = JSON.parse( await page.evaluate( () => window.localStorage.getItem( 'glasshead.session' ) ) );

	} );

	const slider = ( name ) => page.getByRole( 'slider', { name, exact: true } );
	const button = ( name ) => page.getByRole( 'button', { name, exact: true } );
	const jsonBox = () => page.getByRole( 'textbox', { name: 'Parameters as JSON' } );

	/** Set the toggles and the view of the 3D scene, then wait until it is drawn. */
	async function show( { view, ...toggles } ) {

		const state = ( await readDebug( page ) ).workbench;
		const labels = { skin: 'Skin', jaw: 'Jaw & lips', palate: 'Palate', tongue: 'Tongue', cutaway: 'Cutaway', contacts: 'Contacts', liner: 'Liner', voxels: 'Voxels' };
		for ( const [ key, on ] of Object.entries( toggles ) ) if ( state[ key ] !== on ) await button( labels[ key ] ).click();
		if ( view ) await button( view ).click();
		await settle( page );

	}

	/** Paste a pose as JSON and apply it (names left out go back to neutral). */
	async function pose( params ) {

		await jsonBox().fill( JSON.stringify( params ) );
		await button( 'Apply JSON' ).click();
		await settle( page );
		return readDebug( page );

	}

	async function tongueShot() {

		const rect = ( await readDebug( page ) ).tongueRect;
		const clip = { x: Math.max( 0, Math.floor( rect.x ) ), y: Math.max( 0, Math.floor( rect.y ) ) };
		clip.width = Math.min( 1280 - clip.x, Math.ceil( rect.width ) );
		clip.height = Math.min( 800 - clip.y, Math.ceil( rect.height ) );
		return decodePng( await page.screenshot( { clip } ) );

	}

	test( 'it shows a slider for every parameter, in the groups of the paper, with no console errors', async () => {

		assert.deepEqual( page.problems, [] );
		const state = await readDebug( page );
		assert.equal( state.route, '/workbench' );
		assert.equal( await page.getByRole( 'slider' ).count(), Object.keys( state.params ).length );
		for ( const p of rig.parameters ) assert.ok( p.name in state.params, `${ p.name } has no value in window.glasshead.params` );
		const legends = await page.locator( '.wb-group legend' ).allTextContents();
		assert.deepEqual( legends.filter( ( text ) => text !== 'Lips' ), [ 'Jaw', 'Velum (soft palate)', 'Tongue sagittal', 'Tongue coronal: front', 'Tongue coronal: middle', 'Tongue coronal: back' ] );
		assert.equal( state.tongue.vertexCount, 2978 );
		assert.equal( state.collision.enabled, true, `no collision tables: ${ state.workbench.tablesError }` );
		assert.equal( state.collision.screened, state.tongue.vertexCount );

	} );

	test( 'moving a tongue slider changes the tongue in window.glasshead and on screen', async () => {

		await show( { view: 'Profile', cutaway: true, jaw: true, palate: true } );
		const before = await readDebug( page );
		const pixels = await tongueShot();
		await slider( 'Tip height' ).fill( '6' );
		await settle( page );
		const after = await readDebug( page );
		assert.equal( after.params.tip_height, 6 );
		assert.notEqual( after.tongue.checksum, before.tongue.checksum );
		assert.ok( after.tongue.tip[ 1 ] > before.tongue.tip[ 1 ] + 3, `the tip went from y = ${ before.tongue.tip[ 1 ] } to ${ after.tongue.tip[ 1 ] }` );
		assert.ok( after.collision.updates > before.collision.updates );
		const change = compareImages( pixels, await tongueShot() );
		assert.ok( change.changedFraction > 0.01, `the tongue barely changed on screen: ${ JSON.stringify( change ) }` );
		assert.match( await page.locator( 'output[for="param-tip_height"]' ).textContent(), /^6\.0 mm$/ );

	} );

	test( 'jaw opening opens the mouth: the lip gap grows', async () => {

		await button( 'Reset' ).click();
		await settle( page );
		const gaps = [];
		for ( const opening of [ 0, 8, 16 ] ) {

			await slider( 'Jaw opening' ).fill( String( opening ) );
			await settle( page );
			gaps.push( ( await readDebug( page ) ).lipGap );

		}

		assert.ok( gaps[ 1 ] > gaps[ 0 ] + 2 && gaps[ 2 ] > gaps[ 1 ] + 2, `lip gaps ${ gaps } mm at 0, 8 and 16 degrees` );
		await saveScreenshot( page, 'workbench-jaw-open' );
		// The face rig's lips close over the open jaw (p, b, m) when their opening goes to 0.
		await slider( 'Lip opening' ).fill( '0' );
		await settle( page );
		assert.ok( ( await readDebug( page ) ).lipGap < 0.5, `lip gap ${ ( await readDebug( page ) ).lipGap } mm with the lips closed` );
		await show( { view: 'Front', skin: true, cutaway: false } );
		await saveScreenshot( page, 'workbench-lips-closed' );
		await show( { view: 'Profile', skin: false, cutaway: true } );

	} );

	test( 'raising the tongue tip past the alveolar ridge flattens it against the palate', async () => {

		const state = await pose( POSES.tipRaised );
		await show( { view: 'Profile', cutaway: true, jaw: false, palate: true, contacts: true } );
		assert.equal( state.params.tip_height, 8 );
		assert.ok( state.collision.corrected > 0, `collision ${ JSON.stringify( state.collision ) }` );
		await saveScreenshot( page, 'workbench-tip-raised' );

	} );

	test( 'raising the tongue into the palate is corrected, and window.glasshead counts it', async () => {

		const state = await pose( POSES.intoPalate );
		const { screened, tested, corrected } = state.collision;
		assert.equal( screened, state.tongue.vertexCount );
		assert.ok( corrected > 50 && tested >= corrected, `screened ${ screened }, tested ${ tested }, corrected ${ corrected }` );
		await show( { view: 'Profile', cutaway: true, jaw: false, palate: true, contacts: true } );
		await saveScreenshot( page, 'workbench-collision' );
		// Where it touched, from above, the palate taken away: the corrected vertices as dots.
		await show( { view: 'Above', cutaway: false, palate: false } );
		await saveScreenshot( page, 'workbench-contacts' );
		await show( { palate: true } );
		const rest = await pose( {} );
		assert.equal( rest.collision.corrected, 0 );

	} );

	test( 'a grooved and a retracted tongue are saved as screenshots', async () => {

		const rest = await readDebug( page );
		const grooved = await pose( POSES.grooved );
		assert.ok( grooved.tongue.volumeMm3 < rest.tongue.volumeMm3, 'a groove takes volume away' );
		await show( { view: 'Above', cutaway: false, jaw: false, palate: false } );
		await saveScreenshot( page, 'workbench-grooved' );

		const retracted = await pose( POSES.retracted );
		assert.ok( retracted.tongue.tip[ 0 ] < rest.tongue.tip[ 0 ] - 4, `the tip went from x = ${ rest.tongue.tip[ 0 ] } to ${ retracted.tongue.tip[ 0 ] }` );
		await show( { view: 'Profile', cutaway: true, jaw: true, palate: true } );
		await saveScreenshot( page, 'workbench-retracted' );

	} );

	test( 'the liner and the voxel grid show as toggles', async () => {

		await pose( {} );
		// The liner over the tongue, seen from above with the palate it lines taken away (Figure 2).
		await show( { view: 'Above', cutaway: false, jaw: false, palate: false, liner: true, voxels: false } );
		let state = ( await readDebug( page ) ).workbench;
		assert.equal( state.liner, true );
		assert.ok( state.linerSegments > 1000, `${ state.linerSegments } liner segments` );
		await saveScreenshot( page, 'workbench-liner' );
		// The voxels around the palate, cut at the midline, the tongue out of the way (Figure 3).
		await show( { view: 'Three-quarter', liner: false, voxels: true, cutaway: true, palate: true, tongue: false } );
		state = ( await readDebug( page ) ).workbench;
		assert.deepEqual( [ state.liner, state.voxels ], [ false, true ] );
		assert.ok( state.voxelCounts.ok > 0 && state.voxelCounts.borderline > 0 );
		await saveScreenshot( page, 'workbench-voxels' );
		await show( { voxels: false, tongue: true, jaw: true } );

	} );

	test( 'copy puts every parameter into the box as JSON, and pasting it back restores them', async () => {

		const wanted = await pose( { tip_height: 3.5, jaw_opening: 6 } );
		await button( 'Copy JSON' ).click();
		const copied = JSON.parse( await jsonBox().inputValue() );
		assert.deepEqual( copied, wanted.params );
		await button( 'Reset' ).click();
		await settle( page );
		assert.equal( ( await readDebug( page ) ).params.tip_height, 0 );
		await button( 'Apply JSON' ).click();
		await settle( page );
		assert.deepEqual( ( await readDebug( page ) ).params, wanted.params );

	} );

	test( 'a bad paste shows a clear message in place and changes nothing', async () => {

		const before = ( await readDebug( page ) ).params;
		const alert = page.locator( '.wb-pose [role="alert"]' ).first();
		for ( const [ text, message ] of [
			[ '{"tip_height": 5,', /not valid JSON/ ],
			[ '{"tip_heigth": 5}', /Unknown parameter "tip_heigth": did you mean "tip_height"\?/ ],
			[ '{"tip_height": 40}', /tip_height = 40 is outside its range -18 to 8 mm/ ],
		] ) {

			await jsonBox().fill( text );
			await button( 'Apply JSON' ).click();
			await settle( page );
			assert.match( await alert.textContent(), message );
			assert.equal( await alert.isVisible(), true );
			const state = await readDebug( page );
			assert.deepEqual( state.params, before, `${ text } changed the parameters` );
			assert.match( state.workbench.pasteError, message );

		}

		await pose( before );
		assert.equal( await alert.isVisible(), false, 'a good paste clears the message' );

	} );

	test( 'Save pose saves the parameters under a name, and a second save of that name says it exists', async () => {

		const name = `e2e tongue ${ Date.now() }`;
		await page.getByRole( 'textbox', { name: 'Pose name' } ).fill( name );
		await button( 'Save pose' ).click();
		await page.waitForFunction( () => window.glasshead.workbench.poseStatus !== null, null, { timeout: 60_000 } );
		let state = await readDebug( page );
		assert.deepEqual( state.workbench.poseStatus, { ok: true, message: `Saved the pose "${ name }".` } );
		const saved = await ( await fetch( `${ server.baseUrl }/api/v1/poses?name=${ encodeURIComponent( name ) }`, { headers: authHeaders( author ) } ) ).json();
		assert.equal( saved.total, 1 );
		assert.equal( saved.poses[ 0 ].params.tip_height, state.params.tip_height );

		await button( 'Save pose' ).click();
		await page.waitForFunction( () => window.glasshead.workbench.poseStatus?.ok === false, null, { timeout: 60_000 } );
		state = await readDebug( page );
		assert.equal( state.workbench.poseStatus.message, `A pose named "${ name }" already exists. Choose another name.` );
		assert.match( await page.locator( '.wb-pose [role="alert"]' ).last().textContent(), /already exists/ );

	} );

	test( 'the head\'s formants follow the sliders: /i/ and /ɑ/ where the vowel chart puts them, and /m/ through the nose, as the server computes them', async () => {

		const shown = {};
		for ( const vowel of [ 'i', 'ɑ', 'm' ] ) {

			const target = await ( await fetch( `${ server.baseUrl }/api/v1/phonemes/${ encodeURIComponent( vowel ) }` ) ).json();
			const state = await pose( target.params );
			shown[ vowel ] = state.tractAcoustics;
			const answer = await ( await fetch( `${ server.baseUrl }/api/v1/tract/acoustics`, { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify( { params: target.params } ) } ) ).json();
			answer.formants.slice( 0, 3 ).forEach( ( f, k ) => assert.ok( Math.abs( shown[ vowel ].formants[ k ] - f.frequency_hz ) <= 0.03 * f.frequency_hz, `/${ vowel }/ F${ k + 1 }: ${ shown[ vowel ].formants[ k ] } Hz shown, ${ f.frequency_hz } Hz from the server` ) );
			assert.match( await page.locator( '.wb-formants-text' ).textContent(), new RegExp( `F1 ${ shown[ vowel ].formants[ 0 ] } Hz` ) );
			assert.equal( shown[ vowel ].nasalAt, answer.area_function.nasal?.at ?? null, `/${ vowel }/: the nose leaves where the server says` );
			if ( vowel === 'm' ) {

				assert.match( await page.locator( '.wb-formants-text' ).textContent(), /through the nose/ );
				await page.locator( '.wb-formants' ).scrollIntoViewIfNeeded();
				await saveScreenshot( page, 'workbench-formants-m' );

			}

		}

		assert.ok( shown.i.formants[ 0 ] < shown[ 'ɑ' ].formants[ 0 ] && shown.i.formants[ 1 ] > shown[ 'ɑ' ].formants[ 1 ], JSON.stringify( shown ) );
		assert.ok( shown.m.nasalAt > 0 && shown.m.formants[ 0 ] < 450 && shown.i.nasalAt === null, JSON.stringify( shown ) );
		await pose( ( await ( await fetch( `${ server.baseUrl }/api/v1/phonemes/i` ) ).json() ).params );
		await page.locator( '.wb-formants' ).scrollIntoViewIfNeeded();
		await saveScreenshot( page, 'workbench-formants' );

	} );

	test( 'no console errors appeared while using the workbench', () => {

		// The browser itself logs the 409 of the duplicate save above; that one is expected.
		const duplicate = /status of 409 \(Conflict\) \(.*\/api\/v1\/poses\)$/;
		assert.deepEqual( page.problems.filter( ( problem ) => ! duplicate.test( problem ) ), [] );

	} );

} );
