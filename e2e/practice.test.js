// End-to-end, in Debian's Chromium on touch screens: the child's practice (#/practice). A code
// that cannot be one is caught before asking, and an unknown one is said in plain words; the
// roster and the practice have buttons of 64 px and more in portrait (768 x 1024) and landscape
// (1024 x 768) with nothing wider than the screen; a child with two lessons (one for the class,
// one for them alone) chooses between them and never sees a third; a reload keeps them signed in;
// a whole lesson ends on the star with one record per item; "Not me" signs out and the token no
// longer works. e2e/screenshots/practice-roster-768x1024.png and practice-1024x768.png are for a
// person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { apiSession, authHeaders } from './accounts.js';
import { readDebug, saveScreenshot, serverAndBrowser } from './harness.js';

/** The smallest touch target of the child's view, CSS pixels. */
const TOUCH_PX = 64;
const PORTRAIT = Object.freeze( { width: 768, height: 1024 } );
const LANDSCAPE = Object.freeze( { width: 1024, height: 768 } );
const item = ( kind, text ) => ( { target: { kind, text }, presentation: kind === 'phoneme' ? 'static' : 'dynamic', views: { epg: true } } );

describe( 'the child\'s practice', { timeout: 900_000 }, () => {

	let server, browser, context, page, teacher, schoolClass, ada, forClass, forAda, other;

	const api = async ( session, method, path, body ) => {

		const response = await fetch( `${ server.baseUrl }/api/v1/${ path }`, {
			method, headers: authHeaders( session, body ? { 'Content-Type': 'application/json' } : {} ), body: body ? JSON.stringify( body ) : undefined,
		} );
		const text = await response.text();
		return { status: response.status, body: text ? JSON.parse( text ) : null };

	};
	const practice = async () => ( await readDebug( page ) ).practice;
	const screen = ( name, timeout = 30_000 ) => page.waitForFunction( ( wanted ) => window.glasshead.practice?.screen === wanted, name, { timeout } );
	const ready = () => page.waitForFunction( () => window.glasshead.practice?.ready === true || Boolean( window.glasshead.error ), null, { timeout: 300_000, polling: 200 } );

	/** The visible buttons of the view that are smaller than a finger, and whether anything is wider than the screen. */
	const layout = () => page.evaluate( ( touch ) => ( {
		small: [ ...document.querySelectorAll( '#app button' ) ].filter( ( b ) => b.offsetParent !== null ).map( ( b ) => {

			const box = b.getBoundingClientRect();
			return { name: b.getAttribute( 'aria-label' ) ?? b.textContent.trim(), width: box.width, height: box.height };

		} ).filter( ( b ) => b.width < touch || b.height < touch ),
		count: [ ...document.querySelectorAll( '#app button' ) ].filter( ( b ) => b.offsetParent !== null ).length,
		overflow: document.documentElement.scrollWidth - window.innerWidth,
	} ), TOUCH_PX );

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		teacher = await apiSession( server, 'teacher' );
		const author = await apiSession( server, 'author' );
		schoolClass = ( await api( teacher, 'POST', 'classes', { name: 'Class 3B' } ) ).body;
		ada = ( await api( teacher, 'POST', 'children', { class_id: schoolClass.id, display_name: 'Ada', avatar: 'owl' } ) ).body;
		await api( teacher, 'POST', 'children', { class_id: schoolClass.id, display_name: 'Bo', avatar: 'cat' } );
		const lesson = async ( title, items ) => ( await api( author, 'POST', 'lessons', { title, items } ) ).body;
		forClass = await lesson( 'Sounds at the front', [ item( 'phoneme', 't' ), item( 'word', 'tea' ) ] );
		forAda = await lesson( 'Ada\'s words', [ item( 'word', 'key' ) ] );
		other = await lesson( 'Not assigned', [ item( 'word', 'sea' ) ] );
		for ( const body of [ { lesson_id: forClass.id, class_id: schoolClass.id }, { lesson_id: forAda.id, child_id: ada.id } ] ) {

			assert.equal( ( await api( teacher, 'POST', 'assignments', body ) ).status, 201 );

		}

		context = await browser.newContext( { viewport: PORTRAIT, deviceScaleFactor: 1, hasTouch: true, isMobile: true } );
		page = await context.newPage();
		page.problems = [];
		page.on( 'pageerror', ( error ) => page.problems.push( `uncaught: ${ error.message }` ) );

	} );

	test( 'a code that cannot be one is caught before asking, and an unknown code is said in plain words', async () => {

		await page.goto( `${ server.baseUrl }/#/practice` );
		const code = page.getByRole( 'textbox', { name: 'Class code' } );
		await code.waitFor( { timeout: 60_000 } );
		assert.equal( await page.locator( '.nav-bar' ).isVisible(), false, 'a kiosk: no adult navigation' );
		await code.fill( 'ABC123' );
		await page.getByRole( 'button', { name: 'Go' } ).tap();
		const said = 'A class code never has B, 1 and 2. Ask a grown-up to read the code again.';
		const alert = page.getByRole( 'alert' ).filter( { hasText: said } );
		await alert.waitFor( { timeout: 60_000 } );
		assert.equal( await alert.locator( 'svg' ).count(), 1, 'the message has its picture' );
		await page.waitForFunction( ( text ) => window.glasshead.practice.spoken.includes( text ), said, { timeout: 10_000 } );
		// Six characters of the code alphabet, but no class has them.
		const unknown = schoolClass.join_code === 'CDEFGH' ? 'CDEFGJ' : 'CDEFGH';
		await code.fill( unknown );
		await page.getByRole( 'button', { name: 'Go' } ).tap();
		await page.getByRole( 'alert' ).filter( { hasText: 'There is no class with this code. Ask a grown-up to check it.' } ).waitFor( { timeout: 60_000 } );
		assert.equal( ( await practice() ).screen, 'code' );

	} );

	test( 'the roster shows each child\'s picture and name as a big button in portrait', async () => {

		await page.getByRole( 'textbox', { name: 'Class code' } ).fill( schoolClass.join_code );
		await page.getByRole( 'button', { name: 'Go' } ).tap();
		await screen( 'roster' );
		const roster = page.getByRole( 'group', { name: 'Who are you?' } );
		assert.deepEqual( await roster.getByRole( 'button' ).allTextContents(), [ 'Ada', 'Bo' ] );
		assert.equal( await roster.locator( 'svg' ).count(), 2, 'a picture in each button' );
		const { small, overflow } = await layout();
		assert.deepEqual( small, [] );
		assert.ok( overflow <= 0, `${ overflow } px wider than the screen` );
		await saveScreenshot( page, 'practice-roster-768x1024' );

	} );

	test( 'a child with two lessons chooses one, never sees a lesson not given to them, and stays signed in after a reload', async () => {

		await page.getByRole( 'button', { name: 'Ada', exact: true } ).tap();
		await screen( 'lessons' );
		await page.getByRole( 'group', { name: 'Lessons' } ).getByRole( 'button' ).first().waitFor();
		const titles = await page.getByRole( 'group', { name: 'Lessons' } ).getByRole( 'button' ).evaluateAll( ( buttons ) => buttons.map( ( b ) => b.getAttribute( 'aria-label' ) ) );
		assert.deepEqual( titles.sort(), [ forAda.title, forClass.title ].sort() );
		assert.ok( ! titles.includes( other.title ) );
		await page.reload();
		await screen( 'lessons' );
		assert.equal( ( await practice() ).child.id, ada.id );

	} );

	test( 'in landscape every button is 64 px and more, and a whole lesson ends on the star with a record per item', async () => {

		await page.setViewportSize( LANDSCAPE );
		await page.getByRole( 'button', { name: forClass.title } ).tap();
		await ready();
		let state = await practice();
		assert.deepEqual( [ state.lesson, state.item, state.items ], [ forClass.id, 0, 2 ] );
		const { small, count, overflow } = await layout();
		assert.ok( count >= 3, `${ count } buttons` );
		assert.deepEqual( small, [] );
		assert.ok( overflow <= 0, `${ overflow } px wider than the screen` );
		const stage = await page.locator( '.cp-stage' ).boundingBox();
		assert.ok( stage.height >= 0.4 * LANDSCAPE.height && stage.width >= 0.9 * LANDSCAPE.width, `the head is ${ stage.width } x ${ stage.height }` );
		// The palatogram card sits whole inside the head's rounded frame, its own border showing.
		const card = await page.locator( '.cp-stage .epg-overlay' ).boundingBox();
		assert.ok( card, 'the palatogram card is shown' );
		assert.ok( card.y >= stage.y && card.y + card.height <= stage.y + stage.height - 8, `card ${ card.y }..${ card.y + card.height }, frame ${ stage.y }..${ stage.y + stage.height }` );
		await saveScreenshot( page, 'practice-1024x768' );
		// The first without a face (the arrow), the second with one.
		await page.getByRole( 'button', { name: 'I tried it' } ).tap();
		await page.getByRole( 'button', { name: 'Next' } ).tap();
		await page.waitForFunction( () => window.glasshead.practice.item === 1 && window.glasshead.practice.ready === true, null, { timeout: 120_000 } );
		await page.getByRole( 'button', { name: 'Hear it again' } ).tap();
		await page.getByRole( 'button', { name: 'Hear it again' } ).tap();
		await page.getByRole( 'button', { name: 'I tried it' } ).tap();
		await page.getByRole( 'button', { name: 'Nearly' } ).tap();
		await screen( 'done' );
		assert.ok( await page.getByRole( 'img', { name: 'Well done' } ).isVisible() );
		state = await practice();
		const records = ( await api( teacher, 'GET', `practice?child_id=${ ada.id }&lesson_id=${ forClass.id }` ) ).body.records;
		assert.deepEqual( records.map( ( r ) => [ r.id, r.item_index, r.replays, r.rating, r.rated_by ] ).sort( ( a, b ) => a[ 1 ] - b[ 1 ] ),
			[ [ state.recorded[ 0 ], 0, 0, null, null ], [ state.recorded[ 1 ], 1, 2, 2, 'child' ] ] );

	} );

	test( '"Not me" signs the child out: back to the code, and the token no longer works', async () => {

		const icon = ( name ) => page.getByRole( 'button', { name } ).locator( 'svg' ).innerHTML();
		assert.notEqual( await icon( 'Not me: sign out' ), await icon( 'For grown-ups: hold for 2 seconds to leave' ) );
		const token = await page.evaluate( () => JSON.parse( localStorage.getItem( 'glasshead.session' ) ).token );
		await page.getByRole( 'button', { name: 'Not me: sign out' } ).tap();
		await screen( 'code' );
		assert.equal( await page.evaluate( () => localStorage.getItem( 'glasshead.session' ) ), null );
		assert.equal( ( await api( { token }, 'GET', 'auth/child-sessions/current' ) ).status, 401 );
		assert.deepEqual( page.problems, [] );

	} );

	test( 'the kiosk is left only by a grown-up holding the lock: a tap says so aloud, two seconds leave', async () => {

		const lock = page.getByRole( 'button', { name: 'For grown-ups: hold for 2 seconds to leave' } );
		await lock.tap();
		const said = 'This is for grown-ups: they hold it to leave.';
		await page.getByRole( 'alert' ).filter( { hasText: said } ).waitFor( { timeout: 10_000 } );
		await page.waitForFunction( ( text ) => window.glasshead.practice.spoken.includes( text ), said, { timeout: 10_000 } );
		assert.equal( await page.evaluate( () => location.hash ), '#/practice' );
		const box = await lock.boundingBox();
		await page.mouse.move( box.x + box.width / 2, box.y + box.height / 2 );
		await page.mouse.down();
		await page.waitForTimeout( 2300 );
		await page.mouse.up();
		await page.waitForFunction( () => location.hash === '#/', null, { timeout: 10_000 } );
		await page.locator( '.nav-bar' ).waitFor( { state: 'visible', timeout: 30_000 } );
		assert.equal( await page.evaluate( () => document.body.classList.contains( 'cp-kiosk' ) ), false );

	} );

} );
