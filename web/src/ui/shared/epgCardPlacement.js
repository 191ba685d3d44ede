// Where the EPG card sits over the 3D view: in a corner of the stage that does not cover the
// head's lips, nor, with the cutaway on, the velum where it can help it. On a tablet the head fills the stage and the lips come close to the bottom-left
// corner the card started in, so the card moves, whenever the camera or the stage's size changes,
// to the first corner (bottom left, top left, bottom right, top right) clear of the lips; if
// none is, to the one that covers least of them.
//
// window.glasshead.epgCard = { corner, card, mouth }: the rectangles in CSS px of the page.

import { registerDebug } from '../../debug.js';

/** Corners in order of preference: bottom left reads beside the head without hiding the face. */
export const CORNERS = Object.freeze( [ 'bottom-left', 'top-left', 'bottom-right', 'top-right' ] );
/** Space between the card and the stage's edge, CSS px. */
export const MARGIN_PX = 16;

/** The card's rectangle { x, y, width, height } in `corner` of `stage` (all rectangles in one frame). */
export function cornerRect( corner, stage, card, margin = MARGIN_PX ) {

	const left = corner.endsWith( 'left' );
	const top = corner.startsWith( 'top' );
	return {
		x: left ? stage.x + margin : stage.x + stage.width - margin - card.width,
		y: top ? stage.y + margin : stage.y + stage.height - margin - card.height,
		width: card.width,
		height: card.height,
	};

}

/** The area of the overlap of two rectangles. */
export function overlapArea( a, b ) {

	const w = Math.min( a.x + a.width, b.x + b.width ) - Math.max( a.x, b.x );
	const h = Math.min( a.y + a.height, b.y + b.height ) - Math.max( a.y, b.y );
	return w > 0 && h > 0 ? w * h : 0;

}

/**
 * The corner for the card: of those whose card misses `mouth` (null: no lips known), the first
 * that misses `also` too (the velum in the cutaway's section; null: nothing else), else the one
 * covering least of it; when every corner covers the lips, the one covering least of them.
 */
export function chooseCorner( stage, card, mouth, margin = MARGIN_PX, also = null ) {

	const cover = ( corner, rect ) => ( rect ? overlapArea( cornerRect( corner, stage, card, margin ), rect ) : 0 );
	const clear = CORNERS.filter( ( corner ) => cover( corner, mouth ) === 0 );
	const [ among, rect ] = clear.length ? [ clear, also ] : [ CORNERS, mouth ];
	let best = among[ 0 ], least = Infinity;
	for ( const corner of among ) {

		const area = cover( corner, rect );
		if ( area < least ) [ best, least ] = [ corner, area ];

	}

	return best;

}

/**
 * Keep `panel` (absolutely placed in `view.stage`) clear of the lips of `view.head`, seen by
 * `view.viewer`. Returns a function that stops.
 */
export function keepCardClearOfLips( view, panel ) {

	const { viewer } = view;
	const seen = new Float64Array( 18 ).fill( Number.NaN );
	let corner = null, mouth = null;

	const place = () => {

		const stage = view.stage.getBoundingClientRect();
		const card = { width: panel.offsetWidth, height: panel.offsetHeight };
		mouth = viewer.screenRect( view.head.mouthBox() );
		const velum = view.head.velumBox?.();
		const next = chooseCorner( { x: stage.left, y: stage.top, width: stage.width, height: stage.height }, card, mouth, MARGIN_PX, velum ? viewer.screenRect( velum ) : null );
		if ( next === corner ) return;
		corner = next;
		panel.dataset.corner = corner;
		// Through the CSSOM: the page's policy allows no inline style attributes.
		panel.style.left = corner.endsWith( 'left' ) ? `${ MARGIN_PX }px` : 'auto';
		panel.style.right = corner.endsWith( 'left' ) ? 'auto' : `${ MARGIN_PX }px`;
		panel.style.top = corner.startsWith( 'top' ) ? `${ MARGIN_PX }px` : 'auto';
		panel.style.bottom = corner.startsWith( 'top' ) ? 'auto' : `${ MARGIN_PX }px`;

	};

	const changed = () => {

		const matrix = viewer.camera.matrixWorld.elements;
		const canvas = viewer.renderer.domElement;
		let moved = false;
		for ( let k = 0; k < 16; k ++ ) {

			if ( seen[ k ] !== matrix[ k ] ) moved = true;
			seen[ k ] = matrix[ k ];

		}

		if ( seen[ 16 ] !== canvas.clientWidth || seen[ 17 ] !== canvas.clientHeight ) moved = true;
		seen[ 16 ] = canvas.clientWidth;
		seen[ 17 ] = canvas.clientHeight;
		return moved;

	};

	const stopFrames = viewer.onFrame( () => {

		if ( changed() ) place();
		return false; // the card is HTML over the canvas: it never needs a new 3D frame

	} );
	const unregister = registerDebug( 'epgCard', () => {

		const r = panel.getBoundingClientRect();
		return { corner, card: { x: r.left, y: r.top, width: r.width, height: r.height }, mouth };

	} );
	return () => {

		stopFrames();
		unregister();

	};

}
