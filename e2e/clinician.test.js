// End-to-end tests of the clinician view (#/clinician) in Debian's Chromium, on what a clinician
// meets first: a pose saved in the workbench with every group of parameters changed (tongue, jaw,
// lips, velum) chosen as the target, a real recording (the emuR engassim set) imported by choosing
// its file, kappa beside the raw agreement, readable names and titles, playback slow enough to
// follow, the selection kept in the URL, bad input refused in words, and long names cut. Assertions
// read `window.glasshead`; e2e/screenshots/clinician-1366x768.png and clinician-768x1024.png are for
// a person to look at.

import assert from 'node:assert/strict';
import { join, resolve } from 'node:path';
import { describe, test } from 'node:test';
import { apiSession, authHeaders, openSignedIn, signIn } from './accounts.js';
import { openPage, readDebug, REPO, saveScreenshot, SCREENSHOT_DIR, serverAndBrowser, settle } from './harness.js';

const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( REPO, '..', 'shared', 'data' );
const EMUR = join( DATA_DIR, 'epg', 'emur-engassim.json' );
/** A velar closure: the back of the tongue raised. */
const TONGUE = Object.freeze( { back_dorsum_height: 8, dorsum_height: 10, body_height: 4 } );
/** The workbench groups that are not the tongue's, each of which the saved pose changes. */
const OTHER_GROUPS = Object.freeze( [ 'jaw', 'lips', 'velum' ] );
const LONG_NAME = `velar closure with the lips rounded and the velum lowered, ${ 'a long name '.repeat( 4 ) }end`;

describe( 'the clinician view', { timeout: 300_000 }, () => {

	let server, browser, page, pose, sliders, recordingIds, session;

	/** A request of the test itself, made as the clinician. */
	const api = async ( method, path, body ) => {

		const response = await fetch( `${ server.baseUrl }/api/v1${ path }`, {
			method, headers: authHeaders( session, body ? { 'Content-Type': 'application/json' } : {} ), body: body ? JSON.stringify( body ) : undefined,
		} );
		const text = await response.text();
		return { status: response.status, body: text ? JSON.parse( text ) : null };

	};
	const clinician = () => readDebug( page ).then( ( state ) => state.clinician );
	const button = ( name ) => page.getByRole( 'button', { name, exact: true } );
	/** Open `hash` afresh (a reload, so that the view reads its URL again) and wait until it has loaded. */
	const openClinician = async ( hash ) => {

		await page.goto( `${ server.baseUrl }/${ hash }` );
		await page.reload();
		await page.waitForFunction( () => window.glasshead.clinician?.loaded === true, null, { timeout: 90_000, polling: 200 } );

	};

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		// A clinician saves the pose and reads the recordings.
		page = await openSignedIn( browser, server, 'clinician', `${ server.baseUrl }/#/workbench`, { width: 1366, height: 768 } );
		session = await apiSession( server, 'clinician' );

	} );

	test( 'a pose saved in the workbench with tongue, jaw, lips and velum changed is accepted by the contact route', async () => {

		sliders = await page.locator( 'input[data-param]' ).evaluateAll( ( nodes ) => nodes.map( ( n ) => ( {
			name: n.dataset.param, group: n.closest( 'fieldset' )?.dataset.group, min: Number( n.min ), max: Number( n.max ), neutral: Number( n.value ),
		} ) ) );
		const groups = new Set( sliders.map( ( s ) => s.group ) );
		for ( const group of OTHER_GROUPS ) assert.ok( groups.has( group ), `the workbench has a ${ group } group (has ${ [ ...groups ].join( ', ' ) })` );
		// The tongue's velar closure, and every jaw, lip and velum parameter a fifth of the way
		// from neutral toward the far end of its range.
		const params = { ...TONGUE };
		for ( const s of sliders.filter( ( s ) => OTHER_GROUPS.includes( s.group ) ) ) {

			const far = s.max - s.neutral >= s.neutral - s.min ? s.max : s.min;
			params[ s.name ] = Math.round( 100 * ( s.neutral + 0.2 * ( far - s.neutral ) ) ) / 100;

		}

		await page.getByRole( 'textbox', { name: 'Parameters as JSON' } ).fill( JSON.stringify( params ) );
		await button( 'Apply JSON' ).click();
		await settle( page );
		const shown = ( await readDebug( page ) ).params;
		for ( const [ name, value ] of Object.entries( params ) ) assert.ok( Math.abs( shown[ name ] - value ) <= 0.01, `${ name }: ${ shown[ name ] } in the workbench, ${ value } applied` );

		const name = `every group changed ${ Date.now() }`;
		await page.getByRole( 'textbox', { name: 'Pose name' } ).fill( name );
		await button( 'Save pose' ).click();
		await page.waitForFunction( () => window.glasshead.workbench.poseStatus !== null, null, { timeout: 60_000 } );
		assert.deepEqual( ( await readDebug( page ) ).workbench.poseStatus, { ok: true, message: `Saved the pose "${ name }".` } );
		pose = ( await api( 'GET', `/poses?name=${ encodeURIComponent( name ) }` ) ).body.poses[ 0 ];
		assert.deepEqual( Object.keys( pose.params ).sort(), sliders.map( ( s ) => s.name ).sort(), 'the workbench saves every parameter' );
		for ( const group of [ 'tongue', ...OTHER_GROUPS ] ) {

			const changed = sliders.filter( ( s ) => ( group === 'tongue' ? s.name in TONGUE : s.group === group ) && Math.abs( pose.params[ s.name ] - s.neutral ) > 1e-6 );
			assert.ok( changed.length > 0, `the saved pose changes the ${ group } group` );

		}

		const contacts = await api( 'POST', '/epg/contacts', { params: pose.params } );
		assert.equal( contacts.status, 200, `POST /epg/contacts with the saved params: ${ JSON.stringify( contacts.body ) }` );
		pose.rows = contacts.body.rows;

	} );

	test( 'the saved pose opens as the clinician\'s target and shows its synthetic palatogram', async () => {

		await openClinician( `#/clinician?target=pose:${ pose.id }` );
		await page.waitForFunction( () => window.glasshead.clinician.target3d !== null, null, { timeout: 90_000, polling: 200 } );
		const state = await clinician();
		assert.equal( state.error, null );
		assert.equal( state.target.name, `pose:${ pose.id }` );
		const epg = ( await readDebug( page ) ).epg;
		assert.equal( epg.source, 'clinician' );
		// The server's synthetic EPG of the saved parameters is shown, and the browser's own
		// contacts for them (tongue and jaw on the 3D palate) are the same.
		assert.deepEqual( epg.synthetic.rows, pose.rows );
		assert.deepEqual( state.target3d.rows, pose.rows );
		assert.ok( epg.synthetic.contacted >= 10, `${ epg.synthetic.contacted } contacts for a velar closure with the jaw a little open: ${ pose.rows.join( ' ' ) }` );
		assert.equal( state.speed, 0.1, 'playback starts at a tenth of real time' );
		assert.equal( await page.getByRole( 'combobox', { name: 'Playback speed' } ).inputValue(), '0.1' );

	} );

	test( 'choosing the emuR file imports its recordings, titled by word and speaker, and the URL holds the choice', async () => {

		const before = ( await api( 'GET', '/epg/recordings?limit=1' ) ).body.total;
		await page.getByLabel( 'Import a recording file' ).setInputFiles( EMUR );
		await page.waitForFunction( () => window.glasshead.clinician.imported !== null && window.glasshead.clinician.recording !== null && window.glasshead.clinician.agreement !== null, null, { timeout: 60_000, polling: 200 } );
		const state = await clinician();
		assert.equal( state.imported.ok, true, state.imported.message );
		recordingIds = state.imported.ids;
		assert.equal( recordingIds.length, 32 );
		assert.equal( ( await api( 'GET', '/epg/recordings?limit=1' ) ).body.total, before + 32 );
		assert.equal( state.recording.id, recordingIds[ 0 ] );
		assert.equal( state.recording.title, 'bescan (s→k), speaker sp1' );
		assert.match( await page.getByRole( 'status' ).filter( { hasText: 'Imported' } ).textContent(), /Imported "emur-engassim.json": 32 recordings\./ );
		const options = await page.getByRole( 'combobox', { name: 'Recording' } ).locator( 'option' ).allTextContents();
		assert.ok( options.includes( 'bescan (s→k), speaker sp1 (52 frames, 200 Hz)' ), options.slice( 0, 3 ).join( ' | ' ) );
		await page.waitForFunction( ( id ) => window.location.hash.includes( `recording=${ id }` ), recordingIds[ 0 ], { timeout: 60_000 } );
		assert.equal( await page.evaluate( () => window.location.hash ), `#/clinician?target=pose:${ pose.id }&recording=${ recordingIds[ 0 ] }` );

	} );

	test( 'kappa stands beside the raw agreement, as the compare API computes it, with an explanation', async () => {

		const state = await clinician();
		const report = ( await api( 'POST', `/epg/recordings/${ state.recording.id }/compare`, { reference: { pose_id: pose.id, frames: [ pose.rows ] } } ) ).body;
		assert.ok( Math.abs( state.kappa - report.kappa[ state.frame ] ) <= 1e-12, `kappa ${ state.kappa } vs ${ report.kappa[ state.frame ] }` );
		assert.ok( Math.abs( state.meanKappa - report.summary.mean_kappa ) <= 1e-12 );
		assert.ok( Math.abs( state.agreement - report.agreement[ state.frame ] ) <= 1e-12 );
		const caption = await page.locator( 'figure', { hasText: 'Agreement' } ).locator( '.cv-sub' ).textContent();
		assert.match( caption, /^κ −?\d\.\d\d \(mean −?\d\.\d\d\) · raw \d+ % \(mean \d+ %\)$/ );
		assert.ok( await page.getByText( /Cohen's kappa/ ).isVisible() );
		const heads = await page.getByRole( 'table', { name: 'EPG indices of this frame' } ).locator( 'th' ).allTextContents();
		assert.ok( heads.includes( 'Centre of gravity (rows: 0.5 = back R8 … 7.5 = front R1)' ), heads.join( ' | ' ) );
		assert.ok( heads.includes( 'difference (recording − target)' ) );
		assert.ok( ! heads.includes( 'cog' ) && ! heads.includes( 'alveolar_percent' ) );

	} );

	test( 'playing at the default speed moves slowly enough to follow', async () => {

		// On a page of its own whose clock the test moves on (Playwright's fake timers): the frame
		// shown after a second of the page's time, however fast the machine draws.
		const start = 10;
		const played = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( played, server, 'clinician' );
		await played.clock.install();
		await played.goto( `${ server.baseUrl }/#/clinician?target=pose:${ pose.id }&recording=${ recordingIds[ 0 ] }&frame=${ start }` );
		await played.waitForFunction( () => window.glasshead.clinician?.loaded === true && window.glasshead.clinician.recording !== null, null, { timeout: 90_000, polling: 200 } );
		const shown = () => readDebug( played ).then( ( state ) => state.clinician );
		const state = await shown();
		assert.deepEqual( [ state.speed, state.frame ], [ 0.1, start ] );
		await played.clock.pauseAt( await played.evaluate( () => Date.now() ) + 1000 );
		await played.evaluate( () => document.querySelector( 'button[aria-label="Play"]' ).click() );
		await played.clock.runFor( 1000 );
		const playing = await shown();
		// 1 s at a tenth of real time is 0.1 s of a 200 Hz take: 20 frames on (19 when the last
		// animation frame, 16 ms of the page's clock apart, came just before), never all 52.
		const rate = state.recording.frameRateHz;
		const [ least, most ] = [ start + Math.floor( ( 1 - 0.017 ) * 0.1 * rate ), start + Math.floor( 0.1 * rate + 1e-9 ) ];
		assert.ok( playing.playing && playing.frame >= least && playing.frame <= most, `frame ${ playing.frame } of ${ state.frames } 1 s after Play from ${ start }, ${ least } to ${ most } wanted` );
		assert.deepEqual( played.problems, [] );
		await played.context().close();

	} );

	test( 'a reload restores the target, the recording and the frame from the URL', async () => {

		await page.getByRole( 'slider', { name: 'Frame' } ).fill( '30' );
		const id = recordingIds[ 0 ];
		await page.waitForFunction( () => window.location.hash.includes( 'frame=30' ), null, { timeout: 60_000 } );
		await page.reload();
		await page.waitForFunction( () => window.glasshead.clinician?.loaded === true, null, { timeout: 90_000, polling: 200 } );
		const state = await clinician();
		assert.equal( state.error, null );
		assert.equal( state.target.name, `pose:${ pose.id }` );
		assert.equal( state.recording.id, id );
		assert.equal( state.frame, 30 );
		assert.equal( await page.getByRole( 'combobox', { name: 'Recording' } ).inputValue(), String( id ) );

	} );

	test( 'the frame slider is a 44 px touch target, and the strip of frames takes the focus and steps with the arrows', async () => {

		const slider = await page.getByRole( 'slider', { name: 'Frame' } ).boundingBox();
		assert.ok( slider.height >= 44, `the frame slider is ${ slider.height } px tall` );
		const strip = page.getByRole( 'img', { name: /Palatograms over time/ } );
		assert.equal( await strip.evaluate( ( node ) => node.tabIndex ), 0 );
		await strip.focus();
		const before = ( await clinician() ).frame;
		await page.keyboard.press( 'ArrowRight' );
		assert.equal( ( await clinician() ).frame, before + 1 );

	} );

	test( 'bad values in the URL are said in words and nothing is chosen', async () => {

		await openClinician( '#/clinician?target=pose:999999&recording=abc&frame=-3' );
		const state = await clinician();
		assert.equal( state.target, null );
		assert.equal( state.recording, null );
		assert.match( state.error, /recording "abc" is not a recording number/ );
		assert.match( state.error, /frame "-3" is not a frame number/ );
		assert.match( state.error, /target "pose:999999" does not exist/ );
		assert.ok( await page.getByRole( 'alert' ).filter( { hasText: 'does not exist' } ).isVisible() );

	} );

	test( 'a dropped file that is not a recording is refused in plain words beside the import box, and nothing is stored', async () => {

		const before = ( await api( 'GET', '/epg/recordings?limit=1' ) ).body.total;
		const dataTransfer = await page.evaluateHandle( () => {

			const transfer = new DataTransfer();
			transfer.items.add( new File( [ 'name,age\nanna,7\n' ], 'notes.csv', { type: 'text/csv' } ) );
			return transfer;

		} );
		await page.locator( '.cv-import' ).dispatchEvent( 'drop', { dataTransfer } );
		await page.waitForFunction( () => window.glasshead.clinician.imported?.ok === false, null, { timeout: 30_000, polling: 100 } );
		const { imported } = await clinician();
		assert.match( imported.message, /^The file could not be imported, nothing was stored: / );
		const alert = page.locator( '.cv-import [role="alert"]' );
		assert.ok( await alert.isVisible() );
		assert.equal( await alert.textContent(), imported.message );
		assert.equal( ( await api( 'GET', '/epg/recordings?limit=1' ) ).body.total, before );

	} );

	test( 'a long pose name is cut with an ellipsis in its card and shown whole on hover', async () => {

		const created = await api( 'POST', '/poses', { name: LONG_NAME, params: TONGUE } );
		assert.equal( created.status, 201, JSON.stringify( created.body ) );
		await openClinician( `#/clinician?target=pose:${ created.body.id }&recording=${ recordingIds[ 0 ] }&frame=20` );
		const state = await clinician();
		assert.equal( state.error, null );
		assert.equal( state.target.label, LONG_NAME );
		const caption = page.locator( 'figure', { hasText: 'Target (synthetic)' } ).locator( '.cv-sub' );
		const box = await caption.evaluate( ( node ) => ( { scroll: node.scrollWidth, client: node.clientWidth, height: node.clientHeight, title: node.title, overflow: getComputedStyle( node ).textOverflow } ) );
		assert.equal( box.title, LONG_NAME );
		assert.equal( box.overflow, 'ellipsis' );
		assert.ok( box.scroll > box.client, 'the name is longer than its card and cut' );
		assert.ok( box.height < 30, `the caption stays on one line (${ box.height } px)` );

	} );

	test( 'the head saying the take\'s own phones on its timing is scored phone by phone', async () => {

		const id = recordingIds[ 0 ]; // bescan, s->k
		await openClinician( `#/clinician?target=said:${ id }&recording=${ id }` );
		await page.waitForFunction( () => window.glasshead.clinician.phones !== null, null, { timeout: 90_000, polling: 200 } );
		const state = await clinician();
		assert.equal( state.error, null );
		assert.equal( state.target.frames, state.recording.frames, 'one frame of the head per frame of the take' );
		assert.deepEqual( state.phones.map( ( p ) => p.symbol ), [ 'S', 'K' ] );
		assert.equal( state.phones.reduce( ( sum, p ) => sum + p.frames, 0 ), state.recording.frames );
		assert.equal( state.target3d, null );
		assert.match( await page.locator( 'figcaption', { hasText: 'Target on the palate' } ).textContent(), /shown for a target of one pose/ );
		const said = ( await api( 'POST', `/epg/recordings/${ id }/coarticulated`, {} ) ).body;
		const report = ( await api( 'POST', `/epg/recordings/${ id }/compare`, { reference: { frames: said.frames, t_s: said.t_s, phones: said.phones } } ) ).body;
		for ( const [ k, phone ] of state.phones.entries() ) assert.ok( Math.abs( phone.mean_kappa - report.phones[ k ].mean_kappa ) <= 1e-12 );
		const line = await page.locator( 'figure', { hasText: 'Agreement' } ).getByText( /^Per phone:/ ).textContent();
		assert.match( line, /^Per phone: \/s\/ κ −?\d\.\d\d \(\d+ frames\) · \/k\/ κ −?\d\.\d\d \(\d+ frames\); mean over the phones κ −?\d\.\d\d$/ );
		await saveScreenshot( page, 'clinician-said-1366' );

	} );

	test( 'the view at a laptop and a tablet size is saved as screenshots', async () => {

		await openClinician( `#/clinician?target=pose:${ pose.id }&recording=${ recordingIds[ 0 ] }&frame=30` );
		await page.waitForFunction( () => window.glasshead.clinician.target3d !== null, null, { timeout: 90_000, polling: 200 } );
		await page.waitForTimeout( 500 );
		await page.screenshot( { path: join( SCREENSHOT_DIR, 'clinician-1366x768.png' ) } );
		await page.setViewportSize( { width: 768, height: 1024 } );
		await page.waitForTimeout( 800 );
		await page.screenshot( { path: join( SCREENSHOT_DIR, 'clinician-768x1024.png' ) } );
		const state = await clinician();
		assert.equal( state.error, null );
		assert.equal( state.frame, 30 );

	} );

	test( 'no console errors appeared, but the refused import\'s own 422', () => {

		const refused = /status of 422 \(Unprocessable (Entity|Content)\) \(.*\/api\/v1\/epg\/recordings\)$/;
		assert.deepEqual( page.problems.filter( ( problem ) => ! refused.test( problem ) ), [] );

	} );

} );
