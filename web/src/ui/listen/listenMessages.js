// What the listening page says, in plain words and a picture, about its input: why the
// microphone cannot be used, a recording that is not audio, and a voice too quiet, too loud or
// whispered. `listenMessage( kind )` is the pure part the unit tests read; `messagePicture`
// draws its picture as inline SVG, as the child's practice draws its own (shapesSvg).

import { shapesSvg } from '../shared/ChildPracticePictures.js';

/** Each kind's words and picture. */
export const MESSAGES = Object.freeze( {
	ready: { text: 'Press Start, then say a sound.', picture: 'microphone' },
	listening: { text: 'Listening…', picture: 'microphone' },
	asking: { text: 'Glasshead needs the microphone to hear you. What you say stays on this device: allow it when the browser asks.', picture: 'microphone' },
	unsupported: { text: 'This browser cannot listen. Try an up-to-date Chrome, Edge, Firefox or Safari.', picture: 'no-microphone' },
	refused: { text: 'The microphone is not allowed. Allow it in the browser’s address bar, then press Start again.', picture: 'no-microphone' },
	'no-microphone': { text: 'No microphone was found. Plug one in, then press Start again.', picture: 'no-microphone' },
	busy: { text: 'The microphone is busy in another app. Close it there, then press Start again.', picture: 'no-microphone' },
	'not-audio': { text: 'That file is not a sound recording. Open a WAV, MP3 or other audio file.', picture: 'no-file' },
	silent: { text: 'I cannot hear you. Come closer to the microphone, or check it is not muted.', picture: 'quiet' },
	clipping: { text: 'Too loud! Move back from the microphone a little.', picture: 'loud' },
	whisper: { text: 'That sounds like a whisper. Use your voice for vowels.', picture: 'whisper' },
	noisy: { text: 'It is noisy here. Find a quieter place, or come closer to the microphone.', picture: 'loud' },
} );

/** { kind, text, picture } for `kind` (an unknown kind reads as the microphone being unusable). */
export function listenMessage( kind ) {

	const entry = MESSAGES[ kind ] ?? MESSAGES.unsupported;
	return { kind: MESSAGES[ kind ] ? kind : 'unsupported', ...entry };

}

const INK = '#1f2328';
const MIC = [
	[ 'rect', { x: 38, y: 14, width: 24, height: 42, rx: 12, fill: INK } ],
	[ 'path', { d: 'M28 46 Q28 70 50 70 Q72 70 72 46', stroke: INK, 'stroke-width': 5, fill: 'none' } ],
	[ 'path', { d: 'M50 70 L50 86 M36 86 L64 86', stroke: INK, 'stroke-width': 5, fill: 'none' } ],
];
const CROSS = [ [ 'path', { d: 'M18 18 L82 82', stroke: '#c62828', 'stroke-width': 8, 'stroke-linecap': 'round' } ] ];
const WAVES = ( n ) => Array.from( { length: n }, ( _, k ) => [ 'path', { d: `M${ 70 + 8 * k } ${ 34 - 6 * k } Q${ 80 + 10 * k } 50 ${ 70 + 8 * k } ${ 66 + 6 * k }`, stroke: '#2f7fd1', 'stroke-width': 4, fill: 'none' } ] );

/** The pictures: SVG shapes [tag, attributes] in a 100 x 100 box. */
const PICTURES = Object.freeze( {
	microphone: MIC,
	'no-microphone': [ ...MIC, ...CROSS ],
	'no-file': [ [ 'path', { d: 'M26 12 L62 12 L76 26 L76 88 L26 88 Z', fill: '#e8eaed', stroke: INK, 'stroke-width': 4 } ], ...CROSS ],
	quiet: [ ...MIC.map( ( [ tag, a ] ) => [ tag, { ...a, transform: 'translate(-14 0)' } ] ), ...WAVES( 1 ) ],
	loud: [ ...MIC.map( ( [ tag, a ] ) => [ tag, { ...a, transform: 'translate(-18 0)' } ] ), ...WAVES( 3 ).map( ( [ tag, a ] ) => [ tag, { ...a, stroke: '#c62828' } ] ) ],
	whisper: [ [ 'circle', { cx: 44, cy: 50, r: 30, fill: '#f2dcc0', stroke: INK, 'stroke-width': 3 } ], [ 'ellipse', { cx: 44, cy: 60, rx: 6, ry: 4, fill: INK } ], [ 'path', { d: 'M78 40 Q84 46 78 52 M86 34 Q96 46 86 58', stroke: '#9aa0a6', 'stroke-width': 3, fill: 'none', 'stroke-dasharray': '3 3' } ] ],
} );

/** The shapes of picture `name` (the pure part). */
export function pictureShapes( name ) {

	return PICTURES[ name ] ?? PICTURES.microphone;

}

/** An <svg> of picture `name`, named `label` for screen readers, of class `className`. */
export function messagePicture( name, label, { className = 'ls-picture', doc = globalThis.document } = {} ) {

	return shapesSvg( pictureShapes( name ), { label, className, doc } );

}
