// Starts the Glasshead server on a free port and launches Debian's Chromium (software WebGL via
// SwiftShader) through playwright-core, for the end-to-end tests.
//
// GLASSHEAD_E2E_BASE_URL=http://host:port runs the tests against a server that is already running.
//
// Every test file starts the same way, in the body of its describe block:
//
//   let server, browser, page;
//   serverAndBrowser( async ( running ) => {
//
//   	( { server, browser } = running );
//   	page = await openLoaded( browser, `${ server.baseUrl }/#/workbench` ); // the file's own set-up
//
//   } );

import { spawn } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { createServer } from 'node:net';
import { dirname, join } from 'node:path';
import { after, before } from 'node:test';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

export const REPO = join( dirname( fileURLToPath( import.meta.url ) ), '..' );
export const SCREENSHOT_DIR = join( REPO, 'e2e', 'screenshots' );
export const CHROMIUM = process.env.GLASSHEAD_CHROMIUM ?? '/usr/bin/chromium';

const CHROMIUM_ARGS = [
	'--use-angle=swiftshader',
	'--enable-unsafe-swiftshader',
	'--no-sandbox',
	'--disable-gpu-sandbox',
	'--disable-background-networking',
	'--disable-component-update',
	'--disable-sync',
	'--no-first-run',
];

/** Chromium's arguments for a microphone that plays the WAV at `path` (looped), its use allowed. */
export function fakeMicrophoneArgs( path ) {

	return [ '--use-fake-ui-for-media-stream', '--use-fake-device-for-media-stream', `--use-file-for-fake-audio-capture=${ path }`, '--autoplay-policy=no-user-gesture-required' ];

}

/** A TCP port that was free a moment ago on 127.0.0.1. */
export function freePort() {

	return new Promise( ( resolve, reject ) => {

		const server = createServer();
		server.unref();
		server.on( 'error', reject );
		server.listen( 0, '127.0.0.1', () => {

			const { port } = server.address();
			server.close( () => resolve( port ) );

		} );

	} );

}

/**
 * Start `uvicorn glasshead.api.app:app` from the repository root and wait until
 * /api/v1/health answers. Returns { baseUrl, databaseUrl, stop() }: `databaseUrl` is the server's
 * own database (for e2e/accounts.js to create users in), null for a server started elsewhere
 * unless GLASSHEAD_E2E_DATABASE_URL names it. `own`: a server of the file's own even when
 * GLASSHEAD_E2E_BASE_URL names a shared one (for tests that leave the server in a state the
 * other files must not meet, such as a user refused for too many wrong passwords).
 */
export async function startServer( { timeoutMs = 60_000, own = false } = {} ) {

	if ( process.env.GLASSHEAD_E2E_BASE_URL && ! own ) {

		const baseUrl = process.env.GLASSHEAD_E2E_BASE_URL.replace( /\/+$/, '' );
		await waitForHealth( baseUrl, timeoutMs, () => null );
		return { baseUrl, databaseUrl: process.env.GLASSHEAD_E2E_DATABASE_URL ?? null, stop: async () => {} };

	}

	const python = join( REPO, '.venv', 'bin', 'python' );
	if ( ! existsSync( python ) ) throw new Error( `No Python environment at ${ python }: run \`npm test\` (or node scripts/setup.mjs test) first` );
	if ( ! existsSync( join( REPO, 'web', 'dist', 'index.html' ) ) ) {

		throw new Error( 'The web app is not built (web/dist/index.html is missing): run `npx vite build web`' );

	}

	const port = await freePort();
	// A database of its own, so the run neither touches nor races with a developer's database.
	const scratch = mkdtempSync( join( tmpdir(), 'glasshead-e2e-' ) );
	const named = own ? null : process.env.GLASSHEAD_E2E_DATABASE_URL;
	const databaseUrl = named ?? `sqlite:///${ join( scratch, 'e2e.sqlite3' ) }`;
	const child = spawn( python, [ '-m', 'uvicorn', 'glasshead.api.app:app', '--host', '127.0.0.1', '--port', String( port ), '--log-level', 'warning' ], {
		cwd: REPO,
		stdio: [ 'ignore', 'pipe', 'pipe' ],
		env: { ...process.env, GLASSHEAD_DATABASE_URL: databaseUrl },
	} );
	let output = '';
	child.stdout.on( 'data', ( chunk ) => ( output += chunk ) );
	child.stderr.on( 'data', ( chunk ) => ( output += chunk ) );
	let exited = null;
	child.on( 'exit', ( code, signal ) => ( exited = { code, signal } ) );

	const baseUrl = `http://127.0.0.1:${ port }`;
	try {

		await waitForHealth( baseUrl, timeoutMs, () => ( exited ? `the server exited (${ exited.code ?? exited.signal }):\n${ lastLines( output, 30 ) }` : null ) );

	} catch ( error ) {

		child.kill( 'SIGTERM' );
		rmSync( scratch, { recursive: true, force: true } );
		throw error;

	}

	return {
		baseUrl,
		databaseUrl,
		stop: () => new Promise( ( resolve ) => {

			const done = () => {

				rmSync( scratch, { recursive: true, force: true } );
				resolve();

			};
			if ( exited ) return done();
			child.once( 'exit', done );
			child.kill( 'SIGTERM' );
			setTimeout( () => child.kill( 'SIGKILL' ), 5000 ).unref();

		} ),
	};

}

function lastLines( text, count ) {

	return text.trimEnd().split( '\n' ).slice( - count ).join( '\n' );

}

async function waitForHealth( baseUrl, timeoutMs, failure ) {

	const deadline = Date.now() + timeoutMs;
	let last = 'no answer yet';
	while ( Date.now() < deadline ) {

		const reason = failure();
		if ( reason ) throw new Error( `Could not start the Glasshead server: ${ reason }` );
		try {

			const response = await fetch( `${ baseUrl }/api/v1/health` );
			const body = await response.json();
			if ( response.ok && body.status === 'ok' ) return body;
			last = `HTTP ${ response.status }: ${ JSON.stringify( body ) }`;

		} catch ( error ) {

			last = error.message;

		}

		await new Promise( ( resolve ) => setTimeout( resolve, 200 ) );

	}

	throw new Error( `The Glasshead server at ${ baseUrl } did not become healthy in ${ timeoutMs } ms (last: ${ last })` );

}

/**
 * Launch Debian's Chromium headless, with `args` besides the usual ones (a fake microphone);
 * fails with an install hint when it is missing.
 */
export async function launchBrowser( { args = [] } = {} ) {

	if ( ! existsSync( CHROMIUM ) ) {

		throw new Error( `Debian's Chromium is not installed at ${ CHROMIUM }: install it with \`sudo apt-get install chromium\` (the tests never download a browser)` );

	}

	return chromium.launch( { executablePath: CHROMIUM, headless: true, args: [ ...CHROMIUM_ARGS, ...args ] } );

}

/**
 * The start-up and shut-down of a describe block's tests, called in its body: before the tests,
 * start the server (startServer) and launch the browser (launchBrowser), then run
 * `prepare( { server, browser } )`, the file's own set-up (accounts, data, a first page); after
 * them, close the browser and stop the server, whatever failed. Returns that { server, browser }
 * object, filled in once the tests' `before` has run. `ownServer`: as startServer's `own`.
 */
export function serverAndBrowser( prepare = () => {}, { ownServer = false } = {} ) {

	const running = { server: null, browser: null };
	before( async () => {

		running.server = await startServer( { own: ownServer } );
		running.browser = await launchBrowser();
		await prepare( running );

	} );
	after( async () => {

		await running.browser?.close();
		await running.server?.stop();

	} );
	return running;

}

/**
 * A page that records console errors and uncaught exceptions into `page.problems`.
 */
export async function openPage( browser, { width = 1280, height = 800 } = {} ) {

	const context = await browser.newContext( { viewport: { width, height }, deviceScaleFactor: 1 } );
	const page = await context.newPage();
	page.problems = [];
	page.on( 'console', ( message ) => {

		if ( message.type() !== 'error' ) return;
		const { url } = message.location();
		page.problems.push( `console error: ${ message.text() }${ url ? ` (${ url })` : '' }` );

	} );
	page.on( 'pageerror', ( error ) => page.problems.push( `uncaught: ${ error.message }` ) );
	return page;

}

/** The page's `window.glasshead`, copied out as plain data. */
export function readDebug( page ) {

	return page.evaluate( () => JSON.parse( JSON.stringify( window.glasshead ) ) );

}

/** Wait until `window.glasshead.loaded` (or fail with the page's error message). */
export async function waitForLoaded( page, timeoutMs = 90_000 ) {

	await page.waitForFunction( () => window.glasshead?.loaded === true || Boolean( window.glasshead?.error ), null, { timeout: timeoutMs, polling: 200 } );
	const state = await readDebug( page );
	if ( state.error ) throw new Error( `The page reported an error while loading: ${ state.error }` );
	return state;

}

/** Wait until the camera has stopped and every change has been drawn. */
export async function settle( page ) {

	await page.waitForFunction( () => window.glasshead.cameraMoving === false && window.glasshead.renderPending === false, null, { timeout: 30_000, polling: 50 } );

}

/**
 * Wait until the page has been through `count` animation frames: whatever a change of size or of
 * the page sets off before the next paint (resize observers, the next draw) has run by then, on a
 * fast machine or a slow one.
 */
export async function animationFrames( page, count = 2 ) {

	await page.evaluate( ( n ) => new Promise( ( resolve ) => {

		let left = n;
		const tick = () => ( -- left <= 0 ? resolve() : requestAnimationFrame( tick ) );
		requestAnimationFrame( tick );

	} ), count );

}

/**
 * Wait until a whole animation frame of the 3D view goes by with nothing drawn: the camera has
 * stopped, every change has been drawn and every frame hook (the eyes' gaze and blinks, the cue
 * layer) reports no change. A moving gaze or a blink keeps drawing, however slowly frames come.
 */
export async function waitForStill( page, timeoutMs = 60_000 ) {

	await page.evaluate( () => ( window.__e2eStillFrames = null ) );
	await page.waitForFunction( () => {

		const g = window.glasshead;
		const last = window.__e2eStillFrames;
		window.__e2eStillFrames = g.frames;
		return last === g.frames && g.cameraMoving === false && g.renderPending === false;

	}, null, { timeout: timeoutMs, polling: 'raf' } );

}

/**
 * A new page at `url` (a view of the served app, e.g. `${ server.baseUrl }/#/workbench`) once it has loaded and
 * settled; `size` as openPage's.
 */
export async function openLoaded( browser, url, size ) {

	const page = await openPage( browser, size );
	await page.goto( url );
	await waitForLoaded( page );
	await settle( page );
	return page;

}

/** Save a screenshot of the page to e2e/screenshots/<name>.png and return its path. */
export async function saveScreenshot( page, name ) {

	mkdirSync( SCREENSHOT_DIR, { recursive: true } );
	const path = join( SCREENSHOT_DIR, `${ name }.png` );
	await page.screenshot( { path } );
	return path;

}
