// The pictures of the child's practice, so that nothing needs reading: an animal face for each
// avatar of GET /children/avatars, three faces for how a try went (the rating 1 not yet, 2 nearly,
// 3 got it) and the icons of the big buttons. Drawn as small inline SVG from shape lists (no
// emoji font needed, no inline style attribute: the page's CSP forbids them), each with an
// accessible name. `pictureShapes( name )` is the pure part the unit tests read.

const SVG = 'http://www.w3.org/2000/svg';

/** How a try went, as the child rates it (the practice record's `rating`). */
export const RATINGS = Object.freeze( [
	Object.freeze( { rating: 1, face: 'sad', label: 'Not yet' } ),
	Object.freeze( { rating: 2, face: 'meh', label: 'Nearly' } ),
	Object.freeze( { rating: 3, face: 'happy', label: 'Got it' } ),
] );

const EYES = ( y = 46, dx = 12, r = 4 ) => [ [ 'circle', { cx: 50 - dx, cy: y, r, fill: '#1f2328' } ], [ 'circle', { cx: 50 + dx, cy: y, r, fill: '#1f2328' } ] ];
const NOSE = ( fill = '#1f2328', y = 58 ) => [ [ 'ellipse', { cx: 50, cy: y, rx: 5, ry: 3.5, fill } ] ];
const HEAD = ( fill, r = 30, cy = 52 ) => [ [ 'circle', { cx: 50, cy, r, fill } ] ];
const POINTED_EARS = ( fill ) => [ [ 'polygon', { points: '24,40 28,12 46,28', fill } ], [ 'polygon', { points: '76,40 72,12 54,28', fill } ] ];
const ROUND_EARS = ( fill ) => [ [ 'circle', { cx: 27, cy: 28, r: 11, fill } ], [ 'circle', { cx: 73, cy: 28, r: 11, fill } ] ];
const WHISKERS = [ [ 'path', { d: 'M20 58 L38 60 M20 66 L38 63 M80 58 L62 60 M80 66 L62 63', stroke: '#1f2328', 'stroke-width': 2, fill: 'none' } ] ];
const BEAK = ( fill ) => [ [ 'polygon', { points: '44,56 56,56 50,67', fill } ] ];

/** The avatars' pictures: SVG shapes [tag, attributes] in a 100 x 100 box. */
const AVATAR_SHAPES = Object.freeze( {
	cat: [ ...POINTED_EARS( '#f0a050' ), ...HEAD( '#f0a050' ), ...EYES(), ...NOSE( '#c0506a' ), ...WHISKERS ],
	dog: [ [ 'ellipse', { cx: 22, cy: 50, rx: 10, ry: 20, fill: '#7a4a26' } ], [ 'ellipse', { cx: 78, cy: 50, rx: 10, ry: 20, fill: '#7a4a26' } ], ...HEAD( '#c08850' ), ...EYES(), [ 'ellipse', { cx: 50, cy: 64, rx: 13, ry: 10, fill: '#f2dcc0' } ], ...NOSE( '#1f2328', 60 ) ],
	fox: [ [ 'polygon', { points: '22,44 24,6 46,28', fill: '#d9612a' } ], [ 'polygon', { points: '78,44 76,6 54,28', fill: '#d9612a' } ], [ 'polygon', { points: '20,40 80,40 50,86', fill: '#d9612a' } ], [ 'polygon', { points: '34,58 66,58 50,86', fill: '#ffffff' } ], ...EYES( 46 ), ...NOSE( '#1f2328', 82 ) ],
	owl: [ [ 'polygon', { points: '22,34 26,14 40,28', fill: '#8a6a4a' } ], [ 'polygon', { points: '78,34 74,14 60,28', fill: '#8a6a4a' } ], ...HEAD( '#8a6a4a', 32 ), [ 'circle', { cx: 38, cy: 46, r: 11, fill: '#ffffff' } ], [ 'circle', { cx: 62, cy: 46, r: 11, fill: '#ffffff' } ], ...EYES( 46, 12, 5 ), ...BEAK( '#e0a020' ) ],
	frog: [ [ 'circle', { cx: 32, cy: 34, r: 13, fill: '#4caf50' } ], [ 'circle', { cx: 68, cy: 34, r: 13, fill: '#4caf50' } ], [ 'ellipse', { cx: 50, cy: 60, rx: 36, ry: 24, fill: '#4caf50' } ], [ 'circle', { cx: 32, cy: 32, r: 7, fill: '#ffffff' } ], [ 'circle', { cx: 68, cy: 32, r: 7, fill: '#ffffff' } ], ...EYES( 32, 18, 3.5 ), [ 'path', { d: 'M30 64 Q50 78 70 64', stroke: '#1f2328', 'stroke-width': 3, fill: 'none' } ] ],
	bear: [ ...ROUND_EARS( '#6b4226' ), ...HEAD( '#6b4226' ), ...EYES(), [ 'ellipse', { cx: 50, cy: 64, rx: 13, ry: 10, fill: '#c8a27a' } ], ...NOSE( '#1f2328', 60 ) ],
	fish: [ [ 'polygon', { points: '70,50 94,30 94,70', fill: '#2f7fd1' } ], [ 'ellipse', { cx: 46, cy: 50, rx: 34, ry: 22, fill: '#4aa3f0' } ], [ 'circle', { cx: 26, cy: 46, r: 4, fill: '#1f2328' } ], [ 'path', { d: 'M48 34 Q56 50 48 66', stroke: '#2f7fd1', 'stroke-width': 3, fill: 'none' } ] ],
	bird: [ ...HEAD( '#f4c430', 30 ), [ 'ellipse', { cx: 50, cy: 22, rx: 6, ry: 10, fill: '#f4c430' } ], ...EYES( 46, 11 ), ...BEAK( '#e07020' ) ],
	rabbit: [ [ 'ellipse', { cx: 38, cy: 22, rx: 8, ry: 22, fill: '#d8d8d8' } ], [ 'ellipse', { cx: 62, cy: 22, rx: 8, ry: 22, fill: '#d8d8d8' } ], [ 'ellipse', { cx: 38, cy: 24, rx: 4, ry: 15, fill: '#f4b6c2' } ], [ 'ellipse', { cx: 62, cy: 24, rx: 4, ry: 15, fill: '#f4b6c2' } ], ...HEAD( '#d8d8d8', 28, 60 ), ...EYES( 56 ), ...NOSE( '#e07a90', 66 ) ],
	turtle: [ [ 'circle', { cx: 84, cy: 56, r: 10, fill: '#7cb342' } ], [ 'path', { d: 'M14 66 A36 36 0 0 1 78 66 Z', fill: '#558b2f' } ], [ 'path', { d: 'M30 64 L38 46 L54 46 L62 64 M38 46 L46 36 L54 46', stroke: '#33691e', 'stroke-width': 3, fill: 'none' } ], [ 'circle', { cx: 87, cy: 53, r: 2.5, fill: '#1f2328' } ] ],
	lion: [ [ 'circle', { cx: 50, cy: 52, r: 42, fill: '#b5651d' } ], ...HEAD( '#f0b040', 28 ), ...ROUND_EARS( '#f0b040' ).map( ( [ tag, a ] ) => [ tag, { ...a, r: 7, cy: 30 } ] ), ...EYES( 48, 10 ), ...NOSE( '#6b3a16', 60 ) ],
	panda: [ ...ROUND_EARS( '#1f2328' ), ...HEAD( '#ffffff' ), [ 'circle', { cx: 50, cy: 52, r: 30, fill: 'none', stroke: '#1f2328', 'stroke-width': 2 } ], [ 'ellipse', { cx: 38, cy: 48, rx: 8, ry: 10, fill: '#1f2328' } ], [ 'ellipse', { cx: 62, cy: 48, rx: 8, ry: 10, fill: '#1f2328' } ], [ 'circle', { cx: 38, cy: 47, r: 3, fill: '#ffffff' } ], [ 'circle', { cx: 62, cy: 47, r: 3, fill: '#ffffff' } ], ...NOSE( '#1f2328', 62 ) ],
} );

const FACE = ( fill ) => [ [ 'circle', { cx: 50, cy: 50, r: 44, fill, stroke: '#1f2328', 'stroke-width': 3 } ], ...EYES( 40, 15, 6 ) ];

/** The rating faces and the buttons' icons, in the same 100 x 100 box. */
const ICON_SHAPES = Object.freeze( {
	sad: [ ...FACE( '#f7b6a8' ), [ 'path', { d: 'M30 74 Q50 56 70 74', stroke: '#1f2328', 'stroke-width': 5, fill: 'none', 'stroke-linecap': 'round' } ] ],
	meh: [ ...FACE( '#f9e08a' ), [ 'path', { d: 'M32 68 L68 68', stroke: '#1f2328', 'stroke-width': 5, 'stroke-linecap': 'round' } ] ],
	happy: [ ...FACE( '#a8e0a0' ), [ 'path', { d: 'M28 60 Q50 84 72 60', stroke: '#1f2328', 'stroke-width': 5, fill: 'none', 'stroke-linecap': 'round' } ] ],
	/** Hear it again: a loudspeaker with sound waves. */
	replay: [ [ 'polygon', { points: '14,38 30,38 50,20 50,80 30,62 14,62', fill: '#ffffff' } ], [ 'path', { d: 'M62 34 Q72 50 62 66 M72 24 Q88 50 72 76', stroke: '#ffffff', 'stroke-width': 6, fill: 'none', 'stroke-linecap': 'round' } ] ],
	/** I tried it: a smiling mouth and a tick. */
	tried: [ [ 'circle', { cx: 50, cy: 50, r: 44, fill: '#ffffff' } ], [ 'path', { d: 'M26 52 L44 70 L76 32', stroke: '#2e7d32', 'stroke-width': 11, fill: 'none', 'stroke-linecap': 'round', 'stroke-linejoin': 'round' } ] ],
	/** Go on without saying how it went. */
	next: [ [ 'path', { d: 'M18 50 L76 50 M52 24 L80 50 L52 76', stroke: '#1f2328', 'stroke-width': 10, fill: 'none', 'stroke-linecap': 'round', 'stroke-linejoin': 'round' } ] ],
	/** Go back, or not me. */
	back: [ [ 'path', { d: 'M82 50 L24 50 M48 24 L20 50 L48 76', stroke: '#1f2328', 'stroke-width': 10, fill: 'none', 'stroke-linecap': 'round', 'stroke-linejoin': 'round' } ] ],
	/** Not me: a person stepping out through a door. */
	notme: [ [ 'rect', { x: 52, y: 10, width: 38, height: 80, rx: 3, fill: '#8d6e63' } ], [ 'circle', { cx: 82, cy: 52, r: 3.5, fill: '#f4c430' } ], [ 'circle', { cx: 30, cy: 26, r: 11, fill: '#1f2328' } ], [ 'path', { d: 'M30 40 L30 66 M30 66 L18 88 M30 66 L42 88 M30 46 L14 58 M30 46 L46 40', stroke: '#1f2328', 'stroke-width': 7, fill: 'none', 'stroke-linecap': 'round' } ] ],
	/** My lessons: cards laid out to choose from. */
	lessons: [ [ 'rect', { x: 10, y: 12, width: 36, height: 34, rx: 6, fill: '#4aa3f0' } ], [ 'rect', { x: 54, y: 12, width: 36, height: 34, rx: 6, fill: '#f4c430' } ], [ 'rect', { x: 10, y: 54, width: 36, height: 34, rx: 6, fill: '#4caf50' } ], [ 'rect', { x: 54, y: 54, width: 36, height: 34, rx: 6, fill: '#ec407a' } ] ],
	/** For grown-ups: a padlock. */
	lock: [ [ 'path', { d: 'M32 46 L32 32 Q32 14 50 14 Q68 14 68 32 L68 46', stroke: '#1f2328', 'stroke-width': 8, fill: 'none' } ], [ 'rect', { x: 22, y: 44, width: 56, height: 44, rx: 8, fill: '#1f2328' } ], [ 'circle', { cx: 50, cy: 64, r: 6, fill: '#ffffff' } ] ],
	/** Ask a grown-up: a tall person beside a small one. */
	'ask-adult': [ [ 'circle', { cx: 34, cy: 18, r: 10, fill: '#6d4c41' } ], [ 'path', { d: 'M34 30 L34 62 M34 62 L24 92 M34 62 L44 92 M34 38 L52 52', stroke: '#6d4c41', 'stroke-width': 8, fill: 'none', 'stroke-linecap': 'round' } ], [ 'circle', { cx: 70, cy: 48, r: 8, fill: '#2f7fd1' } ], [ 'path', { d: 'M70 58 L70 76 M70 76 L62 94 M70 76 L78 94 M70 62 L56 54', stroke: '#2f7fd1', 'stroke-width': 7, fill: 'none', 'stroke-linecap': 'round' } ] ],
	/** Done: a star. */
	star: [ [ 'polygon', { points: '50,6 62,36 94,38 69,58 78,90 50,72 22,90 31,58 6,38 38,36', fill: '#f4c430', stroke: '#b38600', 'stroke-width': 3 } ] ],
} );

/** The avatars that have a picture (the server's list: cat, dog, fox, ...). */
export const AVATAR_NAMES = Object.freeze( Object.keys( AVATAR_SHAPES ) );

/** The shapes of picture `name` (an avatar or an icon): [[tag, attributes]]; a plain circle for an unknown avatar. */
export function pictureShapes( name ) {

	return AVATAR_SHAPES[ name ] ?? ICON_SHAPES[ name ] ?? [ [ 'circle', { cx: 50, cy: 50, r: 40, fill: '#9aa4ae' } ] ];

}

/**
 * An <svg> of `shapes` ([tag, attributes] in a 100 x 100 box). With a `label` it is an image of
 * that name (role img); without, it is decoration (the button around it carries the name).
 */
export function shapesSvg( shapes, { label = null, className = 'cp-picture', doc = globalThis.document } = {} ) {

	const svg = doc.createElementNS( SVG, 'svg' );
	svg.setAttribute( 'viewBox', '0 0 100 100' );
	svg.setAttribute( 'class', className );
	svg.setAttribute( 'focusable', 'false' );
	if ( label ) {

		svg.setAttribute( 'role', 'img' );
		svg.setAttribute( 'aria-label', label );

	} else svg.setAttribute( 'aria-hidden', 'true' );

	for ( const [ tag, attributes ] of shapes ) {

		const shape = doc.createElementNS( SVG, tag );
		for ( const [ key, value ] of Object.entries( attributes ) ) shape.setAttribute( key, String( value ) );
		svg.append( shape );

	}

	return svg;

}

/** An <svg> of picture `name` (an avatar or an icon; shapesSvg's options). */
export function picture( name, options ) {

	return shapesSvg( pictureShapes( name ), options );

}
