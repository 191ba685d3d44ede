// End-to-end, in Debian's Chromium: keeping the sound of a child's attempts, which only a
// clinician can switch on. The clinician switches it on for a child on #/clinician; the child
// sees the red dot, says the target into the microphone (Chromium's fake microphone playing a
// real child's "heed") and the attempt's record gets its sound: a 16 kHz 16-bit WAV of the
// attempt's length, which the clinician then plays from the practice table. A sound the server
// does not take is said in plain words, and the try stays saved. Switched off again, the child's
// next attempt sends no sound at all: no request carries audio. Screenshots of the switch at a
// desktop's and an upright tablet's size (recording-switch-*.png), of the child's red dot and of
// the clinician's player are for a person to look at.

import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { after, before, describe, test } from 'node:test';
import { parseWav } from '../web/src/core/listen/wav.js';
import { MAX_ATTEMPT_S } from '../web/src/ui/practice/PracticeListener.js';
import { KEEPING_LABEL } from '../web/src/ui/practice/PracticeAudio.js';
import { SWITCH_LABEL } from '../web/src/ui/clinician/RecordingSwitch.js';
import { apiSession, authHeaders, signIn } from './accounts.js';
import { fakeMicrophoneArgs, launchBrowser, openPage, readDebug, REPO, saveScreenshot, startServer } from './harness.js';

const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( REPO, '..', 'shared', 'data' );
/** Boy 14 of Hillenbrand et al. (1995) saying "heed": the fake microphone plays it, looped. */
const HEED = join( DATA_DIR, 'speech', 'hillenbrand1995-dev', 'audio', 'b14iy.wav' );
const DESKTOP = Object.freeze( { width: 1920, height: 1080 } );
const TABLET = Object.freeze( { width: 768, height: 1024 } );
/** The smallest touch target of the adults' views, CSS pixels. */
const TOUCH_PX = 44;

describe( 'keeping the sound of a child\'s attempts', { timeout: 900_000 }, () => {

	let server, browser, clinician, teacher, caseload, ada, clinicianPage, childPage;
	/** Every request the child's page made: { method, url, type, riff }. */
	const childRequests = [];

	/** A request of the test itself, as `session`: { status, headers, body } (JSON when it is). */
	const api = async ( session, method, path, body ) => {

		const response = await fetch( `${ server.baseUrl }/api/v1/${ path }`, {
			method, headers: authHeaders( session, body ? { 'Content-Type': 'application/json' } : {} ), body: body ? JSON.stringify( body ) : undefined,
		} );
		const type = response.headers.get( 'content-type' ) ?? '';
		const answer = type.includes( 'json' ) ? await response.json() : new Uint8Array( await response.arrayBuffer() );
		return { status: response.status, headers: response.headers, body: answer };

	};
	const practice = async () => ( await readDebug( childPage ) ).practice;
	const child = async () => ( await readDebug( clinicianPage ) ).clinicianChild;

	/** The clinician view, at the child's history, once the switch has been read. */
	async function openChildHistory() {

		await clinicianPage.goto( `${ server.baseUrl }/#/clinician` );
		await clinicianPage.reload();
		await clinicianPage.waitForFunction( () => window.glasshead?.clinicianChild?.loaded === true, null, { timeout: 90_000 } );
		await clinicianPage.getByRole( 'figure', { name: 'A child’s history' } ).getByLabel( 'Child', { exact: true } ).selectOption( String( ada.id ) );
		await clinicianPage.waitForFunction( ( id ) => {

			const state = window.glasshead.clinicianChild;
			return state.child === id && state.recording.child === id && /^(On|Off)/.test( state.recording.words ) && state.practice !== undefined;

		}, ada.id, { timeout: 30_000 } );
		await clinicianPage.getByRole( 'switch', { name: SWITCH_LABEL } ).scrollIntoViewIfNeeded();

	}

	/** Flip the switch through the page and wait for the server's answer to show. */
	async function flipSwitch( on ) {

		const control = clinicianPage.getByRole( 'switch', { name: SWITCH_LABEL } );
		assert.equal( await control.isChecked(), ! on );
		await control.click();
		await clinicianPage.waitForFunction( ( wanted ) => {

			const state = window.glasshead.clinicianChild.recording;
			return state.busy === false && state.enabled === wanted && state.words.startsWith( wanted ? 'On since' : 'Off since' );

		}, on, { timeout: 30_000 } );

	}

	/** One spoken attempt at the current item, rated "Got it"; resolves to the id of its record. */
	async function sayAndRate() {

		await childPage.waitForFunction( () => window.glasshead.practice?.ready === true, null, { timeout: 300_000, polling: 200 } );
		await childPage.getByRole( 'button', { name: 'Say it' } ).click();
		await childPage.waitForFunction( () => window.glasshead.practice.attempt !== null && window.glasshead.practice.listening === false, null, { timeout: 60_000, polling: 100 } );
		const before = ( await practice() ).recorded.length;
		await childPage.getByRole( 'button', { name: 'Got it' } ).click();
		await childPage.waitForFunction( ( n ) => window.glasshead.practice.recorded.length > n, before, { timeout: 60_000 } );
		return ( await practice() ).recorded.at( - 1 );

	}

	before( async () => {

		if ( ! existsSync( HEED ) ) throw new Error( `missing recording ${ HEED }: the test needs ../shared/data (set GLASSHEAD_DATA_DIR)` );
		server = await startServer();
		browser = await launchBrowser( { args: fakeMicrophoneArgs( HEED ) } );
		clinician = await apiSession( server, 'clinician' );
		teacher = await apiSession( server, 'teacher' );
		const author = await apiSession( server, 'author' );
		caseload = ( await api( clinician, 'POST', 'classes', { name: 'Caseload R' } ) ).body;
		ada = ( await api( clinician, 'POST', 'children', { class_id: caseload.id, display_name: 'Ada', avatar: 'owl' } ) ).body;
		const lesson = ( await api( author, 'POST', 'lessons', { title: 'The vowel in heed', items: [ { target: { kind: 'phoneme', text: 'i' }, presentation: 'static' } ] } ) ).body;
		assert.equal( ( await api( clinician, 'POST', 'assignments', { lesson_id: lesson.id, class_id: caseload.id } ) ).status, 201 );

		clinicianPage = await openPage( browser, DESKTOP );
		await signIn( clinicianPage, server, 'clinician' );
		const context = await browser.newContext( { viewport: { width: 1024, height: 768 }, deviceScaleFactor: 1 } );
		await context.grantPermissions( [ 'microphone' ], { origin: server.baseUrl } );
		childPage = await context.newPage();
		childPage.problems = [];
		childPage.on( 'pageerror', ( error ) => childPage.problems.push( error.message ) );
		childPage.on( 'request', ( request ) => {

			const body = request.postDataBuffer();
			childRequests.push( { method: request.method(), url: request.url(), type: request.headers()[ 'content-type' ] ?? '', riff: body?.subarray( 0, 4 ).toString( 'latin1' ) === 'RIFF', bytes: body?.length ?? 0 } );

		} );

	} );

	after( async () => {

		await browser?.close();
		await server?.stop();

	} );

	test( 'a clinician switches recording on for a child, and the page says since when and by whom', async () => {

		await openChildHistory();
		const state = ( await child() ).recording;
		assert.deepEqual( [ state.enabled, state.checked, state.disabled, state.words ], [ false, false, false, 'Off' ], 'off until someone switches it on' );
		await flipSwitch( true );
		const shown = ( await child() ).recording.words;
		assert.match( shown, /^On since \d{1,2} [A-Z][a-z]+ 20\d\d, \d\d:\d\d UTC, by E2E Clinician$/ );
		const answer = ( await api( clinician, 'GET', `children/${ ada.id }/audio-recording` ) ).body;
		assert.deepEqual( [ answer.enabled, answer.set_by_name, answer.history.length ], [ true, 'E2E Clinician', 1 ] );
		// The switch is a teacher's to read, not to set.
		const refused = await api( teacher, 'PUT', `children/${ ada.id }/audio-recording`, { enabled: false } );
		assert.equal( refused.status, 403 );
		assert.ok( refused.body.detail, 'a refusal says why' );
		const box = await clinicianPage.getByRole( 'switch', { name: SWITCH_LABEL } ).boundingBox();
		assert.ok( box.height >= TOUCH_PX && box.width >= TOUCH_PX, `the switch is ${ box.width } x ${ box.height } px` );
		await saveScreenshot( clinicianPage, 'recording-switch-1920x1080' );
		await clinicianPage.setViewportSize( TABLET );
		await clinicianPage.getByRole( 'switch', { name: SWITCH_LABEL } ).scrollIntoViewIfNeeded();
		const overflow = await clinicianPage.evaluate( () => document.documentElement.scrollWidth - window.innerWidth );
		assert.ok( overflow <= 0, `${ overflow } px wider than the tablet` );
		await saveScreenshot( clinicianPage, 'recording-switch-768x1024' );
		await clinicianPage.setViewportSize( DESKTOP );

	} );

	test( 'the child sees the red dot, and the attempt\'s record gets its sound: a 16 kHz WAV of the attempt', async () => {

		await childPage.goto( `${ server.baseUrl }/#/practice` );
		await childPage.getByRole( 'textbox', { name: 'Class code' } ).fill( caseload.join_code );
		await childPage.getByRole( 'button', { name: 'Go' } ).click();
		await childPage.getByRole( 'button', { name: 'Ada', exact: true } ).click(); // one lesson: it starts at once
		await childPage.getByText( KEEPING_LABEL ).waitFor( { state: 'visible', timeout: 60_000 } );
		await childPage.waitForFunction( () => window.glasshead.practice?.ready === true, null, { timeout: 300_000, polling: 200 } );
		await saveScreenshot( childPage, 'recording-practice-1024x768' );
		const id = await sayAndRate();
		await childPage.waitForFunction( ( record ) => window.glasshead.practice.audio.kept.includes( record ) || window.glasshead.practice.audio.failed.includes( record ), id, { timeout: 60_000 } );
		const { audio } = await practice();
		assert.deepEqual( [ audio.kept, audio.failed ], [ [ id ], [] ] );
		const uploads = childRequests.filter( ( r ) => r.riff || /\/audio$/.test( new URL( r.url ).pathname ) );
		assert.deepEqual( uploads.map( ( r ) => [ r.method, new URL( r.url ).pathname, r.type, r.riff ] ), [ [ 'PUT', `/api/v1/practice/${ id }/audio`, 'audio/wav', true ] ] );

		const kept = await api( clinician, 'GET', `practice/${ id }/audio` );
		assert.equal( kept.status, 200 );
		assert.match( kept.headers.get( 'content-type' ), /^audio\/(x-)?wav/ );
		const wav = parseWav( kept.body );
		const seconds = wav.samples.length / wav.sampleRate;
		assert.deepEqual( [ wav.sampleRate, wav.channels, wav.bitsPerSample ], [ 16000, 1, 16 ] );
		assert.ok( seconds >= 0.5 && seconds <= MAX_ATTEMPT_S + 1, `the attempt lasted ${ seconds } s` );
		let peak = 0;
		for ( const v of wav.samples ) peak = Math.max( peak, Math.abs( v ) );
		assert.ok( peak > 0.01, `the child's voice is in it (peak ${ peak })` );
		const records = ( await api( clinician, 'GET', `practice?child_id=${ ada.id }` ) ).body.records;
		assert.deepEqual( records.map( ( r ) => [ r.id, r.has_audio ] ), [ [ id, true ] ] );
		assert.deepEqual( childPage.problems, [] );

	} );

	test( 'the clinician plays the kept sound from the practice table', async () => {

		await openChildHistory();
		const [ record ] = ( await api( clinician, 'GET', `practice?child_id=${ ada.id }` ) ).body.records;
		const row = clinicianPage.locator( `tr[data-practice="${ record.id }"]` );
		const play = row.getByRole( 'button', { name: /^Play the go of / } );
		await play.waitFor( { timeout: 30_000 } );
		const box = await play.boundingBox();
		assert.ok( box.height >= TOUCH_PX, `the play button is ${ box.height } px high` );
		await play.click();
		await clinicianPage.waitForFunction( ( id ) => {

			const sound = window.glasshead.clinicianChild.sound;
			return sound.error !== null || ( sound.opened.includes( id ) && sound.via !== null );

		}, record.id, { timeout: 30_000 } );
		const sound = ( await child() ).sound;
		await row.scrollIntoViewIfNeeded();
		await saveScreenshot( clinicianPage, 'recording-play-1920x1080' );
		assert.equal( sound.error, null );
		assert.equal( sound.via, 'element', JSON.stringify( sound ) );
		assert.deepEqual( clinicianPage.problems, [] );

	} );

	test( 'the clinician deletes a kept sound after a second press, and only that sound goes', async () => {

		const [ record ] = ( await api( clinician, 'GET', `practice?child_id=${ ada.id }` ) ).body.records;
		const row = clinicianPage.locator( `tr[data-practice="${ record.id }"]` );
		const remove = row.getByRole( 'button', { name: /^Delete the sound of the go of / } );
		const box = await remove.boundingBox();
		assert.ok( box.height >= TOUCH_PX, `the delete button is ${ box.height } px high` );
		await remove.click();
		// The first press only asks; "Keep it" leaves the sound where it was.
		await row.getByRole( 'button', { name: /^Keep the sound of the go of / } ).click();
		assert.equal( ( await api( clinician, 'GET', `practice/${ record.id }/audio` ) ).status, 200 );
		await remove.click();
		await row.getByRole( 'button', { name: /^Yes, delete the sound of the go of / } ).click();
		await row.getByRole( 'status' ).filter( { hasText: 'Sound deleted.' } ).waitFor( { timeout: 30_000 } );
		assert.deepEqual( ( await child() ).sound.deleted, [ record.id ] );
		assert.equal( ( await api( clinician, 'GET', `practice/${ record.id }/audio` ) ).status, 404 );
		const records = ( await api( clinician, 'GET', `practice?child_id=${ ada.id }` ) ).body.records;
		assert.deepEqual( records.filter( ( r ) => r.id === record.id ).map( ( r ) => r.has_audio ), [ false ], 'the try stays, without its sound' );
		assert.deepEqual( clinicianPage.problems, [] );

	} );

	test( 'a sound the server does not take is said in plain words, and the try itself stays saved', async () => {

		const failing = `**/api/v1/practice/*/audio`;
		await childPage.route( failing, ( route ) => route.fulfill( { status: 500, contentType: 'application/json', body: JSON.stringify( { detail: 'disk full' } ) } ) );
		try {

			await childPage.getByRole( 'button', { name: 'Again' } ).click();
			const id = await sayAndRate();
			await childPage.waitForFunction( ( record ) => window.glasshead.practice.audio.failed.includes( record ), id, { timeout: 60_000 } );
			await childPage.getByRole( 'alert' ).filter( { hasText: 'This try’s sound could not be kept. Your try is saved.' } ).waitFor( { timeout: 10_000 } );
			const records = ( await api( clinician, 'GET', `practice?child_id=${ ada.id }` ) ).body.records;
			assert.deepEqual( records.filter( ( r ) => r.id === id ).map( ( r ) => r.has_audio ), [ false ], 'the record is there, without sound' );
			assert.equal( ( await practice() ).audio.enabled, true, 'a failure does not switch it off' );

		} finally {

			await childPage.unroute( failing );

		}

	} );

	test( 'switched off, the child\'s next attempt sends no sound: no request carries audio', async () => {

		await openChildHistory();
		await flipSwitch( false );
		assert.match( ( await child() ).recording.words, /^Off since .*, by E2E Clinician$/ );
		// The child starts the lesson again: the switch is read afresh.
		await childPage.getByRole( 'button', { name: 'Again' } ).click();
		await childPage.waitForFunction( () => window.glasshead.practice?.screen === 'practice' && window.glasshead.practice.audio.enabled === false, null, { timeout: 60_000 } );
		assert.equal( await childPage.getByText( KEEPING_LABEL ).isVisible(), false, 'no red dot' );
		const from = childRequests.length;
		const id = await sayAndRate();
		// Long enough for an upload to have gone, were there one.
		await childPage.waitForTimeout( 3000 );
		const sent = childRequests.slice( from );
		assert.ok( sent.some( ( r ) => r.method === 'POST' && new URL( r.url ).pathname === '/api/v1/practice' ), 'the practice record itself was sent' );
		const withAudio = sent.filter( ( r ) => r.riff || /^audio\//.test( r.type ) || /\/audio$/.test( new URL( r.url ).pathname ) || r.bytes > 16 * 1024 );
		assert.deepEqual( withAudio, [], 'no request carries audio' );
		assert.deepEqual( ( await practice() ).audio.kept.includes( id ), false );
		const records = ( await api( clinician, 'GET', `practice?child_id=${ ada.id }` ) ).body.records;
		assert.equal( records.find( ( r ) => r.id === id ).has_audio, false );
		assert.equal( ( await api( clinician, 'GET', `practice/${ id }/audio` ) ).status, 404 );
		await openChildHistory();
		assert.equal( await clinicianPage.locator( `tr[data-practice="${ id }"]` ).getByRole( 'button', { name: /^Play the go of / } ).count(), 0, 'no player without sound' );
		assert.deepEqual( childPage.problems, [] );

	} );

} );
