// The speech player's clock: one time, in seconds into the utterance, that the head, the
// cutaway, the diagram, the cues, the live palatogram, the phoneme strip and the dominance plot
// all read. While the audio plays, the audio element's currentTime is the clock, so what is seen
// is what is heard; without audio (or while the audio cannot play) the clock runs from the
// page's time source at the chosen speed. Slow motion sets the audio's playbackRate, with
// preservesPitch, so the sound stays in step at 0.1x to 1x.
//
// Pure: the audio element and the time source are handed in (tests pass fakes); the view calls
// update( nowMs ) once per frame and draws what it returns.
//
//   const clock = new SpeechClock( { audio } );
//   clock.load( utterance.duration_s, utterance.rate_hz );
//   clock.play( performance.now() );
//   const t = clock.update( performance.now() );   // every frame

/** Slowest and fastest playback (times real time). */
export const SPEED_RANGE = Object.freeze( [ 0.1, 1 ] );

export class SpeechClock {

	/**
	 * @param {{ audio?: object|null, now?: () => number }} options `audio` an HTMLAudioElement (or
	 *   an object with currentTime, paused, ended, playbackRate, preservesPitch, play() and
	 *   pause()); `now` milliseconds (performance.now in the page)
	 */
	constructor( { audio = null, now = () => globalThis.performance.now() } = {} ) {

		this.audio = audio;
		this.now = now;
		this.duration = 0;
		this.rateHz = 100;
		this.time = 0;
		this.speed = 1;
		this.loop = false;
		this.playing = false;
		this.hasAudio = false;
		/** Why the audio did not play (the browser refused it), or null. */
		this.audioError = null;
		/** The time and the clock reading when the time last came from the audio or a seek. */
		this.startTime = 0;
		this.startMs = 0;
		/** Which clock the last update read: 'audio' or 'page'. */
		this.source = 'page';

	}

	/** A new utterance of `duration` seconds, tracks at `rateHz`; with audio when `hasAudio`. */
	load( duration, rateHz, hasAudio = false ) {

		this.pause();
		this.duration = Math.max( 0, duration );
		this.rateHz = rateHz;
		this.hasAudio = hasAudio && this.audio !== null;
		this.audioError = null;
		this.seek( 0 );

	}

	/** Play from the current time (from the start when at the end). */
	play() {

		if ( this.duration <= 0 ) return false;
		if ( this.time >= this.duration ) this.time = 0;
		this.playing = true;
		this.rebase( this.time );
		if ( this.hasAudio ) {

			const audio = this.audio;
			audio.playbackRate = this.speed;
			audio.preservesPitch = true;
			audio.currentTime = this.time;
			const started = audio.play();
			started?.catch?.( ( error ) => {

				this.audioError = error?.message ?? String( error ); // the page's clock carries on

			} );

		}

		return true;

	}

	/** Stop where the clock is now. */
	pause() {

		if ( this.playing ) this.time = Math.min( this.read(), this.duration );
		this.playing = false;
		if ( this.hasAudio && ! this.audio.paused ) this.audio.pause();

	}

	/** Go to time `t` (clamped into the utterance), playing on from there if playing. */
	seek( t ) {

		this.time = Math.min( Math.max( Number.isFinite( t ) ? t : 0, 0 ), this.duration );
		this.rebase( this.time );
		if ( this.hasAudio ) this.audio.currentTime = this.time;
		return this.time;

	}

	/** Pause and move by `frames` frames of the tracks (negative: back). */
	step( frames ) {

		this.pause();
		const frame = Math.round( this.time * this.rateHz ) + frames;
		return this.seek( frame / this.rateHz );

	}

	/** The playback speed, SPEED_RANGE; playing goes on at the new speed from where it is. */
	setSpeed( speed ) {

		const [ low, high ] = SPEED_RANGE;
		const clamped = Math.min( Math.max( speed, low ), high );
		if ( this.playing ) this.rebase( this.read() );
		this.speed = clamped;
		if ( this.hasAudio ) {

			this.audio.preservesPitch = true;
			this.audio.playbackRate = clamped;

		}

		return clamped;

	}

	setLoop( on ) {

		this.loop = Boolean( on );

	}

	/** The current frame of the tracks. */
	get frame() {

		return Math.round( this.time * this.rateHz );

	}

	/**
	 * The time now: the audio's currentTime while it plays, else the page's clock at the speed.
	 * At the end, playing stops or (looping) starts again from 0. Returns the time.
	 */
	update() {

		if ( ! this.playing ) return this.time;
		let t = this.read();
		if ( t >= this.duration ) {

			if ( this.loop ) {

				t = 0;
				this.seek( 0 );
				if ( this.hasAudio && this.audio.paused ) this.audio.play()?.catch?.( () => {} );

			} else {

				this.pause();
				this.time = this.duration;
				return this.time;

			}

		}

		this.time = t;
		return t;

	}

	/** The clock's reading while playing (see update), without side effects on playing. */
	read() {

		const audio = this.audio;
		if ( this.hasAudio && this.audioError === null && ! audio.paused && ! audio.ended ) {

			this.source = 'audio';
			this.rebase( audio.currentTime ); // the page's clock carries on from here if the audio stops
			return audio.currentTime;

		}

		this.source = 'page';
		return this.startTime + ( this.now() - this.startMs ) / 1000 * this.speed;

	}

	rebase( t ) {

		this.startTime = t;
		this.startMs = this.now();

	}

}

/**
 * Index of the phone at time `t` in `phones` (start_s ascending, each [start_s, end_s)): binary
 * search; the last phone at or past the end, -1 for none.
 */
export function phoneIndexAt( phones, t ) {

	const n = phones.length;
	if ( n === 0 ) return - 1;
	if ( t >= phones[ n - 1 ].start_s ) return n - 1;
	let low = 0;
	let high = n - 1;
	while ( low < high ) {

		const mid = ( low + high + 1 ) >> 1;
		if ( phones[ mid ].start_s <= t ) low = mid;
		else high = mid - 1;

	}

	return low;

}
