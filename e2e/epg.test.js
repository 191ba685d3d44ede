// End-to-end tests of synthetic EPG in Debian's Chromium: the electrodes and live palatogram of the
// head view, and the clinician view on a real recording (the emuR engassim set, uploaded through
// the API) against a saved pose and a phoneme target. Assertions read `window.glasshead`; the screenshots
// e2e/screenshots/clinician.png and epg-3d.png are for a person to look at.

import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { describe, test } from 'node:test';
import { apiSession, authHeaders, signIn } from './accounts.js';
import { openPage, readDebug, REPO, SCREENSHOT_DIR, serverAndBrowser, waitForLoaded } from './harness.js';

const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( REPO, '..', 'shared', 'data' );
const EMUR = join( DATA_DIR, 'epg', 'emur-engassim.json' );
/** A velar closure (the back of the tongue raised) and an alveolar one (the tip raised). */
const POSES = Object.freeze( {
	'k closure (e2e)': { back_dorsum_height: 8, dorsum_height: 10, body_height: 4 },
	't closure (e2e)': { tip_height: 8, tip_advancement: 4, blade_height: 4 },
} );

describe( 'synthetic EPG and the clinician view', { timeout: 300_000 }, () => {

	let server, browser, page, api, recording, detail, poses;

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		// Recordings and saved poses are a clinician's: the test's requests and the page are one's.
		const session = await apiSession( server, 'clinician' );
		api = async ( method, path, body ) => {

			const response = await fetch( `${ server.baseUrl }/api/v1${ path }`, {
				method, headers: authHeaders( session, body ? { 'Content-Type': 'application/json' } : {} ), body: body ? JSON.stringify( body ) : undefined,
			} );
			const text = await response.text();
			return { status: response.status, body: text ? JSON.parse( text ) : null };

		};

		const upload = await api( 'POST', '/epg/recordings', { format: 'emur-json', content: JSON.parse( readFileSync( EMUR, 'utf8' ) ) } );
		assert.equal( upload.status, 201, `upload of ${ EMUR }: ${ JSON.stringify( upload.body ) }` );
		assert.equal( upload.body.total, 32 );
		recording = upload.body.recordings.find( ( r ) => r.name.startsWith( 'sp1bescan' ) );
		detail = ( await api( 'GET', `/epg/recordings/${ recording.id }` ) ).body;
		poses = {};
		for ( const [ name, params ] of Object.entries( POSES ) ) {

			const created = await api( 'POST', '/poses', { name, description: 'end-to-end test', params } );
			poses[ name ] = created.status === 201 ? created.body : ( await api( 'GET', `/poses?name=${ encodeURIComponent( name ) }` ) ).body.poses[ 0 ];

		}

		page = await openPage( browser, { width: 1400, height: 1020 } );
		await signIn( page, server, 'clinician' );

	} );

	const clinician = () => readDebug( page ).then( ( state ) => state.clinician );
	const epg = () => readDebug( page ).then( ( state ) => state.epg );
	const recordingCanvas = () => page.getByRole( 'img', { name: 'Recording palatogram (real)' } );

	test( 'the layout API serves the Reading palate and the dense grid on the scene palate', async () => {

		const reading = await api( 'GET', '/epg/layout' );
		assert.equal( reading.status, 200, JSON.stringify( reading.body ) );
		assert.equal( reading.body.electrodes.length, 62 );
		assert.deepEqual( reading.body.electrodes.filter( ( e ) => e.row === 1 ).map( ( e ) => e.column ), [ 2, 3, 4, 5, 6, 7 ] );
		assert.equal( ( await api( 'GET', '/epg/layout?grid=dense96' ) ).body.electrodes.length, 96 );

	} );

	test( 'the head view shows the live palatogram and reports no contact for the resting tongue', async () => {

		await page.goto( `${ server.baseUrl }/#/` );
		await waitForLoaded( page );
		await page.waitForFunction( () => window.glasshead.epg !== undefined, null, { timeout: 30_000 } );
		const live = await epg();
		assert.equal( live.source, 'live' );
		assert.equal( live.contacted, 0 );
		assert.deepEqual( live.rows, Array( 8 ).fill( '00000000' ) );
		assert.ok( await page.getByRole( 'img', { name: /Live synthetic palatogram/ } ).isVisible() );

	} );

	test( 'the clinician view loads the recording and the saved pose, and shows the pose on the 3D palate', async () => {

		const pose = poses[ 'k closure (e2e)' ];
		await page.goto( `${ server.baseUrl }/#/clinician?recording=${ recording.id }&target=pose:${ pose.id }` );
		await page.waitForFunction( () => window.glasshead.clinician?.loaded === true && window.glasshead.clinician.target3d !== null, null, { timeout: 90_000, polling: 200 } );
		const state = await clinician();
		assert.equal( state.error, null );
		assert.equal( state.recording.frames, detail.n_frames );
		assert.equal( state.recording.frameRateHz, detail.frame_rate_hz );
		assert.equal( state.frame, 0 );
		const shown = await epg();
		assert.equal( shown.source, 'clinician' );
		assert.deepEqual( shown.recording.rows, detail.frames[ 0 ] );
		// The synthetic EPG the server computed (Python) is the one the browser computes (JS).
		const reference = ( await api( 'POST', '/epg/contacts', { params: pose.params } ) ).body;
		assert.deepEqual( shown.synthetic.rows, reference.rows );
		assert.deepEqual( state.target3d.rows, reference.rows );
		assert.ok( state.target3d.contacted >= 20, `${ state.target3d.contacted } contacts for a velar closure` );
		assert.equal( state.target3d.squares, state.target3d.contacted );
		assert.deepEqual( reference.rows.slice( 5 ), [ '11111111', '11111111', '11111111' ] );
		await page.getByRole( 'img', { name: /target on the 3D palate/ } ).screenshot( { path: join( SCREENSHOT_DIR, 'epg-3d.png' ) } );

	} );

	test( 'the agreement is the compare API\'s', async () => {

		const pose = poses[ 'k closure (e2e)' ];
		const reference = ( await api( 'POST', '/epg/contacts', { params: pose.params } ) ).body;
		const report = ( await api( 'POST', `/epg/recordings/${ recording.id }/compare`, { reference: { label: pose.name, pose_id: pose.id, frames: [ reference.rows ] } } ) ).body;
		const state = await clinician();
		// Shares of electrodes, from the API in JSON: equal up to rounding.
		assert.ok( Math.abs( state.meanAgreement - report.summary.mean_agreement ) <= 1e-12, `mean agreement ${ state.meanAgreement } vs ${ report.summary.mean_agreement }` );
		assert.ok( Math.abs( state.agreement - report.agreement[ 0 ] ) <= 1e-12, `agreement ${ state.agreement } vs ${ report.agreement[ 0 ] }` );

	} );

	test( 'stepping with the keys and the buttons moves frame by frame and changes the palatogram', async () => {

		const changed = detail.frames.findIndex( ( rows ) => rows.join() !== detail.frames[ 0 ].join() );
		assert.ok( changed > 0, 'the recording changes over time' );
		const before = await recordingCanvas().screenshot();
		await page.locator( '.cv-main' ).click( { position: { x: 5, y: 5 } } );
		for ( let k = 0; k < changed; k ++ ) await page.keyboard.press( 'ArrowRight' );
		let state = await clinician();
		assert.equal( state.frame, changed );
		assert.deepEqual( ( await epg() ).recording.rows, detail.frames[ changed ] );
		const after = await recordingCanvas().screenshot();
		assert.notDeepEqual( after, before, 'the palatogram is redrawn with the new contacts' );
		await page.getByRole( 'button', { name: 'Previous frame' } ).click();
		state = await clinician();
		assert.equal( state.frame, changed - 1 );
		await page.getByRole( 'button', { name: 'Last frame' } ).click();
		assert.equal( ( await clinician() ).frame, detail.n_frames - 1 );
		await page.keyboard.press( 'Home' );
		assert.equal( ( await clinician() ).frame, 0 );

	} );

	test( 'playing at real time runs through the frames at the recording\'s own frame times', async () => {

		// On a page of its own whose clock the test moves on (Playwright's fake timers): the frame
		// shown after so many milliseconds of the page's time, however fast the machine draws.
		const played = await openPage( browser, { width: 1400, height: 1020 } );
		await signIn( played, server, 'clinician' );
		await played.clock.install();
		await played.goto( `${ server.baseUrl }/#/clinician?recording=${ recording.id }` );
		await played.waitForFunction( () => window.glasshead.clinician?.loaded === true && window.glasshead.clinician.recording !== null, null, { timeout: 90_000, polling: 200 } );
		const shown = () => readDebug( played ).then( ( state ) => state.clinician );
		assert.equal( ( await shown() ).speed, 0.1, 'playback starts at a tenth of real time' );
		await played.getByRole( 'combobox', { name: 'Playback speed' } ).selectOption( '1' );
		assert.equal( ( await shown() ).speed, 1 );
		await played.clock.pauseAt( await played.evaluate( () => Date.now() ) + 1000 );
		await played.evaluate( () => document.querySelector( 'button[aria-label="Play"]' ).click() );
		const times = detail.t_s;
		const frameAt = ( elapsed ) => times.findLastIndex( ( t ) => t <= times[ 0 ] + elapsed + 1e-9 );
		let ms = 0;
		for ( const step of [ 40, 60, 100 ] ) {

			await played.clock.runFor( step );
			ms += step;
			// The view moves on at animation frames, 16 ms apart on the page's clock.
			const [ least, most ] = [ frameAt( ( ms - 17 ) / 1000 ), frameAt( ms / 1000 ) ];
			const state = await shown();
			assert.ok( state.playing && state.frame >= least && state.frame <= most, `frame ${ state.frame } ${ ms } ms after Play at real time, ${ least } to ${ most } wanted` );

		}

		await played.clock.runFor( Math.ceil( ( times.at( - 1 ) - times[ 0 ] ) * 1000 ) );
		const end = await shown();
		assert.deepEqual( [ end.playing, end.frame ], [ false, detail.n_frames - 1 ], 'stopped on the last frame' );
		assert.deepEqual( played.problems, [] );
		await played.context().close();

	} );

	test( 'the clinician view at a frame of the closure is saved as a screenshot', async () => {

		const frame = Math.round( detail.n_frames * 0.4 );
		await page.getByRole( 'slider', { name: 'Frame' } ).fill( String( frame ) );
		assert.equal( ( await clinician() ).frame, frame );
		await page.waitForTimeout( 300 );
		await page.screenshot( { path: join( SCREENSHOT_DIR, 'clinician.png' ), fullPage: true } );

	} );

	test( 'the target list offers the phoneme targets; choosing /t/ shows its synthetic palatogram', async () => {

		const built = await api( 'GET', '/phonemes/T' );
		assert.equal( built.status, 200, JSON.stringify( built.body ) );
		const options = await page.getByRole( 'combobox', { name: 'Target' } ).locator( 'optgroup[label="Phoneme targets"] option' ).evaluateAll( ( nodes ) => nodes.map( ( n ) => n.value ) );
		assert.equal( options.length, 39 );
		assert.ok( options.includes( 'phoneme:T' ) && options.every( ( v ) => v.startsWith( 'phoneme:' ) ), 'the phonemes are a group of their own' );
		await page.getByRole( 'combobox', { name: 'Target' } ).selectOption( 'phoneme:T' );
		await page.waitForFunction( () => window.glasshead.clinician?.target?.name === 'phoneme:T' && window.glasshead.clinician.target3d !== null, null, { timeout: 60_000, polling: 200 } );
		// The 3D palate's contacts are computed after the choice (the last target's until then):
		// wait, however long that takes, until they are /t/'s; the checks below say what differs.
		await page.waitForFunction( ( rows ) => [ window.glasshead.clinician.target3d?.rows, window.glasshead.epg?.synthetic?.rows ].every( ( shown ) => JSON.stringify( shown ) === JSON.stringify( rows ) ),
			built.body.epg.rows, { timeout: 60_000, polling: 200 } ).catch( () => {} );
		const state = await clinician();
		assert.equal( state.error, null );
		const shown = await epg();
		// The palatogram shown is the built target's, and the browser's own contacts for its
		// parameters (the 3D palate, tongue and jaw only) are the same.
		assert.deepEqual( shown.synthetic.rows, built.body.epg.rows );
		assert.deepEqual( state.target3d.rows, built.body.epg.rows );
		// Front closure: a complete row across R1-R4. The build's realism report says whether the
		// fitted /t/ reaches it (docs/targets.md); the view must show what the build computed.
		const rows = built.body.epg.rows;
		const frontClosure = rows.slice( 0, 4 ).some( ( row, k ) => ( k === 0 ? row.slice( 1, 7 ) : row ) === ( k === 0 ? '111111' : '11111111' ) );
		const report = ( await api( 'GET', '/phonemes' ) ).body;
		assert.equal( report.count, 39 );
		console.log( `# /t/ synthetic EPG ${ rows.join( ' ' ) }: front closure ${ frontClosure }` );
		await page.waitForTimeout( 300 );
		await page.screenshot( { path: join( SCREENSHOT_DIR, 'clinician-phoneme-t.png' ), fullPage: true } );

	} );

	test( 'no console errors appeared', () => {

		assert.deepEqual( page.problems, [] );

	} );

} );
