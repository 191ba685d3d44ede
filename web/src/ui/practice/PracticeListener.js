// One spoken attempt in the child's practice: the microphone is opened when the child presses
// "Say it" (never before), the voice is measured as it comes (core/listen), and the attempt
// ends by itself once the child has spoken and fallen quiet, or after MAX_ATTEMPT_S, or when
// the button is pressed again. The summary is what the page measures; the attempt's samples are
// handed on too (`recording`), for PracticeAudio.js to keep only when recording is switched on.

import { AttemptRecorder } from '../listen/AttemptRecorder.js';
import { startMicrophone } from '../listen/audioInput.js';
import { summariseAttempt } from '../listen/listenScales.js';

/** The longest attempt, s. */
export const MAX_ATTEMPT_S = 5;
/** Quiet after sound that ends an attempt, s. */
export const QUIET_END_S = 0.7;
/** Loudness over the attempt's quietest that counts as sound, dB. */
const SOUND_ABOVE_FLOOR_DB = 15;

/**
 * Whether an attempt's hops (so far) are done: sound came, then QUIET_END_S of quiet; or the
 * attempt has run MAX_ATTEMPT_S. The pure part the unit tests read.
 */
export function attemptDone( hops ) {

	if ( ! hops.length ) return false;
	const last = hops.at( - 1 ).t;
	if ( last - hops[ 0 ].t >= MAX_ATTEMPT_S ) return true;
	const levels = hops.map( ( hop ) => hop.intensity_db ?? - Infinity );
	const floor = Math.min( ...levels.filter( Number.isFinite ) );
	const loud = hops.filter( ( hop, k ) => levels[ k ] >= floor + SOUND_ABOVE_FLOOR_DB );
	return loud.length >= 5 && last - loud.at( - 1 ).t >= QUIET_END_S;

}

export class PracticeListener {

	/**
	 * @param {{ win?: Window, group?: string, onOpen?: () => void }} options
	 *   `onOpen()` once the microphone is open (the browser's question answered)
	 */
	constructor( { win = globalThis.window, group = 'child', onOpen = () => {} } = {} ) {

		this.window = win;
		this.group = group;
		this.onOpen = onOpen;
		this.microphone = null;
		this.finished = null;
		/** The last attempt's samples as the microphone gave them: { samples, sampleRate }, or null. */
		this.recording = null;

	}

	get listening() {

		return this.microphone !== null;

	}

	/**
	 * Listen to one attempt; resolves with its summary ({ vowel, fricative }, summariseAttempt)
	 * when it ends. Rejects with a ListenError when the microphone cannot be had.
	 */
	async listen() {

		let resolveDone;
		this.finished = new Promise( ( resolve ) => ( resolveDone = resolve ) );
		this.recording = null;
		let recorder = null;
		this.microphone = await startMicrophone( { win: this.window, onBlock: ( block ) => {

			if ( ! recorder ) return;
			recorder.push( block );
			if ( attemptDone( recorder.hops ) ) this.stop();

		} } );
		recorder = new AttemptRecorder( { sampleRate: this.microphone.sampleRate, group: this.group } );
		this.onOpen();
		this.end = () => {

			// A fresh recorder per attempt: its samples are this attempt's, from the microphone's
			// opening to its end (far under the recorder's KEPT_SECONDS).
			this.recording = { samples: recorder.samples(), sampleRate: recorder.sampleRate };
			resolveDone( summariseAttempt( recorder.hops ) );

		};
		return this.finished;

	}

	/** End the attempt now (the button pressed again, the page left). */
	stop() {

		if ( ! this.microphone ) return;
		this.microphone.stop();
		this.microphone = null;
		this.end?.();

	}

}
