// End-to-end, in Debian's Chromium at a projector's 1366 x 768: the teacher's lesson runner
// (#/teach) on the starter lessons. Each item sets up the head as the lesson says (the /s/ lesson:
// skin see-through, labels and the EPG card, its sounds held; the nasals: the cutaway and the 2D
// diagram), the arrow keys move between items and the address follows, Space plays, S slows to a
// quarter, F shows the head alone (no panel, toolbar or navigation bar) with the target in big
// letters, and Esc comes back; an author runs lessons without classes. Read from
// window.glasshead; e2e/screenshots/runner-1366x768.png and runner-present-1366x768.png are for
// a person to look at.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { account, apiSession, authHeaders, signIn } from './accounts.js';
import { animationFrames, openPage, readDebug, saveScreenshot, serverAndBrowser, settle } from './harness.js';

const SIZE = Object.freeze( { width: 1366, height: 768 } );

describe( 'the lesson runner', { timeout: 600_000 }, () => {

	let server, browser, page, lessons;

	const runner = async () => ( await readDebug( page ) ).runner;
	const visible = ( selector ) => page.locator( selector ).first().isVisible();
	/** Wait until item `item` of lesson `lesson` is set up on the head. */
	const ready = ( lesson, item ) => page.waitForFunction( ( [ l, i ] ) => {

		const r = window.glasshead.runner;
		return ( r?.lesson === l && r.item === i && r.ready === true ) || Boolean( window.glasshead.error );

	}, [ lesson, item ], { timeout: 180_000, polling: 200 } );

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		const teacher = await apiSession( server, 'teacher' );
		lessons = ( await ( await fetch( `${ server.baseUrl }/api/v1/lessons`, { headers: authHeaders( teacher ) } ) ).json() ).lessons;
		page = await openPage( browser, SIZE );
		await signIn( page, server, 'teacher' );

	} );

	test( 'a teacher goes from an empty browser to the first target presented in six actions', async () => {

		const teacher = await account( server, 'teacher' );
		const fresh = await openPage( browser, SIZE );
		const actions = [];
		const act = async ( name, action ) => {

			actions.push( name );
			await action();

		};
		await act( 'open the school\'s address', () => fresh.goto( `${ server.baseUrl }/` ) );
		await act( 'Sign in', () => fresh.getByRole( 'navigation', { name: 'Views' } ).getByRole( 'link', { name: 'Sign in' } ).click() );
		await act( 'type the username', () => fresh.getByLabel( 'Username' ).fill( teacher.username ) );
		await act( 'type the password', () => fresh.getByLabel( 'Password' ).fill( teacher.password ) );
		await act( 'press Enter', () => fresh.getByLabel( 'Password' ).press( 'Enter' ) );
		await fresh.getByRole( 'list', { name: 'Lessons' } ).getByRole( 'link' ).first().waitFor( { timeout: 60_000 } );
		assert.equal( await fresh.evaluate( () => location.hash ), '#/teach', 'a teacher lands on Teach' );
		await act( 'Present the first lesson', () => fresh.getByRole( 'link', { name: `Present ${ lessons[ 0 ].title }` } ).click() );
		await fresh.waitForFunction( ( id ) => {

			const r = window.glasshead.runner;
			return ( r?.lesson === id && r.item === 0 && r.ready === true && r.presenting === true ) || Boolean( window.glasshead.error );

		}, lessons[ 0 ].id, { timeout: 180_000, polling: 200 } );
		assert.ok( actions.length <= 6, `${ actions.length } actions: ${ actions.join( ', ' ) }` );
		assert.equal( await fresh.evaluate( () => location.hash ), `#/teach?lesson=${ lessons[ 0 ].id }&item=0`, 'the address drops the request to present' );
		await fresh.keyboard.press( ' ' );
		await fresh.waitForFunction( () => window.glasshead.speech.playing === true || window.glasshead.speech.time > 0, null, { timeout: 60_000 } );
		assert.deepEqual( fresh.problems, [] );
		await fresh.context().close();

	} );

	test( 'the list links every lesson the teacher may read to its first item', async () => {

		await page.goto( `${ server.baseUrl }/#/teach` );
		const list = page.getByRole( 'list', { name: 'Lessons' } );
		await list.getByRole( 'link' ).first().waitFor( { timeout: 60_000 } );
		const hrefs = await list.getByRole( 'link' ).evaluateAll( ( links ) => links.map( ( link ) => link.getAttribute( 'href' ) ) );
		assert.ok( lessons.length >= 5, `${ lessons.length } starter lessons` );
		assert.deepEqual( hrefs, lessons.flatMap( ( lesson ) => [ `#/teach?lesson=${ lesson.id }&item=0`, `#/teach?lesson=${ lesson.id }&item=0&present=1` ] ) );
		const teach = page.getByRole( 'navigation', { name: 'Views' } ).getByRole( 'link', { name: 'Teach', exact: true } );
		assert.equal( await teach.getAttribute( 'aria-current' ), 'page', 'the bar links the runner for a teacher, marked' );

	} );

	test( 'an item of the /s/ lesson shows the skin see-through, the labels and the EPG card, and holds its sound', async () => {

		const lesson = lessons.find( ( l ) => l.title === '/s/ and /ʃ/' );
		await page.getByRole( 'link', { name: /^\/s\/ and \/ʃ\// } ).click();
		await ready( lesson.id, 0 );
		const state = await readDebug( page );
		assert.equal( state.error ?? null, null );
		assert.deepEqual( [ state.runner.target, state.runner.settings.transparency, state.runner.settings.hold ], [ '/s/', 80, true ] );
		assert.equal( state.speech.hold, 'S', 'the target of /s/ is held' );
		const s = state.speech.phones.find( ( phone ) => phone.symbol === 'S' );
		assert.ok( s.end_s - s.start_s >= 0.6 && s.end_s - s.start_s <= 0.8, `/s/ is said for ${ s.end_s - s.start_s } s, long enough to copy` );
		assert.deepEqual( [ state.runner.settings.cutaway, state.runner.settings.camera, state.runner.settings.zoom ], [ true, 'profile', 1.5 ] );
		assert.deepEqual( state.labels.names, [ 'tongue_tip', 'alveolar', 'postalveolar' ], 'the place and the articulator, not every label' );
		assert.deepEqual( state.labels.hidden, [], 'nothing the item names is behind bone' );
		await page.getByRole( 'img', { name: 'a snake: sss' } ).waitFor( { timeout: 30_000 } );
		assert.match( await page.locator( '.lr-how' ).textContent(), /^How \/s\/ is made: .*hiss/ );
		assert.ok( await visible( '.epg-overlay' ), 'the EPG card is shown' );
		assert.ok( state.epg.contacted > 0, `the held /s/ touches the palate: ${ state.epg.rows.join( ' ' ) }` );
		assert.equal( await page.locator( '.lr-dot[aria-current="step"]' ).getAttribute( 'aria-label' ), 'Item 1: /s/' );
		await saveScreenshot( page, 'runner-1366x768' );

	} );

	test( 'the arrow keys move between items and the address follows; the first and last items stay put', async () => {

		const { lesson, items } = await runner();
		await page.locator( 'body' ).press( 'ArrowRight' );
		await ready( lesson, 1 );
		assert.equal( ( await runner() ).target, '/ʃ/' );
		assert.equal( await page.evaluate( () => location.hash ), `#/teach?lesson=${ lesson }&item=1` );
		await page.keyboard.press( 'ArrowLeft' );
		await ready( lesson, 0 );
		await page.keyboard.press( 'ArrowLeft' );
		await page.waitForTimeout( 300 );
		assert.equal( ( await runner() ).item, 0 );
		await page.goto( `${ server.baseUrl }/#/teach?lesson=${ lesson }&item=${ items - 1 }` );
		await ready( lesson, items - 1 );
		await page.keyboard.press( 'ArrowRight' );
		await page.waitForTimeout( 300 );
		assert.equal( ( await runner() ).item, items - 1 );

	} );

	test( 'a word is spoken at the lesson\'s half speed; S slows it to a quarter and back, and Space plays and pauses', async () => {

		const { lesson } = await runner();
		await page.goto( `${ server.baseUrl }/#/teach?lesson=${ lesson }&item=2` );
		await ready( lesson, 2 );
		let state = await readDebug( page );
		assert.deepEqual( [ state.runner.target, state.runner.settings.hold, state.speech.speed, state.speech.hold ], [ 'sip', false, 0.5, null ] );
		await page.keyboard.press( 's' );
		state = await readDebug( page );
		assert.deepEqual( [ state.runner.slow, state.speech.speed ], [ true, 0.25 ] );
		assert.equal( await page.getByRole( 'button', { name: 'Slow (S)' } ).getAttribute( 'aria-pressed' ), 'true' );
		// Looped (a click that leaves the focus where it is), so that the word is still playing
		// when the second Space comes, however slowly the page goes.
		const loop = page.getByRole( 'button', { name: 'Loop', exact: true } );
		await loop.dispatchEvent( 'click' );
		assert.equal( ( await readDebug( page ) ).speech.loop, true );
		await page.keyboard.press( ' ' );
		await page.waitForFunction( () => window.glasshead.speech.playing === true && window.glasshead.speech.time > 0, null, { timeout: 60_000 } );
		await page.keyboard.press( ' ' );
		await page.waitForFunction( () => window.glasshead.speech.playing === false, null, { timeout: 60_000 } );
		await loop.dispatchEvent( 'click' );
		assert.equal( ( await readDebug( page ) ).speech.loop, false );
		await page.keyboard.press( 'S' );
		assert.equal( ( await readDebug( page ) ).speech.speed, 0.5 );

	} );

	test( 'Present takes the focus, so the first Space plays; its bar says Esc leaves and hides while the pointer rests', async () => {

		await page.getByRole( 'button', { name: 'Present', exact: true } ).click();
		await page.waitForFunction( () => window.glasshead.runner.presenting === true, null, { timeout: 60_000 } );
		assert.equal( await page.evaluate( () => document.activeElement?.classList.contains( 'lesson-runner' ) ), true, 'the runner has the focus' );
		const bar = page.getByRole( 'toolbar', { name: 'Presenting' } );
		assert.ok( await bar.isVisible() );
		assert.match( await bar.textContent(), /Esc leaves/ );
		await page.keyboard.press( ' ' );
		await page.waitForFunction( () => window.glasshead.speech.playing === true || window.glasshead.speech.time > 0, null, { timeout: 60_000 } );
		await page.waitForFunction( () => document.querySelector( '.lr-present-bar' ).classList.contains( 'lr-resting' ), null, { timeout: 10_000 } );
		assert.equal( await bar.evaluate( ( element ) => getComputedStyle( element ).pointerEvents ), 'none', 'the resting bar takes no taps' );
		await page.mouse.move( 300, 300 );
		await page.mouse.move( 320, 310 );
		await page.waitForFunction( () => ! document.querySelector( '.lr-present-bar' ).classList.contains( 'lr-resting' ), null, { timeout: 10_000 } );
		await page.keyboard.press( 'Escape' );
		await page.waitForFunction( () => window.glasshead.runner.presenting === false, null, { timeout: 60_000 } );
		assert.equal( await bar.isVisible(), false );

	} );

	test( 'F shows the head alone with the target in big letters and the item dots; Esc comes back', async () => {

		await page.keyboard.press( 'f' );
		await page.waitForFunction( () => window.glasshead.runner.presenting === true, null, { timeout: 60_000 } );
		await animationFrames( page ); // the new size has reached the 3D view, which draws it next
		await settle( page );
		for ( const selector of [ '.nav-bar', '.lr-panel', '.lr-toolbar', '.sp-bottom' ] ) assert.equal( await visible( selector ), false, `${ selector } is hidden` );
		const viewport = page.viewportSize();
		const stage = await page.locator( '.sp-stage' ).boundingBox();
		assert.ok( stage.width >= viewport.width - 1 && stage.height >= 0.9 * viewport.height, `the head is ${ stage.width } x ${ stage.height } of ${ viewport.width } x ${ viewport.height }` );
		const fontPx = await page.locator( '.lr-target-text' ).evaluate( ( element ) => parseFloat( getComputedStyle( element ).fontSize ) );
		assert.ok( fontPx >= 72, `the target is ${ fontPx } px` );
		assert.ok( await visible( '.lr-dots' ), 'the item dots stay' );
		await saveScreenshot( page, 'runner-present-1366x768' );
		// Esc leaves full screen (when the browser gave it) and so presentation mode.
		await page.keyboard.press( 'Escape' );
		await page.waitForTimeout( 300 );
		if ( ( await runner() ).presenting ) await page.keyboard.press( 'Escape' );
		await page.waitForFunction( () => window.glasshead.runner.presenting === false, null, { timeout: 60_000 } );
		assert.ok( await visible( '.lr-panel' ) && await visible( '.nav-bar' ) );

	} );

	test( 'every starter lesson opens on a view where bone hides none of the labels it names; a view without the cutaway would', async () => {

		const titles = [ '/s/ and /ʃ/', '/t/ and /k/', '/r/ and /l/', 'Nasals and their oral pairs', 'The vowels' ];
		const starters = titles.map( ( title ) => lessons.find( ( l ) => l.title === title ) );
		for ( const [ k, lesson ] of starters.entries() ) {

			await page.goto( `${ server.baseUrl }/#/teach?lesson=${ lesson.id }&item=0` );
			await ready( lesson.id, 0 );
			await settle( page );
			const { labels, runner: state } = await readDebug( page );
			assert.ok( labels.count >= 2 && labels.count <= 4, `${ lesson.title }: ${ labels.names }` );
			assert.deepEqual( labels.hidden, [], `${ lesson.title }: bone hides ${ labels.hidden }` );
			assert.deepEqual( [ state.settings.cutaway, state.settings.camera ], [ true, 'profile' ] );
			await saveScreenshot( page, `runner-starter-${ k + 1 }-1366x768` );

		}

		// The same labels seen from the front without the cutaway: the jaw and teeth hide the tongue.
		const author = await apiSession( server, 'author' );
		const hiding = { title: 'Seen from the front (e2e)', items: [ { target: { kind: 'phoneme', text: 't' }, presentation: 'static', views: { skin_transparency: 0.8, camera: 'front', labels: [ 'tongue_tip', 'tongue_back' ] } } ] };
		const made = await fetch( `${ server.baseUrl }/api/v1/lessons`, { method: 'POST', headers: authHeaders( author, { 'content-type': 'application/json' } ), body: JSON.stringify( hiding ) } );
		assert.equal( made.status, 201 );
		const { id } = await made.json();
		await page.goto( `${ server.baseUrl }/#/teach?lesson=${ id }&item=0` );
		await ready( id, 0 );
		await settle( page );
		assert.deepEqual( ( await readDebug( page ) ).labels.hidden, [ 'tongue_tip', 'tongue_back' ] );

	} );

	test( 'an item of the nasals lesson shows the cutaway and the 2D diagram, and no EPG card', async () => {

		const lesson = lessons.find( ( l ) => l.title === 'Nasals and their oral pairs' );
		await page.goto( `${ server.baseUrl }/#/teach?lesson=${ lesson.id }&item=0` );
		await ready( lesson.id, 0 );
		const { runner: state } = await readDebug( page );
		assert.deepEqual( [ state.target, state.settings.cutaway, state.settings.diagram, state.settings.epg ], [ '/m/', true, true, false ] );
		assert.ok( await visible( '.sp-diagram-section' ), 'the diagram is shown' );
		assert.equal( await visible( '.epg-overlay' ), false, 'the EPG card is hidden' );

	} );

	test( 'an author runs a lesson too, and the panel says that classes are kept by others instead of failing', async () => {

		await signIn( page, server, 'author' );
		const lesson = lessons[ 0 ];
		await page.goto( `${ server.baseUrl }/#/teach?lesson=${ lesson.id }&item=0` );
		await ready( lesson.id, 0 );
		assert.ok( await page.getByText( 'Teachers, clinicians and admins give lessons to their classes here.' ).isVisible() );
		for ( const name of [ 'Class', 'Assign to this class', 'Refresh' ] ) assert.equal( await page.getByRole( /^Class$/.test( name ) ? 'combobox' : 'button', { name, exact: true } ).isVisible(), false, name );
		assert.equal( await visible( '.lr-panel [role="alert"]' ), false, 'no error' );
		// The browser logs the refused GET /classes itself; nothing else went wrong.
		assert.deepEqual( page.problems.filter( ( problem ) => ! /status of 403.*\/api\/v1\/classes/.test( problem ) ), [] );

	} );

} );
