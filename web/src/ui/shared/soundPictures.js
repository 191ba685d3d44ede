// A picture for each sound, for children who cannot read: the child's views show it in place of
// the IPA (a snake for /s/, a finger to the lips for /ʃ/, a smile for /i/). Each is a few SVG
// shapes in a 100 x 100 box, drawn by ChildPracticePictures' shapesSvg, with words that name it
// for a screen reader and for the head to say. Vowels are mouths: spread for /i/, open for /ɑ/,
// round for /u/; a diphthong is its two mouths with an arrow between. Keyed by ARPAbet.
//
//   element.append( soundPicture( 'S' ) );   // <svg role="img" aria-label="a snake: sss">

import { shapesSvg } from './ChildPracticePictures.js';

const INK = '#1f2328';
const SKIN = '#ffd9b3';
const LIP = '#d9475b';
const MOUTH = '#7a1c2a';
const line = ( d, stroke = INK, width = 4 ) => [ 'path', { d, stroke, 'stroke-width': width, fill: 'none', 'stroke-linecap': 'round', 'stroke-linejoin': 'round' } ];
const disc = ( cx, cy, r, fill, extra = {} ) => [ 'circle', { cx, cy, r, fill, ...extra } ];
const oval = ( cx, cy, rx, ry, fill, extra = {} ) => [ 'ellipse', { cx, cy, rx, ry, fill, ...extra } ];
const box = ( x, y, width, height, fill, extra = {} ) => [ 'rect', { x, y, width, height, fill, ...extra } ];

/** The voice: sound waves on the right, for the voiced twin of a picture. */
const VOICE = [ line( 'M84 30 Q92 40 84 50', '#2f7fd1', 4 ), line( 'M90 22 Q102 40 90 58', '#2f7fd1', 4 ) ];
/** A face seen from the front, its mouth left to the picture. */
const FACE = [ disc( 50, 50, 40, SKIN, { stroke: INK, 'stroke-width': 3 } ), disc( 36, 40, 4.5, INK ), disc( 64, 40, 4.5, INK ) ];

/** A mouth at (cx, cy): lips round an opening `rx` by `ry`, spread with teeth for a smile. */
function mouth( cx, cy, rx, ry, { teeth = false } = {} ) {

	const shapes = [ oval( cx, cy, rx, ry, MOUTH, { stroke: LIP, 'stroke-width': 5 } ) ];
	if ( teeth ) shapes.push( box( cx - rx + 3, cy - ry + 1, 2 * rx - 6, Math.max( ry - 1, 2 ), '#ffffff' ) );
	return shapes;

}

/** The vowels' mouths: half width and half height of the opening. */
const VOWEL_MOUTHS = Object.freeze( {
	IY: [ 22, 5, true ], IH: [ 18, 7, true ], EH: [ 17, 10 ], AE: [ 20, 13 ], AH: [ 13, 10 ],
	AA: [ 13, 17 ], AO: [ 11, 14 ], UH: [ 9, 9 ], UW: [ 6, 6 ], ER: [ 9, 8 ],
} );

const vowelFace = ( code ) => {

	const [ rx, ry, teeth ] = VOWEL_MOUTHS[ code ];
	return [ ...FACE, ...mouth( 50, 68, rx, ry, { teeth } ) ];

};

/** A diphthong: the mouth of its start, an arrow, the mouth of its end. */
const glide = ( from, to ) => {

	const [ ax, ay, at ] = VOWEL_MOUTHS[ from ];
	const [ bx, by, bt ] = VOWEL_MOUTHS[ to ];
	return [ ...mouth( 24, 50, ax * 0.8, ay * 0.8, { teeth: at } ), line( 'M42 50 L60 50 M53 42 L61 50 L53 58', INK, 5 ), ...mouth( 78, 50, bx * 0.8, by * 0.8, { teeth: bt } ) ];

};

const tongueOut = [ ...FACE, oval( 50, 70, 14, 6, MOUTH, { stroke: LIP, 'stroke-width': 4 } ), box( 40, 64, 20, 4, '#ffffff' ), oval( 50, 76, 8, 7, '#e86a7a' ) ];
const hush = [ ...FACE, oval( 50, 70, 7, 7, MOUTH, { stroke: LIP, 'stroke-width': 5 } ), box( 46, 52, 8, 36, SKIN, { rx: 4, stroke: INK, 'stroke-width': 2.5 } ) ];
const humming = [ ...FACE, line( 'M38 70 L62 70', LIP, 6 ), line( 'M62 22 L62 6 L74 4 L74 18', INK, 3 ), disc( 59, 22, 4, INK ), disc( 71, 18, 4, INK ) ];

/** Each sound's picture: the words that name it and its shapes. */
const SOUNDS = Object.freeze( {
	// Vowels and diphthongs: mouths.
	IY: [ 'a big smile: ee', vowelFace( 'IY' ) ],
	IH: [ 'a small smile: i', vowelFace( 'IH' ) ],
	EH: [ 'a mouth half open: e', vowelFace( 'EH' ) ],
	AE: [ 'a mouth open and wide: a', vowelFace( 'AE' ) ],
	AH: [ 'a relaxed open mouth: uh', vowelFace( 'AH' ) ],
	AA: [ 'a mouth open wide for the doctor: ah', vowelFace( 'AA' ) ],
	AO: [ 'a round open mouth: aw', vowelFace( 'AO' ) ],
	UH: [ 'a loose round mouth: oo', vowelFace( 'UH' ) ],
	UW: [ 'lips tight and round like an owl: oo', vowelFace( 'UW' ) ],
	ER: [ 'lips a little round: er', vowelFace( 'ER' ) ],
	AW: [ 'open, then round: ow', glide( 'AA', 'UW' ) ],
	AY: [ 'open, then a smile: eye', glide( 'AA', 'IY' ) ],
	EY: [ 'half open, then a smile: ay', glide( 'EH', 'IY' ) ],
	OW: [ 'round, then rounder: oh', glide( 'AO', 'UW' ) ],
	OY: [ 'round, then a smile: oy', glide( 'AO', 'IY' ) ],
	// Consonants: something that makes the sound.
	P: [ 'a balloon going pop: p', [ oval( 44, 46, 26, 30, '#e53935' ), line( 'M44 76 L46 92', INK, 2 ), line( 'M76 20 L86 12 M80 36 L94 34 M74 8 L76 2', '#f4a300', 4 ) ] ],
	B: [ 'bubbles: b b b', [ disc( 32, 64, 18, '#bfe3ff', { stroke: '#2f7fd1', 'stroke-width': 3 } ), disc( 62, 40, 13, '#bfe3ff', { stroke: '#2f7fd1', 'stroke-width': 3 } ), disc( 80, 16, 8, '#bfe3ff', { stroke: '#2f7fd1', 'stroke-width': 3 } ) ] ],
	M: [ 'yummy soup: mmm', [ line( 'M38 30 Q32 20 38 10 M52 30 Q46 20 52 10 M66 30 Q60 20 66 10', '#9aa4ae', 3 ), [ 'path', { d: 'M12 44 L88 44 Q84 84 50 86 Q16 84 12 44 Z', fill: '#f08a24' } ], box( 10, 40, 80, 8, '#c75f0a', { rx: 3 } ) ] ],
	F: [ 'a fan blowing: fff', [ disc( 34, 50, 26, '#cfd8dc', { stroke: INK, 'stroke-width': 3 } ), line( 'M34 24 L34 76 M8 50 L60 50', '#78909c', 6 ), disc( 34, 50, 5, INK ), line( 'M68 36 L94 36 M70 50 L96 50 M68 64 L94 64', '#2f7fd1', 4 ) ] ],
	V: [ 'a phone buzzing: vvv', [ box( 32, 14, 36, 72, INK, { rx: 6 } ), box( 36, 22, 28, 52, '#90caf9' ), line( 'M20 30 L14 40 L20 50 L14 60 M80 30 L86 40 L80 50 L86 60', '#f4a300', 4 ) ] ],
	TH: [ 'the tongue between the teeth: th', tongueOut ],
	DH: [ 'the tongue between the teeth, with the voice on: th', [ ...tongueOut, ...VOICE ] ],
	T: [ 'a clock ticking: t t t', [ disc( 50, 52, 38, '#ffffff', { stroke: INK, 'stroke-width': 5 } ), line( 'M50 52 L50 26 M50 52 L68 60', INK, 5 ), disc( 50, 8, 6, INK ) ] ],
	D: [ 'a drum: d d d', [ oval( 50, 40, 34, 10, '#f5f5f5', { stroke: INK, 'stroke-width': 3 } ), [ 'path', { d: 'M16 40 L16 74 Q50 90 84 74 L84 40 Q50 54 16 40 Z', fill: '#e53935' } ], line( 'M70 8 L56 34 M30 8 L44 34', '#8d6e63', 5 ) ] ],
	N: [ 'humming with the mouth shut: nnn', humming ],
	S: [ 'a snake: sss', [ line( 'M10 70 Q24 50 38 70 Q52 90 66 70 Q78 52 84 44', '#43a047', 12 ), disc( 86, 40, 9, '#43a047' ), disc( 89, 37, 2, INK ), line( 'M94 42 L99 40 M94 42 L99 45', '#e53935', 2 ) ] ],
	Z: [ 'a bee: zzz', [ oval( 48, 56, 26, 18, '#fdd835', { stroke: INK, 'stroke-width': 3 } ), line( 'M40 40 L40 72 M54 40 L54 72', INK, 6 ), oval( 40, 32, 12, 9, '#e3f2fd', { stroke: '#90caf9', 'stroke-width': 2 } ), oval( 58, 30, 12, 9, '#e3f2fd', { stroke: '#90caf9', 'stroke-width': 2 } ), disc( 74, 54, 3, INK ), line( 'M80 80 L86 80 L80 88 L86 88', INK, 2 ) ] ],
	L: [ 'a lollipop: lll', [ line( 'M50 52 L50 96', '#8d6e63', 6 ), disc( 50, 32, 26, '#ec407a' ), line( 'M50 32 m-16 0 a16 16 0 1 1 16 16 a10 10 0 1 1 -10 -10', '#ffffff', 4 ) ] ],
	SH: [ 'a finger to the lips: shh', hush ],
	ZH: [ 'a finger to the lips, with the voice on: zh', [ ...hush, ...VOICE ] ],
	CH: [ 'a train: ch ch', [ box( 10, 40, 56, 34, '#1e88e5', { rx: 4 } ), box( 50, 22, 26, 52, '#1565c0', { rx: 3 } ), box( 20, 24, 10, 16, INK ), disc( 24, 80, 9, INK ), disc( 56, 80, 9, INK ), disc( 20, 14, 7, '#cfd8dc' ), disc( 32, 8, 6, '#cfd8dc' ) ] ],
	JH: [ 'a jelly wobbling: j j j', [ [ 'path', { d: 'M22 80 L28 30 Q50 20 72 30 L78 80 Z', fill: '#ab47bc' } ], oval( 50, 82, 36, 8, '#eeeeee', { stroke: INK, 'stroke-width': 2 } ), line( 'M12 40 Q16 50 12 60 M88 40 Q84 50 88 60', INK, 3 ) ] ],
	Y: [ 'a yo-yo: y y', [ line( 'M50 4 L50 44', INK, 2 ), disc( 50, 62, 26, '#ef6c00' ), disc( 50, 62, 8, '#ffcc80' ), line( 'M28 62 L72 62', '#ffcc80', 3 ) ] ],
	K: [ 'a camera clicking: k', [ box( 10, 30, 80, 54, '#455a64', { rx: 8 } ), box( 24, 20, 20, 12, '#455a64', { rx: 3 } ), disc( 50, 57, 19, '#90a4ae', { stroke: '#263238', 'stroke-width': 5 } ), disc( 78, 40, 4, '#fdd835' ) ] ],
	G: [ 'a glass of water, gulp: g', [ [ 'path', { d: 'M24 14 L76 14 L68 90 L32 90 Z', fill: '#e3f2fd', stroke: INK, 'stroke-width': 3 } ], [ 'path', { d: 'M28 44 L72 44 L68 88 L32 88 Z', fill: '#64b5f6' } ] ] ],
	NG: [ 'a bell: ding-ng', [ [ 'path', { d: 'M50 12 Q24 14 24 50 L18 70 L82 70 L76 50 Q76 14 50 12 Z', fill: '#fbc02d', stroke: '#b38600', 'stroke-width': 3 } ], disc( 50, 78, 7, '#b38600' ), line( 'M8 30 Q4 44 10 56 M92 30 Q96 44 90 56', '#2f7fd1', 3 ) ] ],
	W: [ 'the wind blowing: w w', [ line( 'M8 32 L62 32 Q76 32 76 20 Q76 10 66 10 Q58 10 58 18', '#64b5f6', 6 ), line( 'M8 52 L78 52 Q92 52 92 64 Q92 76 80 76 Q72 76 72 68', '#64b5f6', 6 ), line( 'M8 72 L40 72', '#64b5f6', 6 ) ] ],
	R: [ 'a racing car: rrr', [ [ 'path', { d: 'M6 66 L14 46 L40 42 L52 28 L74 28 L84 46 L96 50 L96 66 Z', fill: '#e53935' } ], box( 54, 32, 16, 12, '#bbdefb' ), disc( 26, 70, 11, INK ), disc( 78, 70, 11, INK ), disc( 26, 70, 4, '#9e9e9e' ), disc( 78, 70, 4, '#9e9e9e' ) ] ],
	HH: [ 'breathing on a cold window: hhh', [ box( 40, 8, 54, 84, '#e1f5fe', { stroke: '#78909c', 'stroke-width': 4 } ), line( 'M67 8 L67 92 M40 50 L94 50', '#78909c', 3 ), oval( 56, 58, 14, 10, '#ffffff', { opacity: 0.9 } ), line( 'M8 58 L28 58 M10 48 L26 52 M10 68 L26 64', '#9aa4ae', 3 ) ] ],
} );

/** The sounds that have a picture, by ARPAbet. */
export const SOUND_PICTURE_CODES = Object.freeze( Object.keys( SOUNDS ) );

/** The words that name the picture of sound `arpabet` ('a snake: sss'), or null. */
export function soundPictureWords( arpabet ) {

	return SOUNDS[ arpabet ]?.[ 0 ] ?? null;

}

/** The shapes of the picture of sound `arpabet`, or null when it has none. */
export function soundPictureShapes( arpabet ) {

	return SOUNDS[ arpabet ]?.[ 1 ] ?? null;

}

/** An <svg> of the picture of sound `arpabet`, named by its words; null when it has none. */
export function soundPicture( arpabet, { className = 'cp-sound-picture', doc = globalThis.document } = {} ) {

	const shapes = soundPictureShapes( arpabet );
	return shapes ? shapesSvg( shapes, { label: soundPictureWords( arpabet ), className, doc } ) : null;

}
