// Whether a child's attempts are kept as sound, and keeping them. By default the sound of an
// attempt never leaves the device; only when a clinician has switched recording on for the child
// (GET /children/{id}/audio-recording says `enabled: true`) is each attempt's sound sent, after
// its practice record is saved: PUT /practice/{record}/audio with a 16 kHz 16-bit WAV (core/listen/
// wavWrite.js). Anything short of a clear "on" (no answer yet, an error, an answer without the
// field) is "off". No DOM: ChildPractice.js shows the sign and the messages.

import { recordingWav } from '../../core/listen/wavWrite.js';

/** The longest recording the server keeps, s; an attempt is far shorter (PracticeListener.MAX_ATTEMPT_S). */
export const MAX_RECORDING_S = 30;
/** What the child's sign says, to a screen reader and under the red dot. */
export const KEEPING_LABEL = 'Your teacher keeps recordings';

/** The path of a child's recording switch. */
export const recordingSwitchPath = ( childId ) => `children/${ childId }/audio-recording`;
/** The path of a practice record's sound. */
export const practiceAudioPath = ( recordId ) => `practice/${ recordId }/audio`;

/** The plain words for a sound that could not be kept (the try itself is saved). */
export function uploadFailureMessage( error ) {

	if ( error?.status === 409 ) return 'Recordings were switched off, so this try’s sound was not kept. Your try is saved.';
	return 'This try’s sound could not be kept. Your try is saved.';

}

export class PracticeAudio {

	/** @param {{ api: object }} options the HTTP client (the child's token goes with it) */
	constructor( { api } ) {

		this.api = api;
		this.enabled = false;
		/** Records whose sound the server took, and those it did not. */
		this.kept = [];
		this.failed = [];
		this.pending = 0;
		this.reads = 0;

	}

	/**
	 * Read the child's switch; resolves to whether attempts are kept. A failure leaves it off:
	 * sound is sent only on a clear "on".
	 */
	async read( childId ) {

		const read = ++ this.reads;
		let enabled = false;
		try {

			enabled = ( await this.api.get( recordingSwitchPath( childId ) ) )?.enabled === true;

		} catch ( error ) {

			console.warn( `Glasshead: recordings stay off, the switch could not be read: ${ error.message }` );

		}

		// Only the newest read counts (a lesson started while the sign-in's read was on its way).
		if ( read === this.reads ) this.enabled = enabled;
		return this.enabled;

	}

	/** Forget the child (signed out): nothing is kept until the next read. */
	reset() {

		this.reads ++;
		this.enabled = false;

	}

	/**
	 * Keep the sound of the attempt whose practice record is `recordId`: `recording` is
	 * { samples: Float32Array, sampleRate } as the microphone gave them. Does nothing, and sends
	 * nothing, unless recording is on and there is sound. Resolves to the server's answer, or null
	 * when nothing was sent; rejects with the ApiError of a refusal (a 409 also turns it off here).
	 */
	async keep( recordId, recording ) {

		if ( ! this.enabled || ! recording?.samples?.length || ! ( recording.sampleRate > 0 ) ) return null;
		const bytes = recordingWav( recording.samples, recording.sampleRate, { maxSeconds: MAX_RECORDING_S } );
		this.pending ++;
		try {

			const answer = await this.api.putBytes( practiceAudioPath( recordId ), bytes, 'audio/wav' );
			this.kept.push( recordId );
			return answer;

		} catch ( error ) {

			this.failed.push( recordId );
			if ( error?.status === 409 ) this.enabled = false; // switched off since it was read
			throw error;

		} finally {

			this.pending --;

		}

	}

	/** What window.glasshead.practice.audio reports. */
	report() {

		return { enabled: this.enabled, kept: [ ...this.kept ], failed: [ ...this.failed ], pending: this.pending };

	}

}
