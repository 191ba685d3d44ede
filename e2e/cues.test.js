// End-to-end: the workbench's cue layer in Debian's Chromium at 1366 x 768, a projector's size. The
// cues switch on and off, lowering the velum gives the nasal flow strength, the tongue tip closing
// against the ridge stops the oral flow behind the closure, a narrow gap makes it turbulent, and a
// hidden layer draws nothing while the head is still. Assertions read `window.glasshead`; the
// screenshots cues-closure, cues-profile and cues-nasal are for a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { openLoaded, readDebug, saveScreenshot, serverAndBrowser, settle, waitForStill } from './harness.js';

describe( 'the cues', { timeout: 240_000 }, () => {

	let server, browser, page;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		page = await openLoaded( browser, `${ server.baseUrl }/#/workbench`, { width: 1366, height: 768 } );

	} );

	const cues = () => page.getByRole( 'group', { name: 'Cues' } );
	const button = ( name ) => cues().getByRole( 'button', { name, exact: true } );
	const slider = ( name ) => page.getByRole( 'slider', { name, exact: true } );

	async function setParam( name, label, value ) {

		await slider( label ).fill( String( value ) );
		await page.waitForFunction( ( [ n, v ] ) => window.glasshead.params[ n ] === v, [ name, value ] );

	}

	/** Out from the mouth to the whole tract, larynx to nose, for the screenshot. */
	async function zoomOut() {

		const box = await page.locator( '.wb-stage canvas' ).boundingBox();
		await page.mouse.move( box.x + box.width * 0.55, box.y + box.height * 0.6 );
		for ( let k = 0; k < 3; k ++ ) await page.mouse.wheel( 0, 250 );
		await settle( page );
		await page.waitForTimeout( 300 );

	}

	test( 'the cues are off by default, and a still workbench without them draws nothing', async () => {

		await waitForStill( page );
		const state = await readDebug( page );
		const { nasalStrength, oralStopped, oralStopMm, oralReachMm, oralFrontX, air, voicingShown } = state.cues;
		assert.deepEqual( state.cues, { visible: false, voicing: true, nasal: true, oral: true, turbulence: false, voicingShown, air, nasalStrength, oralStopped, oralStopMm, oralReachMm, oralFrontX } );
		assert.equal( air.glottisMm2, 5, 'no phoneme chosen: the glottis of a vowel' );
		assert.equal( await button( 'Voicing' ).isVisible(), false, 'the cue switches show with the layer' );
		await page.waitForTimeout( 1000 );
		assert.equal( ( await readDebug( page ) ).frames, state.frames, 'no frames while nothing moves' );

	} );

	test( 'the Cues toggle shows the layer, and it animates', async () => {

		await button( 'Cues' ).click();
		const before = await readDebug( page );
		assert.equal( before.cues.visible, true );
		assert.equal( await button( 'Voicing' ).getAttribute( 'aria-pressed' ), 'true' );
		assert.equal( await button( 'Oral airflow' ).getAttribute( 'aria-pressed' ), 'true' );
		// Frames come as fast as the machine allows (software WebGL): wait for a few.
		await page.waitForFunction( ( frames ) => window.glasshead.frames > frames + 3, before.frames, { timeout: 60_000, polling: 100 } );

	} );

	test( 'a raised velum gives no nasal flow and hides its switch; lowering it gives the flow strength', async () => {

		await page.getByRole( 'button', { name: 'Profile', exact: true } ).click();
		await setParam( 'velum_opening', 'Velum opening', 0 );
		await page.waitForFunction( () => window.glasshead.cues.nasalStrength === 0 );
		assert.equal( await button( 'Nasal airflow' ).isVisible(), false, 'no nasal switch with the port closed' );
		await setParam( 'velum_opening', 'Velum opening', 1 );
		await page.waitForFunction( () => window.glasshead.cues.nasalStrength > 0 );
		const { cues: state, velum } = await readDebug( page );
		assert.ok( state.nasalStrength > 0.9, `nasal strength ${ state.nasalStrength } at a port of ${ velum.nasalPortAreaMm2 } mm2` );
		assert.equal( await button( 'Nasal airflow' ).isVisible(), true );
		await page.waitForTimeout( 300 );
		await saveScreenshot( page, 'cues-nasal' );
		await setParam( 'velum_opening', 'Velum opening', 0 );

	} );

	test( 'the tongue tip closing against the ridge stops the oral flow behind the closure', async () => {

		// The lips at rest are 1.75 mm apart (a closed mouth): raise the upper lip, as for a vowel.
		await setParam( 'velum_opening', 'Velum opening', 0 );
		await setParam( 'upper_lip_raise', 'Upper lip raise', 4 );
		await page.waitForFunction( () => window.glasshead.constriction.widthMm > 2 );
		const open = ( await readDebug( page ) ).cues;
		assert.equal( open.turbulence, false, 'no turbulence with the mouth open' );
		assert.equal( open.oralStopped, false );
		await setParam( 'tip_height', 'Tip height', 8 );
		await setParam( 'tip_advancement', 'Tip advancement', 2 );
		await setParam( 'blade_height', 'Blade height', 5 );
		await page.waitForFunction( () => window.glasshead.constriction.widthMm === 0 && window.glasshead.cues.oralStopped );
		await zoomOut();
		// The dots move: read the flow a few times over a second and a half.
		for ( let k = 0; k < 6; k ++ ) {

			const { cues: state, constriction } = await readDebug( page );
			const closureX = Math.max( constriction.floor[ 0 ], constriction.roof[ 0 ] );
			assert.equal( state.oralStopped, true );
			assert.equal( state.turbulence, false, 'no air passes a closure, so no turbulence' );
			assert.ok( state.oralReachMm <= state.oralStopMm, `a dot ${ state.oralReachMm } mm along the path, the closure at ${ state.oralStopMm } mm` );
			assert.ok( state.oralFrontX !== null && state.oralFrontX < closureX + 1, `an oral dot at x = ${ state.oralFrontX } mm, past the closure at x = ${ closureX } mm` );
			assert.ok( open.oralFrontX > closureX + 10, `the open flow reached x = ${ open.oralFrontX } mm, beyond the lips` );
			await page.waitForTimeout( 250 );

		}

		await saveScreenshot( page, 'cues-closure' );

	} );

	test( 'a narrow gap is turbulent and the flow passes it: the lips at rest, 1.75 mm apart', async () => {

		for ( const [ name, label ] of [ [ 'tip_height', 'Tip height' ], [ 'tip_advancement', 'Tip advancement' ], [ 'blade_height', 'Blade height' ], [ 'upper_lip_raise', 'Upper lip raise' ] ] ) await setParam( name, label, 0 );
		await page.waitForFunction( () => window.glasshead.constriction.widthMm > 0.05 && window.glasshead.constriction.widthMm < 2 && ! window.glasshead.cues.oralStopped );
		const { cues: state, constriction } = await readDebug( page );
		assert.equal( state.turbulence, true, `turbulent at a constriction of ${ constriction.widthMm } mm` );
		await page.waitForFunction( ( x ) => window.glasshead.cues.oralFrontX > x + 10, Math.max( constriction.floor[ 0 ], constriction.roof[ 0 ] ) );
		await setParam( 'velum_opening', 'Velum opening', 1 );
		await page.waitForTimeout( 300 );
		await saveScreenshot( page, 'cues-profile' );
		await button( 'Oral airflow' ).click();
		assert.equal( ( await readDebug( page ) ).cues.turbulence, false, 'no turbulence without the oral flow' );
		await button( 'Oral airflow' ).click();

	} );

	test( 'the targets of /s ʃ f θ/ hiss, those of /m n t/ do not, /p b m/ close the lips, and /m/ sends its air out of the nose', async () => {

		await setParam( 'velum_opening', 'Velum opening', 0 );
		const seen = {};
		for ( const symbol of [ 'S', 'SH', 'F', 'TH', 'M', 'N', 'T', 'P', 'B' ] ) {

			await page.getByRole( 'combobox', { name: 'Phoneme target' } ).selectOption( symbol );
			await page.waitForFunction( ( s ) => window.glasshead.phonemeTarget.symbol === s && window.glasshead.phonemeTarget.state === 'target', symbol );
			await settle( page );
			const { cues: state, constriction } = await readDebug( page );
			seen[ symbol ] = { width: constriction.widthMm, place: constriction.place, turbulence: state.turbulence, stopped: state.oralStopped, ...state.air, voicing: state.voicingShown };
			if ( symbol === 'S' ) await saveScreenshot( page, 'cues-target-s' );

		}

		console.log( `# cues of the targets: ${ JSON.stringify( seen ) }` );
		for ( const symbol of [ 'S', 'SH', 'F', 'TH' ] ) assert.equal( seen[ symbol ].turbulence, true, `/${ symbol }/ hisses: ${ JSON.stringify( seen[ symbol ] ) }` );
		for ( const symbol of [ 'M', 'N', 'T' ] ) assert.equal( seen[ symbol ].turbulence, false, `/${ symbol }/ is silent: ${ JSON.stringify( seen[ symbol ] ) }` );
		// /p b m/ close the lips: their mid-sagittal sections meet (the diagram's 0.0 mm).
		for ( const symbol of [ 'P', 'B', 'M' ] ) assert.ok( seen[ symbol ].place === 'bilabial' && seen[ symbol ].width <= 0.05, `/${ symbol }/: ${ JSON.stringify( seen[ symbol ] ) }` );
		assert.equal( seen.S.glottisMm2 > seen.M.glottisMm2, true, 'the glottis is open for /s/' );
		assert.deepEqual( [ seen.S.voicing, seen.M.voicing ], [ false, true ], 'the voice sounds for /m/, not for /s/' );
		// /m/: no air out of the lips, all of it through the nose.
		assert.equal( seen.M.stopped, true, `/m/: ${ JSON.stringify( seen.M ) }` );
		assert.ok( seen.M.nasalFlow > 10 * seen.M.oralFlow, `/m/: ${ JSON.stringify( seen.M ) }` );

	} );

	test( 'switching the cues off stops the drawing, and no console errors appeared', async () => {

		await button( 'Cues' ).click();
		assert.equal( ( await readDebug( page ) ).cues.visible, false );
		await waitForStill( page );
		const before = await readDebug( page );
		await page.waitForTimeout( 1000 );
		assert.equal( ( await readDebug( page ) ).frames, before.frames, 'no frames once the cues are off' );
		assert.deepEqual( page.problems, [] );

	} );

} );
