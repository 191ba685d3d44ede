// End-to-end: every view on a touch tablet, upright (768 x 1024) and on its side (1024 x 768), in
// Debian's Chromium. Every visible button, slider, select, text box and link is at least 44 px
// tall; the 3D view keeps at least half the screen's width and a third of its area; the EPG card
// never covers the head's lips (window.glasshead.epgCard: the card's and the lips' screen
// rectangles); the head turns and zooms from the keyboard once the 3D view has focus
// (window.glasshead.camera); Tab reaches every control; every slider crosses its range in at
// most 100 arrow presses, or 10 PageUp presses where an arrow is one frame. Screenshots
// tablet-<view>-<width> are for a person.

import assert from 'node:assert/strict';
import { describe, test } from 'node:test';
import { join, resolve } from 'node:path';
import { openSignedIn, signIn } from './accounts.js';
import { openPage, readDebug, REPO, saveScreenshot, serverAndBrowser, settle } from './harness.js';

const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( REPO, '..', 'shared', 'data' );
/** Recordings for the clinician view, imported through its file input (the first time only). */
const EMUR = join( DATA_DIR, 'epg', 'emur-engassim.json' );

const SIZES = [ { width: 768, height: 1024 }, { width: 1024, height: 768 } ];
const VIEWS = [ { name: 'head', hash: '#/' }, { name: 'workbench', hash: '#/workbench' }, { name: 'clinician', hash: '#/clinician' }, { name: 'speak', hash: '#/speak' } ];
/** The smallest touch target, CSS px (WCAG 2.5.5, Apple's guidelines). */
const TARGET_PX = 44;
/** Bounding boxes are fractional: this much under TARGET_PX still passes, px. */
const TOLERANCE_PX = 0.5;
/** The controls of a page: what a finger or the Tab key must reach. */
const CONTROLS = 'button, input, select, textarea, a[href], [tabindex="0"], [role="slider"]';

/** Every visible control's name and rectangle, in document order. */
function controlsOf( page ) {

	return page.evaluate( ( selector ) => [ ...document.querySelectorAll( selector ) ].filter( ( e ) => {

		const style = getComputedStyle( e );
		const rect = e.getBoundingClientRect();
		// The file input is drawn by its label (which is measured instead).
		const drawnByLabel = e.type === 'file' && e.closest( 'label' );
		return rect.width > 0 && rect.height > 0 && style.visibility !== 'hidden' && ! drawnByLabel && ! e.disabled;

	} ).map( ( e ) => {

		const r = e.getBoundingClientRect();
		const label = e.closest( 'label' );
		const rect = e.type === 'file' && label ? label.getBoundingClientRect() : r;
		return {
			name: e.getAttribute( 'aria-label' ) ?? ( e.textContent.trim() || e.id || e.className ).slice( 0, 40 ),
			tag: e.tagName.toLowerCase(), type: e.type ?? null, height: rect.height, width: rect.width,
		};

	} ), CONTROLS );

}

function intersects( a, b ) {

	return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;

}

describe( 'every view on a tablet', { timeout: 900_000 }, () => {

	let server, browser;
	const problems = [];

	serverAndBrowser( ( running ) => ( { server, browser } = running ) );

	let imported = false;
	async function open( view, size ) {

		if ( view.name === 'clinician' ) {

			// The clinician view has no 3D head to wait for: it has loaded when its lists have.
			const page = await openPage( browser, size );
			await signIn( page, server, 'clinician' );
			await page.goto( `${ server.baseUrl }/${ view.hash }` );
			await page.waitForFunction( () => window.glasshead.clinician?.loaded === true, null, { timeout: 90_000, polling: 200 } );
			if ( ! imported ) {

				await page.getByLabel( 'Import a recording file' ).setInputFiles( EMUR );
				imported = true;

			} else {

				// The first recording, as a person would choose it.
				await page.getByLabel( 'Recording', { exact: true } ).selectOption( { index: 1 } );

			}

			await page.waitForFunction( () => window.glasshead.clinician.recording !== null, null, { timeout: 60_000, polling: 200 } );
			return page;

		}

		// Signed in as a clinician, as the clinician view needs: the workbench offers saving.
		const page = await openSignedIn( browser, server, 'clinician', `${ server.baseUrl }/${ view.hash }`, size );
		if ( view.name === 'speak' ) await page.waitForFunction( () => window.glasshead.speech?.id && ! window.glasshead.speech.busy, null, { timeout: 60_000 } );
		await settle( page );
		return page;

	}

	for ( const size of SIZES ) {

		for ( const view of VIEWS ) {

			test( `at ${ size.width } x ${ size.height } the ${ view.name } view has 44 px targets, a 3D view of half the width, and keeps the lips clear`, async () => {

				const page = await open( view, size );
				try {

					const controls = await controlsOf( page );
					assert.ok( controls.length > 0, 'no controls found' );
					const small = controls.filter( ( c ) => c.height < TARGET_PX - TOLERANCE_PX ).map( ( c ) => `${ c.tag } ${ c.name }: ${ c.width.toFixed( 0 ) } x ${ c.height.toFixed( 0 ) }` );
					assert.deepEqual( small, [], `${ small.length } of ${ controls.length } controls under ${ TARGET_PX } px` );

					const canvas = await page.evaluate( () => [ ...document.querySelectorAll( 'canvas.viewer-canvas' ) ]
						.map( ( c ) => c.getBoundingClientRect() ).map( ( r ) => ( { width: r.width, height: r.height } ) )
						.sort( ( a, b ) => b.width * b.height - a.width * a.height )[ 0 ] ?? null );
					if ( view.name !== 'clinician' ) {

						// The clinician view's 3D palate is one card among the palatograms, not the view's stage.
						assert.ok( canvas, 'no 3D view' );
						assert.ok( canvas.width >= size.width / 2, `3D view ${ canvas.width } px wide of ${ size.width }` );
						assert.ok( canvas.width * canvas.height >= size.width * size.height / 3, `3D view ${ canvas.width } x ${ canvas.height }` );

					}

					const card = ( await readDebug( page ) ).epgCard;
					if ( view.name === 'head' || view.name === 'speak' ) {

						assert.ok( card?.card && card.mouth, `no EPG card or lips reported: ${ JSON.stringify( card ) }` );
						assert.ok( ! intersects( card.card, card.mouth ), `the EPG card ${ JSON.stringify( card.card ) } covers the lips ${ JSON.stringify( card.mouth ) }` );

					}

					await saveScreenshot( page, `tablet-${ view.name }-${ size.width }` );
					problems.push( ...page.problems.map( ( p ) => `${ view.name } ${ size.width }: ${ p }` ) );

				} finally {

					await page.context().close();

				}

			} );

		}

	}

	test( 'turned from landscape to upright and back, the head stays whole in the 3D view, and Profile still frames it', async () => {

		const page = await open( VIEWS[ 0 ], SIZES[ 1 ] );
		try {

			const framed = async ( label ) => {

				await settle( page );
				const { headRect } = await readDebug( page );
				const canvas = await page.locator( 'canvas.viewer-canvas' ).boundingBox();
				assert.ok( headRect, `${ label }: no head rectangle` );
				const inside = headRect.x >= canvas.x - 1 && headRect.y >= canvas.y - 1 && headRect.x + headRect.width <= canvas.x + canvas.width + 1 && headRect.y + headRect.height <= canvas.y + canvas.height + 1;
				assert.ok( inside, `${ label }: the head ${ JSON.stringify( headRect ) } leaves the ${ canvas.width } x ${ canvas.height } view` );
				// ...and is not lost in it either.
				assert.ok( headRect.width * headRect.height >= 0.15 * canvas.width * canvas.height, `${ label }: the head ${ JSON.stringify( headRect ) } is small in ${ canvas.width } x ${ canvas.height }` );

			};
			await framed( 'landscape' );
			await page.setViewportSize( SIZES[ 0 ] );
			await framed( 'upright' );
			await page.getByRole( 'button', { name: 'Profile' } ).click();
			await page.waitForFunction( () => window.glasshead.cameraMoving === false, null, { timeout: 30_000 } );
			await framed( 'upright, profile' );
			await page.setViewportSize( SIZES[ 1 ] );
			await framed( 'landscape again' );
			problems.push( ...page.problems );

		} finally {

			await page.context().close();

		}

	} );

	test( 'the head turns with the arrow keys and zooms with + and - once the 3D view has focus', async () => {

		const page = await open( VIEWS[ 0 ], SIZES[ 1 ] );
		try {

			const camera = async () => ( await readDebug( page ) ).camera;
			const distance = ( c ) => Math.hypot( ...c.position.map( ( p, i ) => p - c.target[ i ] ) );
			await page.locator( 'canvas.viewer-canvas' ).focus();
			assert.equal( await page.evaluate( () => document.activeElement.classList.contains( 'viewer-canvas' ) ), true );
			const start = await camera();
			await page.keyboard.press( 'ArrowLeft' );
			await page.keyboard.press( 'ArrowLeft' );
			const turned = await camera();
			// Turning keeps the distance to the target and moves the camera sideways.
			assert.ok( Math.abs( distance( turned ) - distance( start ) ) < 1e-3 * distance( start ), 'the distance changed while turning' );
			assert.ok( Math.hypot( turned.position[ 0 ] - start.position[ 0 ], turned.position[ 2 ] - start.position[ 2 ] ) > 0.2 * distance( start ), `the camera did not turn: ${ JSON.stringify( [ start, turned ] ) }` );
			await page.keyboard.press( 'ArrowUp' );
			assert.ok( ( await camera() ).position[ 1 ] !== turned.position[ 1 ], 'ArrowUp did not tilt the camera' );
			const before = distance( await camera() );
			await page.keyboard.press( '+' );
			const nearer = distance( await camera() );
			assert.ok( nearer < before * 0.95, `+ did not zoom in: ${ before } -> ${ nearer }` );
			await page.keyboard.press( '-' );
			assert.ok( Math.abs( distance( await camera() ) - before ) < 1e-3 * before, '- did not zoom back out' );
			const outline = await page.evaluate( () => getComputedStyle( document.activeElement ).outlineStyle );
			assert.notEqual( outline, 'none' );
			problems.push( ...page.problems );

		} finally {

			await page.context().close();

		}

	} );

	for ( const view of VIEWS ) {

		test( `Tab reaches every control of the ${ view.name } view, each with a visible focus outline, and its sliders cross their range in few presses`, async () => {

			const page = await open( view, SIZES[ 1 ] );
			try {

				const total = await page.evaluate( ( selector ) => [ ...document.querySelectorAll( selector ) ].filter( ( e ) => ! e.disabled && e.getClientRects().length > 0 && e.tabIndex >= 0 ).length, CONTROLS );
				const reached = new Set();
				const unmarked = [];
				for ( let k = 0; k < total + 20; k ++ ) {

					await page.keyboard.press( 'Tab' );
					const focused = await page.evaluate( () => {

						const e = document.activeElement;
						if ( ! e || e === document.body ) return null;
						if ( ! e.dataset.tabSeen ) e.dataset.tabSeen = String( document.querySelectorAll( '[data-tab-seen]' ).length );
						const style = getComputedStyle( e );
						return { id: e.dataset.tabSeen, name: e.getAttribute( 'aria-label' ) ?? e.textContent.trim().slice( 0, 30 ), outline: style.outlineStyle === 'none' ? 0 : parseFloat( style.outlineWidth ) };

					} );
					if ( ! focused ) continue;
					reached.add( focused.id );
					if ( focused.outline < 2 ) unmarked.push( `${ focused.name }: ${ focused.outline } px` );

				}

				const missed = await page.evaluate( ( selector ) => [ ...document.querySelectorAll( selector ) ]
					.filter( ( e ) => ! e.disabled && e.getClientRects().length > 0 && e.tabIndex >= 0 && ! e.dataset.tabSeen )
					.map( ( e ) => e.getAttribute( 'aria-label' ) ?? e.textContent.trim().slice( 0, 30 ) ), CONTROLS );
				assert.deepEqual( missed, [], 'controls Tab never reached' );
				assert.deepEqual( [ ...new Set( unmarked ) ], [], 'focused controls with an outline under 2 px' );

				const sliders = await page.locator( 'input[type="range"]:not(:disabled)' ).all();
				const slow = [];
				for ( const slider of sliders ) {

					if ( ! await slider.isVisible() ) continue;
					const name = await slider.getAttribute( 'aria-label' );
					const [ min, max ] = [ Number( await slider.getAttribute( 'min' ) ), Number( await slider.getAttribute( 'max' ) ) ];
					if ( ! ( max > min ) ) continue;
					await slider.focus();
					await page.keyboard.press( 'Home' );
					await page.keyboard.press( 'ArrowRight' );
					const arrow = Number( await slider.inputValue() ) - min;
					await page.keyboard.press( 'Home' );
					await page.keyboard.press( 'PageUp' );
					const big = Number( await slider.inputValue() ) - min;
					const frames = /^(Frame|Time)$/.test( name );
					// Frame and time sliders step one frame by the arrows: PageUp crosses them in 10 presses.
					if ( frames ? big < ( max - min ) / 10 - 1 : ( max - min ) / arrow > 100 + 1e-6 ) slow.push( `${ name }: arrow ${ arrow }, PageUp ${ big } of ${ max - min }` );

				}

				assert.deepEqual( slow, [] );
				problems.push( ...page.problems.map( ( p ) => `${ view.name }: ${ p }` ) );

			} finally {

				await page.context().close();

			}

		} );

	}

	test( 'the pages reported no errors', () => {

		assert.deepEqual( problems, [] );

	} );

} );
