// End-to-end, in Debian's Chromium, the walk-through of README's "A first lesson in a minute":
// an author writes a lesson (POST /lessons); a teacher, in the lesson runner (#/teach), makes a
// class, adds two children and gives the lesson to the class; a child on a 768 x 1024 touch screen
// types the class code, taps their own picture, hears the first target again and taps "I tried
// it" and a face (#/practice); the teacher sees that try in the runner's practice list and shares
// the class with a clinician there (POST /classes/{id}/staff); the clinician sees the same child's
// practice in the child's history, imports a real EPG recording (the emuR engassim set) for her
// and compares it with a phoneme's target in the clinician view. Each person signs in as they
// would (e2e/accounts.js); what each view shows is read from window.glasshead. Screenshots
// walkthrough-runner-1366x768.png and walkthrough-practice-768x1024.png are for a person.

import assert from 'node:assert/strict';
import { join, resolve } from 'node:path';
import { describe, test } from 'node:test';
import { apiSession, authHeaders, signIn } from './accounts.js';
import { openPage, readDebug, REPO, saveScreenshot, serverAndBrowser } from './harness.js';

const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( REPO, '..', 'shared', 'data' );
const EMUR = join( DATA_DIR, 'epg', 'emur-engassim.json' );
/** The smallest touch target of the child's view, CSS pixels. */
const CHILD_TOUCH_PX = 64;
const LESSON = Object.freeze( {
	title: 'First lesson: /t/ and /k/', language: 'en-US', description: 'The tip at the ridge, then the back of the tongue.',
	items: [
		{ target: { kind: 'phoneme', text: 't' }, presentation: 'static', views: { skin_transparency: 0.8, epg: true } },
		{ target: { kind: 'word', text: 'key' }, presentation: 'dynamic', speed: 0.5, views: { skin_transparency: 0.8, epg: true } },
	],
} );

describe( 'a first lesson, from the author to the child and back to the teacher', { timeout: 900_000 }, () => {

	let server, browser, sessions, lesson, schoolClass, children, teacherPage, childPage, join;

	/** A request of the test itself, as the signed-in `session`. */
	const api = async ( session, method, path, body ) => {

		const response = await fetch( `${ server.baseUrl }/api/v1/${ path }`, {
			method, headers: authHeaders( session, body ? { 'Content-Type': 'application/json' } : {} ), body: body ? JSON.stringify( body ) : undefined,
		} );
		const text = await response.text();
		return { status: response.status, body: text ? JSON.parse( text ) : null };

	};

	serverAndBrowser( async ( running ) => {

		( { server, browser } = running );
		sessions = {};
		for ( const role of [ 'author', 'teacher', 'clinician' ] ) sessions[ role ] = await apiSession( server, role );

	}, { ownServer: true } ); // a new school: the teacher starts with no class

	test( 'an author writes a lesson, which a teacher can read but not change', async () => {

		const made = await api( sessions.author, 'POST', 'lessons', LESSON );
		assert.equal( made.status, 201, JSON.stringify( made.body ) );
		lesson = made.body;
		assert.deepEqual( lesson.items.map( ( item ) => item.target.text ), [ 't', 'key' ] );
		assert.equal( ( await api( sessions.teacher, 'GET', `lessons/${ lesson.id }` ) ).status, 200 );
		assert.equal( ( await api( sessions.teacher, 'PATCH', `lessons/${ lesson.id }`, { title: 'mine now' } ) ).status, 403 );

	} );

	test( 'a teacher makes a class with two children and gives it the lesson, all in the runner', async () => {

		teacherPage = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( teacherPage, server, 'teacher' );
		await teacherPage.goto( `${ server.baseUrl }/#/teach` );
		await teacherPage.getByRole( 'link', { name: new RegExp( `^${ LESSON.title.replace( /[/()]/g, '\\$&' ) }` ) } ).click();
		await teacherPage.waitForFunction( () => window.glasshead.runner?.ready === true || Boolean( window.glasshead.error ), null, { timeout: 180_000, polling: 200 } );
		let runner = ( await readDebug( teacherPage ) ).runner;
		assert.deepEqual( [ runner.lesson, runner.item, runner.target, runner.panel.classes ], [ lesson.id, 0, '/t/', [] ] );
		// No class yet: the forms are open.
		await teacherPage.getByRole( 'textbox', { name: 'Class name' } ).fill( 'Class 3B' );
		await teacherPage.getByRole( 'button', { name: 'Make class' } ).click();
		await teacherPage.waitForFunction( () => window.glasshead.runner.panel?.classes.includes( 'Class 3B' ), null, { timeout: 30_000 } );
		for ( const [ name, avatar ] of [ [ 'Ada', 'owl' ], [ 'Bo', 'cat' ] ] ) {

			await teacherPage.getByRole( 'textbox', { name: 'Child\'s name' } ).fill( name );
			await teacherPage.getByRole( 'combobox', { name: 'Avatar' } ).selectOption( avatar );
			await teacherPage.getByRole( 'button', { name: 'Add child' } ).click();
			await teacherPage.getByText( `Added ${ name }.` ).waitFor( { timeout: 30_000 } );

		}

		await teacherPage.getByText( 'In the class: Ada, Bo.' ).waitFor( { timeout: 30_000 } );
		schoolClass = ( await api( sessions.teacher, 'GET', 'classes' ) ).body.classes[ 0 ];
		children = ( await api( sessions.teacher, 'GET', `children?class_id=${ schoolClass.id }` ) ).body.children;
		assert.deepEqual( children.map( ( c ) => [ c.display_name, c.avatar ] ), [ [ 'Ada', 'owl' ], [ 'Bo', 'cat' ] ] );
		await teacherPage.getByRole( 'button', { name: 'Assign to this class' } ).click();
		await teacherPage.waitForFunction( () => window.glasshead.runner.panel?.assigned === true, null, { timeout: 30_000 } );
		runner = ( await readDebug( teacherPage ) ).runner;
		assert.equal( runner.panel.classId, schoolClass.id );
		const assignments = ( await api( sessions.teacher, 'GET', `assignments?lesson_id=${ lesson.id }` ) ).body;
		assert.deepEqual( assignments.assignments.map( ( a ) => [ a.lesson_id, a.class_id ] ), [ [ lesson.id, schoolClass.id ] ] );
		// The way in, large: the code in two groups, a QR code of the join link, and the link.
		await teacherPage.waitForFunction( () => Boolean( window.glasshead.runner.panel?.join?.code ), null, { timeout: 30_000 } );
		join = ( await readDebug( teacherPage ) ).runner.panel.join;
		assert.deepEqual( [ join.code, join.link ], [ schoolClass.join_code, `${ server.baseUrl }/#/practice?code=${ schoolClass.join_code }` ] );
		assert.equal( await teacherPage.locator( '.lr-join-code' ).textContent(), `${ schoolClass.join_code.slice( 0, 3 ) } ${ schoolClass.join_code.slice( 3 ) }` );
		const fontPx = await teacherPage.locator( '.lr-join-code' ).evaluate( ( element ) => parseFloat( getComputedStyle( element ).fontSize ) );
		assert.ok( fontPx >= 32, `the code is ${ fontPx } px` );
		assert.equal( await teacherPage.getByRole( 'img', { name: `QR code of ${ join.link }` } ).count(), 1 );
		assert.equal( join.reachable, false, '127.0.0.1 is the test machine\'s own address' );
		assert.ok( await teacherPage.getByText( 'tablets cannot reach it' ).isVisible() );
		await teacherPage.getByRole( 'button', { name: 'Show to the class' } ).click();
		const shown = teacherPage.getByRole( 'dialog', { name: `How to join ${ schoolClass.name }` } );
		await shown.waitFor( { timeout: 10_000 } );
		await saveScreenshot( teacherPage, 'walkthrough-join-1366x768' );
		await teacherPage.keyboard.press( 'Escape' );
		await shown.waitFor( { state: 'detached', timeout: 10_000 } );
		// Back to the list while the child practises: one head drawing at a time on the test machine.
		await teacherPage.getByRole( 'link', { name: 'All lessons' } ).click();
		await teacherPage.waitForFunction( () => window.glasshead.runner?.screen === 'list', null, { timeout: 30_000 } );

	} );

	test( 'a child on a 768 x 1024 touch screen signs in with the class code and their picture, and practises the first target', async () => {

		const context = await browser.newContext( { viewport: { width: 768, height: 1024 }, deviceScaleFactor: 1, hasTouch: true, isMobile: true } );
		childPage = await context.newPage();
		childPage.problems = [];
		childPage.on( 'pageerror', ( error ) => childPage.problems.push( `uncaught: ${ error.message }` ) );
		// The tablet scanned the QR code: the join link opens on the class's pictures.
		await childPage.goto( join.link );
		await childPage.waitForFunction( () => window.glasshead.practice?.screen === 'roster', null, { timeout: 30_000 } );
		assert.deepEqual( ( await readDebug( childPage ) ).practice.roster, [ 'Ada', 'Bo' ] );
		assert.ok( await childPage.getByRole( 'group', { name: 'Who are you?' } ).getByRole( 'img' ).count() === 0, 'the pictures are inside named buttons' );
		await childPage.getByRole( 'button', { name: 'Ada', exact: true } ).tap();
		// One lesson is assigned: it starts at once, and the head says its first target.
		await childPage.waitForFunction( () => window.glasshead.practice?.ready === true || Boolean( window.glasshead.error ), null, { timeout: 300_000, polling: 200 } );
		let practice = ( await readDebug( childPage ) ).practice;
		assert.equal( practice.child.id, children[ 0 ].id );
		// The sound as a picture, not as IPA a child of 8 cannot read.
		await childPage.locator( '.cp-target' ).getByRole( 'img', { name: 'a clock ticking: t t t' } ).waitFor( { timeout: 30_000 } );
		assert.equal( await childPage.locator( '.cp-target' ).textContent(), '' );
		assert.deepEqual( [ practice.lessons, practice.lesson, practice.item, practice.items ], [ [ lesson.id ], lesson.id, 0, 2 ] );
		const sizes = await childPage.locator( '#app button' ).evaluateAll( ( buttons ) => buttons.filter( ( b ) => b.offsetParent !== null ).map( ( b ) => {

			const box = b.getBoundingClientRect();
			return { name: b.getAttribute( 'aria-label' ) ?? b.textContent.trim(), width: box.width, height: box.height };

		} ) );
		assert.ok( sizes.length >= 3, JSON.stringify( sizes ) );
		for ( const size of sizes ) assert.ok( size.width >= CHILD_TOUCH_PX && size.height >= CHILD_TOUCH_PX, `${ size.name }: ${ size.width } x ${ size.height } px` );
		await childPage.getByRole( 'button', { name: 'Hear it again' } ).tap();
		await childPage.waitForFunction( () => window.glasshead.speech?.playing === true || window.glasshead.speech?.time > 0, null, { timeout: 30_000 } );
		await saveScreenshot( childPage, 'walkthrough-practice-768x1024' );
		await childPage.getByRole( 'button', { name: 'I tried it' } ).tap();
		await childPage.getByRole( 'button', { name: 'Got it' } ).tap();
		await childPage.waitForFunction( () => window.glasshead.practice.recorded.length === 1, null, { timeout: 30_000 } );
		practice = ( await readDebug( childPage ) ).practice;
		assert.equal( practice.item, 1, 'on to the second target' );
		// The child may read only their own practice; the record is as the server keeps it.
		const child = { token: ( await childPage.evaluate( () => JSON.parse( localStorage.getItem( 'glasshead.session' ) ) ) ).token };
		const records = ( await api( child, 'GET', `practice?child_id=${ children[ 0 ].id }` ) ).body.records;
		assert.deepEqual( records.map( ( r ) => [ r.id, r.lesson_id, r.item_index, r.replays, r.rating, r.rated_by ] ), [ [ practice.recorded[ 0 ], lesson.id, 0, 1, 3, 'child' ] ] );
		const other = await api( child, 'GET', `practice?child_id=${ children[ 1 ].id }` );
		assert.ok( other.status === 404 || other.body.records.length === 0, `another child's practice is not there for them: ${ JSON.stringify( other ) }` );
		assert.deepEqual( childPage.problems, [] );
		await childPage.context().close(); // its head no longer draws on the shared processor

	} );

	test( 'the teacher sees the child\'s try in the runner\'s practice list and shares the class with a clinician', async () => {

		await teacherPage.getByRole( 'link', { name: new RegExp( `^${ LESSON.title.replace( /[/()]/g, '\\$&' ) }` ) } ).click();
		await teacherPage.waitForFunction( () => window.glasshead.runner.panel?.records.length === 1, null, { timeout: 60_000 } );
		await teacherPage.getByRole( 'button', { name: 'Refresh' } ).click();
		await teacherPage.waitForFunction( () => window.glasshead.runner.panel.records.length === 1, null, { timeout: 30_000 } );
		const { records } = ( await readDebug( teacherPage ) ).runner.panel;
		assert.deepEqual( records.map( ( r ) => [ r.child, r.item, r.rating, r.replays ] ), [ [ 'Ada', 0, 3, 1 ] ] );
		const row = teacherPage.getByRole( 'list', { name: 'Practice records' } ).getByRole( 'listitem' );
		assert.match( await row.textContent(), /Ada\s*\/t\// );
		assert.ok( await row.getByRole( 'img', { name: 'Got it (child)' } ).isVisible() );
		// Sharing: an unknown username is refused in plain words, the clinician's is taken.
		const clinician = sessions.clinician.user;
		await teacherPage.getByText( 'Sharing', { exact: true } ).click();
		const share = teacherPage.getByRole( 'textbox', { name: 'Share this class with a clinician or teacher' } );
		await share.fill( 'nobody@glasshead.test' );
		await teacherPage.getByRole( 'button', { name: 'Share', exact: true } ).click();
		await teacherPage.getByText( 'Not shared: no such user among teachers and clinicians.' ).waitFor( { timeout: 30_000 } );
		await share.fill( clinician.username.toUpperCase() );
		await teacherPage.getByRole( 'button', { name: 'Share', exact: true } ).click();
		await teacherPage.waitForFunction( ( name ) => window.glasshead.runner.panel.sharing.staff.includes( name ), clinician.username, { timeout: 30_000 } );
		const sharing = ( await readDebug( teacherPage ) ).runner.panel.sharing;
		assert.deepEqual( sharing, { owner: sessions.teacher.user.username, staff: [ clinician.username ], canShare: true } );
		assert.ok( await teacherPage.getByRole( 'list', { name: 'Shared with' } ).getByRole( 'button', { name: `Stop sharing with ${ clinician.display_name }` } ).isVisible() );
		const staff = ( await api( sessions.teacher, 'GET', `classes/${ schoolClass.id }/staff` ) ).body;
		assert.deepEqual( staff.staff.map( ( m ) => [ m.user_id, m.role ] ), [ [ clinician.id, 'clinician' ] ] );
		await teacherPage.waitForFunction( () => window.glasshead.runner.ready === true, null, { timeout: 180_000, polling: 200 } );
		await saveScreenshot( teacherPage, 'walkthrough-runner-1366x768' );
		// The one refusal is the unknown username's, which the panel said in its own words.
		const refused = new RegExp( `status of 422 .*/api/v1/classes/${ schoolClass.id }/staff\\b` );
		assert.deepEqual( teacherPage.problems.filter( ( problem ) => ! refused.test( problem ) ), [] );
		await teacherPage.context().close();

	} );

	test( 'the clinician sees the same child\'s practice, imports a recording for her and compares it with a target', async () => {

		const child = children[ 0 ];
		const shared = ( await api( sessions.clinician, 'GET', 'classes' ) ).body;
		assert.deepEqual( shared.classes.map( ( c ) => c.id ), [ schoolClass.id ], 'the teacher\'s class, shared with the clinician, and no caseload of their own' );
		// Staff do not change who the class is shared with, nor delete it.
		assert.equal( ( await api( sessions.clinician, 'DELETE', `classes/${ schoolClass.id }/staff/${ sessions.clinician.user.id }` ) ).status, 403 );
		assert.equal( ( await api( sessions.clinician, 'DELETE', `classes/${ schoolClass.id }` ) ).status, 403 );
		const page = await openPage( browser, { width: 1366, height: 768 } );
		await signIn( page, server, 'clinician' );
		await page.goto( `${ server.baseUrl }/#/clinician?target=phoneme:T` );
		await page.waitForFunction( () => window.glasshead.clinician?.loaded === true && window.glasshead.clinicianChild?.loaded === true, null, { timeout: 240_000, polling: 200 } );
		assert.deepEqual( ( await readDebug( page ) ).clinicianChild.options, children.map( ( c ) => String( c.id ) ) );
		await page.getByRole( 'combobox', { name: 'Child', exact: true } ).selectOption( String( child.id ) );
		await page.waitForFunction( ( id ) => window.glasshead.clinicianChild.child === id && window.glasshead.clinicianChild.practice === 1, child.id, { timeout: 30_000 } );
		assert.match( await page.getByRole( 'table', { name: 'Practice history' } ).textContent(), /\/t\// );
		await page.getByRole( 'combobox', { name: 'Recorded from' } ).selectOption( String( child.id ) );
		await page.getByLabel( 'Import a recording file' ).setInputFiles( EMUR );
		await page.waitForFunction( () => window.glasshead.clinician.imported !== null && window.glasshead.clinician.agreement !== null, null, { timeout: 90_000, polling: 200 } );
		const state = ( await readDebug( page ) ).clinician;
		assert.equal( state.imported.ok, true, state.imported.message );
		assert.equal( state.target.name, 'phoneme:T' );
		const recordings = ( await api( sessions.clinician, 'GET', `epg/recordings?child_id=${ child.id }` ) ).body;
		assert.equal( recordings.total, state.imported.ids.length );
		// The view's agreement with the target is the compare API's, for the recording on screen.
		const target = ( await readDebug( page ) ).epg.synthetic.rows;
		const compared = await api( sessions.clinician, 'POST', `epg/recordings/${ state.recording.id }/compare`, { reference: { label: 'phoneme:T', frames: [ target ] } } );
		assert.equal( compared.status, 200, JSON.stringify( compared.body ) );
		assert.ok( Math.abs( state.agreement - compared.body.agreement[ state.frame ] ) <= 1e-12, `agreement ${ state.agreement } vs ${ compared.body.agreement[ state.frame ] }` );
		assert.deepEqual( page.problems, [] );

	} );

} );
